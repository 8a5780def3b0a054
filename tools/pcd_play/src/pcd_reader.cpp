#include "relplane/pcd/pcd_reader.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "relplane/pcd/lzf.hpp"

namespace relplane::pcd {
namespace {

struct Field {
  std::string name;
  int size = 4;
  char type = 'F';
  int count = 1;
  size_t offset = 0;  // byte offset of the field inside one point (binary layout)
};

struct Header {
  std::vector<Field> fields;
  long width = -1;
  long height = -1;
  long points = -1;
  std::string data;
  size_t data_start = 0;  // offset of the first byte after the DATA line
  size_t point_bytes = 0;
};

[[noreturn]] void Fail(const std::string& name, const std::string& why) {
  throw PcdError(name + ": " + why);
}

std::vector<std::string> Words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

long ToLong(const std::string& name, const std::string& key, const std::string& word) {
  try {
    size_t used = 0;
    const long v = std::stol(word, &used);
    if (used != word.size() || v < 0) throw std::invalid_argument(word);
    return v;
  } catch (const std::exception&) {
    Fail(name, "header " + key + ": '" + word + "' is not a non-negative integer");
  }
}

Header ParseHeader(const std::string& bytes, const std::string& name) {
  Header h;
  size_t pos = 0;
  std::vector<std::string> sizes, types, counts;
  while (h.data.empty()) {
    if (pos >= bytes.size()) Fail(name, "header ends before its DATA line");
    size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    const std::string line = bytes.substr(pos, end - pos);
    pos = end + 1;
    const auto words = Words(line);
    if (words.empty() || words[0][0] == '#') continue;
    const std::string& key = words[0];
    const std::vector<std::string> args(words.begin() + 1, words.end());
    if (key == "VERSION") {
      continue;
    } else if (key == "FIELDS") {
      for (const auto& a : args) h.fields.push_back(Field{a});
    } else if (key == "SIZE") {
      sizes = args;
    } else if (key == "TYPE") {
      types = args;
    } else if (key == "COUNT") {
      counts = args;
    } else if (key == "WIDTH" && args.size() == 1) {
      h.width = ToLong(name, key, args[0]);
    } else if (key == "HEIGHT" && args.size() == 1) {
      h.height = ToLong(name, key, args[0]);
    } else if (key == "POINTS" && args.size() == 1) {
      h.points = ToLong(name, key, args[0]);
    } else if (key == "VIEWPOINT") {
      continue;
    } else if (key == "DATA" && args.size() == 1) {
      h.data = args[0];
    } else {
      Fail(name, "unexpected header line '" + line + "'");
    }
  }
  h.data_start = pos;
  if (h.fields.empty()) Fail(name, "header has no FIELDS");
  if (sizes.size() != h.fields.size() || types.size() != h.fields.size()) {
    Fail(name, "SIZE and TYPE must name one entry per field");
  }
  if (!counts.empty() && counts.size() != h.fields.size()) {
    Fail(name, "COUNT must name one entry per field");
  }
  if (h.width < 0 || h.height < 0) Fail(name, "header lacks WIDTH or HEIGHT");
  if (h.points < 0) h.points = h.width * h.height;
  if (h.points != h.width * h.height) Fail(name, "POINTS differs from WIDTH x HEIGHT");
  if (h.points > (1L << 28)) Fail(name, "absurd point count " + std::to_string(h.points));
  for (size_t i = 0; i < h.fields.size(); ++i) {
    Field& f = h.fields[i];
    f.size = static_cast<int>(ToLong(name, "SIZE", sizes[i]));
    f.count = counts.empty() ? 1 : static_cast<int>(ToLong(name, "COUNT", counts[i]));
    if (types[i].size() != 1 || std::string("FIU").find(types[i][0]) == std::string::npos) {
      Fail(name, "TYPE '" + types[i] + "' is not F, I or U");
    }
    f.type = types[i][0];
    if (f.size != 1 && f.size != 2 && f.size != 4 && f.size != 8) {
      Fail(name, "SIZE " + sizes[i] + " is not 1, 2, 4 or 8");
    }
    if (f.count < 1 || f.count > 1 << 16) Fail(name, "COUNT " + std::to_string(f.count));
    f.offset = h.point_bytes;
    h.point_bytes += static_cast<size_t>(f.size) * f.count;
  }
  for (const char* axis : {"x", "y", "z"}) {
    bool found = false;
    for (const Field& f : h.fields) {
      if (f.name != axis) continue;
      found = true;
      if (f.type != 'F' || (f.size != 4 && f.size != 8)) {
        Fail(name, std::string("field ") + axis + " must be a float (TYPE F, SIZE 4 or 8)");
      }
    }
    if (!found) Fail(name, std::string("no field ") + axis);
  }
  if (h.data != "ascii" && h.data != "binary" && h.data != "binary_compressed") {
    Fail(name, "unknown DATA encoding '" + h.data + "'");
  }
  return h;
}

const Field& FieldNamed(const Header& h, const char* axis) {
  for (const Field& f : h.fields) {
    if (f.name == axis) return f;
  }
  return h.fields.front();  // unreachable: ParseHeader checked x, y and z exist
}

float ReadFloat(const uint8_t* p, int size) {
  if (size == 8) {
    double v;
    std::memcpy(&v, p, 8);
    return static_cast<float>(v);
  }
  float v;
  std::memcpy(&v, p, 4);
  return v;
}

void ReadAscii(const std::string& bytes, const Header& h, const std::string& name, PcdCloud* c) {
  std::istringstream in(bytes.substr(h.data_start));
  size_t values_per_point = 0;
  for (const Field& f : h.fields) values_per_point += f.count;
  std::vector<size_t> index(3);
  const char* axes[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    size_t k = 0;
    for (const Field& f : h.fields) {
      if (f.name == axes[a]) break;
      k += f.count;
    }
    index[a] = k;
  }
  std::string line;
  for (long i = 0; i < h.points; ++i) {
    do {
      if (!std::getline(in, line)) {
        Fail(name, "ascii data ends after " + std::to_string(i) + " of " +
                       std::to_string(h.points) + " points");
      }
    } while (Words(line).empty());
    const auto words = Words(line);
    if (words.size() != values_per_point) {
      Fail(name, "ascii point " + std::to_string(i) + " has " + std::to_string(words.size()) +
                     " values, expected " + std::to_string(values_per_point));
    }
    float v[3];
    for (int a = 0; a < 3; ++a) {
      const std::string& w = words[index[a]];
      if (w == "nan" || w == "NaN" || w == "-nan") {
        v[a] = std::numeric_limits<float>::quiet_NaN();
        continue;
      }
      try {
        v[a] = std::stof(w);
      } catch (const std::exception&) {
        Fail(name, "ascii point " + std::to_string(i) + ": '" + w + "' is not a number");
      }
    }
    c->x[i] = v[0];
    c->y[i] = v[1];
    c->z[i] = v[2];
  }
}

// binary: one record per point, fields packed in header order (array of structs).
void ReadBinary(const uint8_t* data, size_t size, const Header& h, const std::string& name,
                PcdCloud* c) {
  const size_t need = h.point_bytes * static_cast<size_t>(h.points);
  if (size < need) {
    Fail(name,
         "binary data has " + std::to_string(size) + " bytes, expected " + std::to_string(need));
  }
  const Field* f[3] = {&FieldNamed(h, "x"), &FieldNamed(h, "y"), &FieldNamed(h, "z")};
  std::vector<float>* out[3] = {&c->x, &c->y, &c->z};
  for (long i = 0; i < h.points; ++i) {
    const uint8_t* record = data + h.point_bytes * i;
    for (int a = 0; a < 3; ++a) (*out[a])[i] = ReadFloat(record + f[a]->offset, f[a]->size);
  }
}

// binary_compressed: two little-endian uint32 sizes, then LZF of the fields laid out one after
// another (struct of arrays: all x, then all y, ...).
void ReadCompressed(const uint8_t* data, size_t size, const Header& h, const std::string& name,
                    PcdCloud* c) {
  if (size < 8) Fail(name, "binary_compressed data lacks its size words");
  uint32_t packed = 0, unpacked = 0;
  std::memcpy(&packed, data, 4);
  std::memcpy(&unpacked, data + 4, 4);
  const size_t need = h.point_bytes * static_cast<size_t>(h.points);
  if (unpacked != need) {
    Fail(name, "binary_compressed expands to " + std::to_string(unpacked) + " bytes, expected " +
                   std::to_string(need));
  }
  if (packed > size - 8) {
    Fail(name, "binary_compressed data truncated: " + std::to_string(size - 8) + " of " +
                   std::to_string(packed) + " bytes");
  }
  std::vector<uint8_t> raw;
  try {
    raw = LzfDecompress(data + 8, packed, unpacked);
  } catch (const std::runtime_error& e) {
    Fail(name, e.what());
  }
  std::vector<float>* out[3] = {&c->x, &c->y, &c->z};
  const char* axes[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    size_t start = 0;
    for (const Field& f : h.fields) {
      if (f.name == axes[a]) break;
      start += static_cast<size_t>(f.size) * f.count * h.points;
    }
    const Field& f = FieldNamed(h, axes[a]);
    const size_t stride = static_cast<size_t>(f.size) * f.count;
    for (long i = 0; i < h.points; ++i) (*out[a])[i] = ReadFloat(&raw[start + stride * i], f.size);
  }
}

}  // namespace

PcdCloud ParsePcd(const std::string& bytes, const std::string& name) {
  const Header h = ParseHeader(bytes, name);
  PcdCloud cloud;
  cloud.width = static_cast<int>(h.width);
  cloud.height = static_cast<int>(h.height);
  cloud.encoding = h.data;
  cloud.x.resize(h.points);
  cloud.y.resize(h.points);
  cloud.z.resize(h.points);
  const auto* data = reinterpret_cast<const uint8_t*>(bytes.data()) + h.data_start;
  const size_t size = bytes.size() - std::min(bytes.size(), h.data_start);
  if (h.data == "ascii") {
    ReadAscii(bytes, h, name, &cloud);
  } else if (h.data == "binary") {
    ReadBinary(data, size, h, name, &cloud);
  } else {
    ReadCompressed(data, size, h, name, &cloud);
  }
  return cloud;
}

PcdCloud ReadPcd(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw PcdError(path + ": cannot open");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return ParsePcd(buffer.str(), path);
}

void OpticalToSensor(PcdCloud* cloud) {
  for (size_t i = 0; i < cloud->size(); ++i) {
    const float right = cloud->x[i], down = cloud->y[i], forward = cloud->z[i];
    cloud->x[i] = forward;
    cloud->y[i] = -right;
    cloud->z[i] = -down;
  }
}

}  // namespace relplane::pcd
