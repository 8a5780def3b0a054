#include "journal.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

namespace relplane::mapper {
namespace {

constexpr size_t kHeaderBytes = 8;           // length + CRC
constexpr uint32_t kMaxPayload = 64u << 20;  // far above any real plane set
constexpr uint32_t kMaxPlanes = 1u << 16;
constexpr uint32_t kMaxVertices = 1u << 16;
constexpr uint32_t kOdometryTag = 0x4F444F31u;  // "ODO1": an odometry block follows the planes

const std::array<uint32_t, 256>& CrcTable() {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  return table;
}

// Little-endian writer and bounds-checked reader of the payload.
class Out {
 public:
  void U32(uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  void U64(uint64_t v) {
    for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  void F64(double v) {
    uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    U64(bits);
  }
  void Vec(const Eigen::Vector3d& v) {
    for (int i = 0; i < 3; ++i) F64(v[i]);
  }
  std::vector<uint8_t> bytes;
};

class In {
 public:
  In(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  bool U32(uint32_t* v) {
    if (size_ - pos_ < 4) return false;
    *v = 0;
    for (int i = 0; i < 4; ++i) *v |= static_cast<uint32_t>(data_[pos_ + i]) << (8 * i);
    pos_ += 4;
    return true;
  }
  bool U64(uint64_t* v) {
    if (size_ - pos_ < 8) return false;
    *v = 0;
    for (int i = 0; i < 8; ++i) *v |= static_cast<uint64_t>(data_[pos_ + i]) << (8 * i);
    pos_ += 8;
    return true;
  }
  bool F64(double* v) {
    uint64_t bits;
    if (!U64(&bits)) return false;
    std::memcpy(v, &bits, sizeof bits);
    return true;
  }
  bool Vec(Eigen::Vector3d* v) { return F64(&(*v)[0]) && F64(&(*v)[1]) && F64(&(*v)[2]); }
  size_t Left() const { return size_ - pos_; }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

bool ParsePayload(const uint8_t* data, size_t size, JournalRecord* record) {
  In in(data, size);
  uint64_t iteration = 0;
  uint32_t num_planes = 0;
  if (!in.U64(&iteration) || !in.U32(&num_planes) || num_planes > kMaxPlanes) return false;
  record->iteration = static_cast<int64_t>(iteration);
  record->planes.clear();
  for (uint32_t p = 0; p < num_planes; ++p) {
    PlaneInput plane;
    uint32_t num_vertices = 0, support = 0;
    if (!in.Vec(&plane.normal) || !in.F64(&plane.d) || !in.Vec(&plane.centroid) ||
        !in.U32(&num_vertices) || num_vertices > kMaxVertices || in.Left() / 24 < num_vertices) {
      return false;
    }
    plane.vertices.resize(num_vertices);
    for (Eigen::Vector3d& v : plane.vertices) {
      if (!in.Vec(&v)) return false;
    }
    if (!in.U32(&support) || !in.F64(&plane.rms)) return false;
    plane.support = static_cast<int>(support);
    record->planes.push_back(std::move(plane));
  }
  record->odometry.reset();
  if (in.Left() == 0) return true;
  uint32_t tag = 0, lost = 0;
  if (!in.U32(&tag) || tag != kOdometryTag) return false;
  OdometryIncrement odometry;
  uint64_t from = 0, to = 0;
  if (!in.F64(&odometry.motion.x) || !in.F64(&odometry.motion.y) ||
      !in.F64(&odometry.motion.yaw)) {
    return false;
  }
  for (int i = 0; i < 9; ++i) {
    if (!in.F64(&odometry.covariance(i / 3, i % 3))) return false;
  }
  if (!in.U64(&from) || !in.U64(&to) || !in.U32(&lost) || lost > 1) return false;
  odometry.from_utime = static_cast<int64_t>(from);
  odometry.to_utime = static_cast<int64_t>(to);
  odometry.readings_lost = lost == 1;
  record->odometry = odometry;
  return in.Left() == 0;
}

}  // namespace

uint32_t Crc32(const uint8_t* data, size_t size) {
  const std::array<uint32_t, 256>& table = CrcTable();
  uint32_t c = 0xFFFFFFFFu;
  for (size_t i = 0; i < size; ++i) c = table[(c ^ data[i]) & 0xFFu] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

std::vector<uint8_t> EncodeRecord(const JournalRecord& record) {
  Out payload;
  payload.U64(static_cast<uint64_t>(record.iteration));
  payload.U32(static_cast<uint32_t>(record.planes.size()));
  for (const PlaneInput& plane : record.planes) {
    payload.Vec(plane.normal);
    payload.F64(plane.d);
    payload.Vec(plane.centroid);
    payload.U32(static_cast<uint32_t>(plane.vertices.size()));
    for (const Eigen::Vector3d& v : plane.vertices) payload.Vec(v);
    payload.U32(static_cast<uint32_t>(plane.support));
    payload.F64(plane.rms);
  }
  if (record.odometry) {
    const OdometryIncrement& odometry = *record.odometry;
    payload.U32(kOdometryTag);
    payload.F64(odometry.motion.x);
    payload.F64(odometry.motion.y);
    payload.F64(odometry.motion.yaw);
    for (int i = 0; i < 9; ++i) payload.F64(odometry.covariance(i / 3, i % 3));
    payload.U64(static_cast<uint64_t>(odometry.from_utime));
    payload.U64(static_cast<uint64_t>(odometry.to_utime));
    payload.U32(odometry.readings_lost ? 1u : 0u);
  }
  Out framed;
  framed.U32(static_cast<uint32_t>(payload.bytes.size()));
  framed.U32(Crc32(payload.bytes.data(), payload.bytes.size()));
  framed.bytes.insert(framed.bytes.end(), payload.bytes.begin(), payload.bytes.end());
  return framed.bytes;
}

JournalContents ParseJournal(const std::vector<uint8_t>& bytes) {
  JournalContents contents;
  size_t pos = 0;
  while (pos < bytes.size()) {
    In header(bytes.data() + pos, bytes.size() - pos);
    uint32_t length = 0, crc = 0;
    if (!header.U32(&length) || !header.U32(&crc)) {
      contents.problem = "torn record header";
      break;
    }
    if (length > kMaxPayload) {
      contents.problem = "record length " + std::to_string(length) + " is implausible";
      break;
    }
    if (bytes.size() - pos - kHeaderBytes < length) {
      contents.problem = "torn record (" + std::to_string(bytes.size() - pos - kHeaderBytes) +
                         " of " + std::to_string(length) + " bytes)";
      break;
    }
    const uint8_t* payload = bytes.data() + pos + kHeaderBytes;
    if (Crc32(payload, length) != crc) {
      contents.problem = "record CRC mismatch";
      break;
    }
    JournalRecord record;
    if (!ParsePayload(payload, length, &record)) {
      contents.problem = "record does not parse";
      break;
    }
    if (!contents.records.empty() && record.iteration <= contents.records.back().iteration) {
      contents.problem = "record iteration does not increase";
      break;
    }
    contents.records.push_back(std::move(record));
    pos += kHeaderBytes + length;
  }
  contents.valid_bytes = pos;
  contents.discarded_bytes = bytes.size() - pos;
  return contents;
}

bool ReadJournal(const std::string& path, JournalContents* contents, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (access(path.c_str(), F_OK) != 0) {
      *contents = JournalContents{};
      return true;  // no journal yet: a fresh start
    }
    *error = path + ": cannot read the journal";
    return false;
  }
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  if (in.bad()) {
    *error = path + ": error reading the journal";
    return false;
  }
  *contents = ParseJournal(bytes);
  return true;
}

JournalWriter::~JournalWriter() {
  if (syncer_.joinable()) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_one();
    syncer_.join();
  }
  if (fd_ >= 0) {
    fdatasync(fd_);
    close(fd_);
  }
}

void JournalWriter::SyncLoop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, std::chrono::microseconds(kSyncPeriodUs), [this] { return stop_; })) {
    fdatasync(fd_);
  }
}

bool JournalWriter::Open(const std::string& path, size_t keep_bytes, std::string* error) {
  fd_ = open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0 || ftruncate(fd_, static_cast<off_t>(keep_bytes)) != 0 ||
      lseek(fd_, 0, SEEK_END) < 0) {
    *error = path + ": cannot open the journal for writing: " + std::strerror(errno);
    if (fd_ >= 0) close(fd_);
    fd_ = -1;
    return false;
  }
  bytes_ = static_cast<int64_t>(keep_bytes);
  syncer_ = std::thread([this] { SyncLoop(); });
  return true;
}

bool JournalWriter::Append(const JournalRecord& record, std::string* error) {
  const std::vector<uint8_t> bytes = EncodeRecord(record);
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = write(fd_, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      *error = std::string("journal write failed: ") + std::strerror(errno);
      // Cut the partial record so that later records still follow intact ones.
      if (ftruncate(fd_, static_cast<off_t>(bytes_)) == 0) lseek(fd_, 0, SEEK_END);
      return false;
    }
    done += static_cast<size_t>(n);
  }
  bytes_ += static_cast<int64_t>(bytes.size());
  return true;
}

}  // namespace relplane::mapper
