#pragma once
// The mapper's checkpoint (issue 8): the mapper library is deterministic in its input, so its
// state is the plane sets it processed. Each one is appended to a journal file as a record
//   [u32 payload length][u32 CRC-32 of the payload][payload: iteration, planes, odometry]
// (little-endian), in one write, so a kill -9 leaves at most one torn record at the end. The
// odometry block is there only when the plane set came with wheel odometry, so journals written
// before odometry existed read as they are. On
// start the journal is replayed through a fresh Mapper; a torn or corrupt tail is cut off.

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "relplane/mapper/odometry.hpp"
#include "relplane/mapper/types.hpp"

namespace relplane::mapper {

struct JournalRecord {
  int64_t iteration = 0;
  std::vector<PlaneInput> planes;
  std::optional<OdometryIncrement> odometry;  // what Mapper::Process took with the planes
};

// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320), as zlib's crc32().
uint32_t Crc32(const uint8_t* data, size_t size);

// One record, framed as above.
std::vector<uint8_t> EncodeRecord(const JournalRecord& record);

struct JournalContents {
  std::vector<JournalRecord> records;  // every complete, intact record, in order
  size_t valid_bytes = 0;              // where the intact records end
  size_t discarded_bytes = 0;          // torn or corrupt bytes after them
  std::string problem;                 // why the tail was discarded ("" when none was)
};

// Parses journal bytes. Stops at the first record that is torn (cut short), fails its CRC,
// or does not parse; what follows it is discarded, never guessed at.
JournalContents ParseJournal(const std::vector<uint8_t>& bytes);

// Reads the journal at `path`; a missing file is an empty journal. False (with *error) when the
// file exists but cannot be read.
bool ReadJournal(const std::string& path, JournalContents* contents, std::string* error);

// Appends records to the journal, each in one write(2), so they survive the process being
// killed; fdatasync at most once per `sync_period_s` so they also survive a power cut.
class JournalWriter {
 public:
  JournalWriter() = default;
  ~JournalWriter();
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;

  // Opens `path` for appending after its first `keep_bytes` (the intact records; a torn tail
  // is cut off). False with *error when it cannot.
  bool Open(const std::string& path, size_t keep_bytes, std::string* error);
  bool IsOpen() const { return fd_ >= 0; }
  // False with *error when the write fails (disk full, ...): the record is not in the journal.
  // A written record survives the process being killed (the page cache has it); a thread of
  // the writer's own flushes it to the disk once a second, so a slow disk never stalls the
  // caller (the mapper's bus loop).
  bool Append(const JournalRecord& record, std::string* error);
  int64_t BytesWritten() const { return bytes_; }

 private:
  void SyncLoop();

  int fd_ = -1;
  int64_t bytes_ = 0;
  std::thread syncer_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  static constexpr int64_t kSyncPeriodUs = 1000000;
};

}  // namespace relplane::mapper
