// PCD reading: files written here in each encoding come back intact; bad files give one clear
// error naming the file.

#include "relplane/pcd/pcd_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "relplane/pcd/lzf.hpp"

namespace relplane::pcd {
namespace {

// A small LZF compressor (greedy, hash of the next 3 bytes) so the test can write
// binary_compressed files with real back references, independent of the decompressor.
std::vector<uint8_t> LzfCompress(const std::vector<uint8_t>& in) {
  std::vector<uint8_t> out;
  std::vector<long> last(1 << 14, -1);
  std::vector<uint8_t> literal;
  auto flush = [&]() {
    for (size_t i = 0; i < literal.size(); i += 32) {
      const size_t n = std::min<size_t>(32, literal.size() - i);
      out.push_back(static_cast<uint8_t>(n - 1));
      out.insert(out.end(), literal.begin() + i, literal.begin() + i + n);
    }
    literal.clear();
  };
  size_t i = 0;
  while (i < in.size()) {
    if (i + 3 <= in.size()) {
      const unsigned h = ((in[i] << 16) | (in[i + 1] << 8) | in[i + 2]) * 2654435761u >> 18;
      const long ref = last[h];
      last[h] = static_cast<long>(i);
      if (ref >= 0 && i - ref <= 8192 && std::memcmp(&in[ref], &in[i], 3) == 0) {
        size_t len = 3;
        while (i + len < in.size() && len < 264 && in[ref + len] == in[i + len]) ++len;
        flush();
        const size_t off = i - ref - 1;
        const size_t l = len - 2;
        if (l < 7) {
          out.push_back(static_cast<uint8_t>((l << 5) | (off >> 8)));
        } else {
          out.push_back(static_cast<uint8_t>((7 << 5) | (off >> 8)));
          out.push_back(static_cast<uint8_t>(l - 7));
        }
        out.push_back(static_cast<uint8_t>(off & 0xff));
        i += len;
        continue;
      }
    }
    literal.push_back(in[i++]);
  }
  flush();
  return out;
}

struct TestCloud {
  int width = 4, height = 3;
  std::vector<float> x, y, z;
  std::vector<uint32_t> rgba;
};

TestCloud MakeCloud() {
  TestCloud c;
  for (int i = 0; i < c.width * c.height; ++i) {
    c.x.push_back(i < 6 ? 0.5f * i : 1.25f);  // repeats so LZF finds back references
    c.y.push_back(-0.25f * i);
    c.z.push_back(i == 7 ? std::numeric_limits<float>::quiet_NaN() : 2.0f + i);
    c.rgba.push_back(0xff0000u + i);
  }
  return c;
}

// Fields: rgba first, then x y z, so the reader must find them by name and offset.
std::string Header(const TestCloud& c, const std::string& encoding) {
  std::ostringstream h;
  h << "# .PCD v0.7 - written by the test\nVERSION 0.7\nFIELDS rgba x y z\nSIZE 4 4 4 4\n"
    << "TYPE U F F F\nCOUNT 1 1 1 1\nWIDTH " << c.width << "\nHEIGHT " << c.height
    << "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << c.width * c.height << "\nDATA " << encoding << "\n";
  return h.str();
}

template <class T>
void Append(std::string* s, T v) {
  s->append(reinterpret_cast<const char*>(&v), sizeof(T));
}

std::string Write(const TestCloud& c, const std::string& encoding) {
  std::string out = Header(c, encoding);
  const size_t n = c.x.size();
  if (encoding == "ascii") {
    std::ostringstream body;
    for (size_t i = 0; i < n; ++i) {
      body << c.rgba[i] << ' ' << c.x[i] << ' ' << c.y[i] << ' ';
      if (std::isnan(c.z[i]))
        body << "nan\n";
      else
        body << c.z[i] << '\n';
    }
    return out + body.str();
  }
  std::string raw;
  if (encoding == "binary") {
    for (size_t i = 0; i < n; ++i) {
      Append(&raw, c.rgba[i]);
      Append(&raw, c.x[i]);
      Append(&raw, c.y[i]);
      Append(&raw, c.z[i]);
    }
    return out + raw;
  }
  for (uint32_t v : c.rgba) Append(&raw, v);
  for (float v : c.x) Append(&raw, v);
  for (float v : c.y) Append(&raw, v);
  for (float v : c.z) Append(&raw, v);
  const auto packed = LzfCompress(std::vector<uint8_t>(raw.begin(), raw.end()));
  Append(&out, static_cast<uint32_t>(packed.size()));
  Append(&out, static_cast<uint32_t>(raw.size()));
  out.append(packed.begin(), packed.end());
  return out;
}

void ExpectSame(const TestCloud& want, const PcdCloud& got) {
  ASSERT_EQ(got.width, want.width);
  ASSERT_EQ(got.height, want.height);
  ASSERT_EQ(got.size(), want.x.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_FLOAT_EQ(got.x[i], want.x[i]);
    EXPECT_FLOAT_EQ(got.y[i], want.y[i]);
    if (std::isnan(want.z[i])) {
      EXPECT_TRUE(std::isnan(got.z[i]));
    } else {
      EXPECT_FLOAT_EQ(got.z[i], want.z[i]);
    }
  }
}

TEST(PcdReader, RoundTripsEveryEncodingThroughAFile) {
  const TestCloud cloud = MakeCloud();
  for (const std::string encoding : {"ascii", "binary", "binary_compressed"}) {
    SCOPED_TRACE(encoding);
    const std::string path = ::testing::TempDir() + "/cloud_" + encoding + ".pcd";
    std::ofstream(path, std::ios::binary) << Write(cloud, encoding);
    const PcdCloud got = ReadPcd(path);
    EXPECT_EQ(got.encoding, encoding);
    ExpectSame(cloud, got);
  }
}

TEST(Lzf, ExpandsLiteralsAndOverlappingBackReferences) {
  // "abc", then a reference 3 back of length 5 that overlaps what it writes.
  const std::vector<uint8_t> packed = {0x02, 'a', 'b', 'c', 0x60, 0x02};
  const auto out = LzfDecompress(packed.data(), packed.size(), 8);
  EXPECT_EQ(std::string(out.begin(), out.end()), "abcabcab");
}

TEST(Lzf, CompressorInTheTestRoundTrips) {
  std::vector<uint8_t> data;
  for (int i = 0; i < 5000; ++i) data.push_back(static_cast<uint8_t>((i * 7) % 13 + (i / 700)));
  const auto packed = LzfCompress(data);
  EXPECT_LT(packed.size(), data.size() / 2);
  EXPECT_EQ(LzfDecompress(packed.data(), packed.size(), data.size()), data);
}

TEST(Lzf, CorruptStreamsAreErrors) {
  const std::vector<uint8_t> before_start = {0x00, 'a', 0x20, 0x05};
  EXPECT_THROW(LzfDecompress(before_start.data(), before_start.size(), 4), std::runtime_error);
  const std::vector<uint8_t> short_literal = {0x05, 'a', 'b'};
  EXPECT_THROW(LzfDecompress(short_literal.data(), short_literal.size(), 6), std::runtime_error);
  const std::vector<uint8_t> too_long = {0x02, 'a', 'b', 'c'};
  EXPECT_THROW(LzfDecompress(too_long.data(), too_long.size(), 2), std::runtime_error);
  EXPECT_THROW(LzfDecompress(too_long.data(), too_long.size(), 9), std::runtime_error);
}

std::string ErrorOf(const std::string& bytes) {
  try {
    ParsePcd(bytes, "bad.pcd");
  } catch (const PcdError& e) {
    return e.what();
  }
  return "";
}

TEST(PcdReader, MalformedFilesGiveOneLineErrorsNamingTheFile) {
  const TestCloud cloud = MakeCloud();
  const std::string good = Write(cloud, "binary");
  const std::string header = Header(cloud, "binary");
  struct Case {
    std::string bytes;
    std::string expect;
  };
  std::string no_z = header;
  no_z.replace(no_z.find("FIELDS rgba x y z"), 17, "FIELDS rgba x y w");
  std::string wrong_points = header;
  wrong_points.replace(wrong_points.find("POINTS 12"), 9, "POINTS 13");
  std::string unknown = header;
  unknown.replace(unknown.find("DATA binary"), 11, "DATA zipped");
  std::string bad_size = header;
  bad_size.replace(bad_size.find("SIZE 4 4 4 4"), 12, "SIZE 4 4 4");
  const std::string compressed = Write(cloud, "binary_compressed");
  const std::string ascii = Write(cloud, "ascii");
  const size_t two_lines = ascii.find('\n', ascii.find('\n', header.size()) + 1) + 1;
  const std::vector<Case> cases = {
      {"", "header ends before its DATA line"},
      {header.substr(0, header.find("DATA")), "header ends before its DATA line"},
      {no_z, "no field z"},
      {wrong_points, "POINTS differs"},
      {unknown, "unknown DATA encoding"},
      {bad_size, "SIZE and TYPE"},
      {"VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH abc\n", "not a non-negative"},
      {"VERSION 0.7\nBOGUS 1\n", "unexpected header line"},
      {good.substr(0, good.size() - 5), "binary data has"},
      {compressed.substr(0, compressed.size() - 3), "truncated"},
      {ascii.substr(0, two_lines), "ascii data ends after 2 of 12 points"},
      {ascii.substr(0, two_lines + 5), "ascii point 2 has 1 values, expected 4"},
  };
  for (const Case& c : cases) {
    const std::string error = ErrorOf(c.bytes);
    EXPECT_NE(error.find("bad.pcd: "), std::string::npos) << error;
    EXPECT_NE(error.find(c.expect), std::string::npos) << error << " | wanted: " << c.expect;
    EXPECT_EQ(error.find('\n'), std::string::npos);
  }
  EXPECT_THROW(ReadPcd("/nonexistent/cloud.pcd"), PcdError);
}

TEST(PcdReader, ReadsTheRealKinectFrames) {
  const PcdCloud c = ReadPcd(RELPLANE_SHARED_DIR "/data/kinect/frame_20121214T142255.814212.pcd");
  EXPECT_EQ(c.encoding, "binary_compressed");
  EXPECT_EQ(c.width, 640);
  EXPECT_EQ(c.height, 480);
  size_t finite = 0;
  float max_depth = 0;
  for (size_t i = 0; i < c.size(); ++i) {
    if (std::isfinite(c.x[i]) && std::isfinite(c.y[i]) && std::isfinite(c.z[i])) {
      ++finite;
      max_depth = std::max(max_depth, c.z[i]);
      EXPECT_GT(c.z[i], 0.3f);  // optical frame: z forward, in front of the camera
    }
  }
  EXPECT_GT(finite, c.size() / 2);  // most pixels are valid ...
  EXPECT_LT(finite, c.size());      // ... and some are NaN
  EXPECT_LT(max_depth, 10.0f);
}

TEST(PcdReader, OpticalToSensorFrame) {
  PcdCloud c;
  c.x = {1.0f};  // right
  c.y = {2.0f};  // down
  c.z = {3.0f};  // forward
  OpticalToSensor(&c);
  EXPECT_EQ(c.x[0], 3.0f);   // forward
  EXPECT_EQ(c.y[0], -1.0f);  // left
  EXPECT_EQ(c.z[0], -2.0f);  // up
}

}  // namespace
}  // namespace relplane::pcd
