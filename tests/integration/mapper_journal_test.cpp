// The mapper's checkpoint journal (services/mapper/journal.hpp): records round-trip exactly, a
// torn or corrupt tail is cut off and counted, the writer appends after the intact records, and
// a mapper fed the replayed records goes on exactly as the one that made them.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <optional>

#include "journal.hpp"
#include "relplane/mapper/mapper.hpp"

namespace relplane::mapper {
namespace {

// A vertical wall seen from the sensor: normal (towards the sensor), offset, its rectangle.
PlaneInput Wall(const Eigen::Vector3d& normal, double d, const Eigen::Vector3d& a,
                const Eigen::Vector3d& b) {
  PlaneInput p;
  p.normal = normal;
  p.d = d;
  p.vertices = {a + Eigen::Vector3d(0, 0, -1), b + Eigen::Vector3d(0, 0, -1),
                b + Eigen::Vector3d(0, 0, 1.5), a + Eigen::Vector3d(0, 0, 1.5)};
  p.centroid = 0.5 * (a + b) + Eigen::Vector3d(0, 0, 0.25);
  p.support = 1000;
  p.rms = 0.001;
  return p;
}

// A sensor moving down a 2 m wide hallway with an end wall, in its own frame.
JournalRecord Frame(int64_t k) {
  const double x = 0.03 * static_cast<double>(k);  // metres travelled
  JournalRecord r;
  r.iteration = k;
  r.planes.push_back(Wall({0, -1, 0}, 1.0, {0.5, 1, 0}, {6.0 - x, 1, 0}));           // left wall
  r.planes.push_back(Wall({0, 1, 0}, 1.0, {0.5, -1, 0}, {6.0 - x, -1, 0}));          // right wall
  r.planes.push_back(Wall({-1, 0, 0}, 6.5 - x, {6.5 - x, 1, 0}, {6.5 - x, -1, 0}));  // end
  return r;
}

std::vector<uint8_t> Concat(const std::vector<JournalRecord>& records) {
  std::vector<uint8_t> bytes;
  for (const JournalRecord& r : records) {
    const std::vector<uint8_t> one = EncodeRecord(r);
    bytes.insert(bytes.end(), one.begin(), one.end());
  }
  return bytes;
}

void ExpectSame(const JournalRecord& a, const JournalRecord& b) {
  ASSERT_EQ(a.iteration, b.iteration);
  ASSERT_EQ(a.planes.size(), b.planes.size());
  for (size_t i = 0; i < a.planes.size(); ++i) {
    EXPECT_EQ(a.planes[i].normal, b.planes[i].normal);  // bit-exact: replay must be identical
    EXPECT_EQ(a.planes[i].d, b.planes[i].d);
    EXPECT_EQ(a.planes[i].centroid, b.planes[i].centroid);
    EXPECT_EQ(a.planes[i].vertices, b.planes[i].vertices);
    EXPECT_EQ(a.planes[i].support, b.planes[i].support);
    EXPECT_EQ(a.planes[i].rms, b.planes[i].rms);
  }
  ASSERT_EQ(a.odometry.has_value(), b.odometry.has_value());
  if (a.odometry) {
    EXPECT_EQ(a.odometry->motion.x, b.odometry->motion.x);
    EXPECT_EQ(a.odometry->motion.y, b.odometry->motion.y);
    EXPECT_EQ(a.odometry->motion.yaw, b.odometry->motion.yaw);
    EXPECT_EQ(a.odometry->covariance, b.odometry->covariance);
    EXPECT_EQ(a.odometry->from_utime, b.odometry->from_utime);
    EXPECT_EQ(a.odometry->to_utime, b.odometry->to_utime);
    EXPECT_EQ(a.odometry->readings_lost, b.odometry->readings_lost);
  }
}

// Wheel odometry's motion over frame k's step (0.03 m forwards, a slight turn), as read.
OdometryIncrement Odometry(int64_t k) {
  OdometryIncrement o;
  o.motion = {0.031, -0.0004, 0.0002};
  o.covariance = Eigen::Matrix3d::Identity() * 1e-6;
  o.covariance(0, 1) = o.covariance(1, 0) = 2e-7;
  o.from_utime = (k - 1) * 33333;
  o.to_utime = k * 33333;
  o.readings_lost = k % 2 == 0;
  return o;
}

TEST(MapperJournal, Crc32MatchesTheStandardCheckValue) {
  const std::string text = "123456789";
  EXPECT_EQ(Crc32(reinterpret_cast<const uint8_t*>(text.data()), text.size()), 0xCBF43926u);
}

TEST(MapperJournal, RoundTrip) {
  std::vector<JournalRecord> records = {Frame(0), Frame(1), Frame(5)};
  records[1].planes.clear();  // a frame with no planes is a record too
  records[2].planes[0].d = 1.0 / 3.0;
  const JournalContents contents = ParseJournal(Concat(records));
  EXPECT_EQ(contents.problem, "");
  EXPECT_EQ(contents.discarded_bytes, 0u);
  ASSERT_EQ(contents.records.size(), 3u);
  for (size_t i = 0; i < records.size(); ++i) ExpectSame(contents.records[i], records[i]);
}

TEST(MapperJournal, OdometryRoundTripsAndOlderRecordsHaveNone) {
  std::vector<JournalRecord> records = {Frame(0), Frame(1), Frame(2)};
  records[1].odometry = Odometry(1);
  records[2].odometry = Odometry(2);
  records[2].planes.clear();
  // A record without odometry is byte for byte what journals held before odometry existed.
  EXPECT_EQ(EncodeRecord(records[0]).size(), EncodeRecord(Frame(0)).size());
  const JournalContents contents = ParseJournal(Concat(records));
  EXPECT_EQ(contents.problem, "");
  ASSERT_EQ(contents.records.size(), 3u);
  for (size_t i = 0; i < records.size(); ++i) ExpectSame(contents.records[i], records[i]);
}

TEST(MapperJournal, UnknownTrailerIsCorruptNotGuessed) {
  std::vector<uint8_t> bytes = EncodeRecord(Frame(0));
  // Four bytes after the planes that are not an odometry block, with the CRC made to match.
  const std::vector<uint8_t> junk = {1, 2, 3, 4};
  bytes.insert(bytes.end(), junk.begin(), junk.end());
  const uint32_t length = static_cast<uint32_t>(bytes.size() - 8);
  const uint32_t crc = Crc32(bytes.data() + 8, length);
  for (int i = 0; i < 4; ++i) {
    bytes[i] = static_cast<uint8_t>(length >> (8 * i));
    bytes[4 + i] = static_cast<uint8_t>(crc >> (8 * i));
  }
  const JournalContents contents = ParseJournal(bytes);
  EXPECT_TRUE(contents.records.empty());
  EXPECT_NE(contents.problem, "");
}

TEST(MapperJournal, TornTailIsCutAtEveryLength) {
  const std::vector<uint8_t> first = EncodeRecord(Frame(0));
  const std::vector<uint8_t> all = Concat({Frame(0), Frame(1)});
  for (size_t cut = first.size() + 1; cut < all.size(); ++cut) {
    const JournalContents c = ParseJournal(std::vector<uint8_t>(all.begin(), all.begin() + cut));
    ASSERT_EQ(c.records.size(), 1u) << cut;
    EXPECT_EQ(c.valid_bytes, first.size());
    EXPECT_EQ(c.discarded_bytes, cut - first.size());
    EXPECT_NE(c.problem.find("torn"), std::string::npos) << c.problem;
  }
}

TEST(MapperJournal, BadCrcDiscardsThatRecordAndEverythingAfter) {
  std::vector<uint8_t> bytes = Concat({Frame(0), Frame(1), Frame(2)});
  const size_t one = EncodeRecord(Frame(0)).size();
  bytes[one + 8 + 20] ^= 0x01;  // a bit inside the second record's payload
  const JournalContents c = ParseJournal(bytes);
  ASSERT_EQ(c.records.size(), 1u);
  EXPECT_EQ(c.problem, "record CRC mismatch");
  EXPECT_EQ(c.discarded_bytes, bytes.size() - one);
}

TEST(MapperJournal, ImplausibleLengthAndDecreasingIterationStopTheReplay) {
  std::vector<uint8_t> huge = {0xFF, 0xFF, 0xFF, 0xFF, 0, 0, 0, 0};
  EXPECT_EQ(ParseJournal(huge).records.size(), 0u);
  EXPECT_NE(ParseJournal(huge).problem.find("implausible"), std::string::npos);
  const JournalContents c = ParseJournal(Concat({Frame(3), Frame(2)}));
  EXPECT_EQ(c.records.size(), 1u);
  EXPECT_EQ(c.problem, "record iteration does not increase");
}

TEST(MapperJournal, WriterAppendsAfterTheIntactRecords) {
  char path[] = "/tmp/relplane-journal-XXXXXX";
  const int fd = mkstemp(path);
  ASSERT_GE(fd, 0);
  close(fd);
  std::string error;
  {
    JournalWriter writer;
    ASSERT_TRUE(writer.Open(path, 0, &error)) << error;
    ASSERT_TRUE(writer.Append(Frame(0), &error));
    ASSERT_TRUE(writer.Append(Frame(1), &error));
  }
  {  // a torn third record, as a kill -9 in the middle of a write would leave
    std::vector<uint8_t> torn = EncodeRecord(Frame(2));
    std::ofstream(path, std::ios::binary | std::ios::app)
        .write(reinterpret_cast<const char*>(torn.data()), 10);
  }
  JournalContents c;
  ASSERT_TRUE(ReadJournal(path, &c, &error)) << error;
  ASSERT_EQ(c.records.size(), 2u);
  EXPECT_EQ(c.discarded_bytes, 10u);
  {
    JournalWriter writer;
    ASSERT_TRUE(writer.Open(path, c.valid_bytes, &error)) << error;
    ASSERT_TRUE(writer.Append(Frame(3), &error));
  }
  ASSERT_TRUE(ReadJournal(path, &c, &error)) << error;
  ASSERT_EQ(c.records.size(), 3u);
  EXPECT_EQ(c.problem, "");
  ExpectSame(c.records[2], Frame(3));
  unlink(path);

  // No file yet: an empty journal, not an error.
  ASSERT_TRUE(ReadJournal(std::string(path) + ".none", &c, &error));
  EXPECT_TRUE(c.records.empty());
}

// With and without wheel odometry: a replay must take the odometry the original took.
class ReplayedMapper : public ::testing::TestWithParam<bool> {};

TEST_P(ReplayedMapper, GoesOnAsTheOriginal) {
  const bool with_odometry = GetParam();
  auto odometry = [&](int64_t k) {
    return with_odometry && k > 0 ? std::optional<OdometryIncrement>(Odometry(k)) : std::nullopt;
  };
  Mapper original;
  std::vector<JournalRecord> written;
  for (int64_t k = 0; k < 40; ++k) {
    written.push_back(Frame(k));
    written.back().odometry = odometry(k);
    original.Process(k, written.back().planes, written.back().odometry);
  }
  Mapper replayed;
  for (const JournalRecord& r : ParseJournal(Concat(written)).records) {
    replayed.Process(r.iteration, r.planes, r.odometry);
  }
  for (int64_t k = 42; k < 60; ++k) {  // a gap, as while the mapper was down
    const PoseEstimate a = original.Process(k, Frame(k).planes, odometry(k));
    const PoseEstimate b = replayed.Process(k, Frame(k).planes, odometry(k));
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.pose.x, b.pose.x) << k;
    EXPECT_EQ(a.pose.y, b.pose.y) << k;
    EXPECT_EQ(a.pose.yaw, b.pose.yaw) << k;
  }
  EXPECT_EQ(original.Map().planes.size(), replayed.Map().planes.size());
}

INSTANTIATE_TEST_SUITE_P(MapperJournal, ReplayedMapper, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? "WithOdometry" : "WithoutOdometry";
                         });

}  // namespace
}  // namespace relplane::mapper
