#include "relplane/common/bus.hpp"

#include <gtest/gtest.h>
#include <relplane/pose_t.hpp>
#include <relplane/status_t.hpp>
#include <relplane/map_t.hpp>
#include <relplane/point_cloud_t.hpp>

namespace relplane::bus {
namespace {

// The tests run with LCM_DEFAULT_URL=memq:// (tests/CMakeLists.txt): an in-process bus.
TEST(Bus, TypedRoundTripOnMemq) {
  auto bus = OpenLcmBus(ResolveUrl(""));
  std::vector<pose_t> got;
  std::vector<std::string> rejects;
  Subscribe<pose_t>(
      *bus, "POSE", [&](const pose_t& m) { got.push_back(m); },
      [&](const std::string& r) { rejects.push_back(r); });
  pose_t pose{};
  pose.seq = 42;
  pose.position[0] = 1.5;
  pose.orientation[0] = 1.0;
  pose.status = pose_t::STATUS_TRACKING;
  ASSERT_TRUE(Publish(*bus, "POSE", pose));
  while (bus->Handle(20) > 0) {
  }
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].seq, 42);
  EXPECT_EQ(got[0].position[0], 1.5);
  EXPECT_TRUE(rejects.empty());
}

// The subscription keeps one message for every delivery; lcm-gen's decoder leaves an array
// untouched when its declared length is 0, so an empty message after a full one must not keep
// the full one's elements (nor a plane set the previous set's planes).
TEST(Bus, AKeptMessageCarriesNothingOfThePreviousOne) {
  auto bus = OpenLcmBus("memq://");
  std::vector<size_t> cloud_sizes, plane_counts;
  Subscribe<point_cloud_t>(
      *bus, "SENSOR_POINTS",
      [&](const point_cloud_t& m) {
        EXPECT_EQ(m.x.size(), static_cast<size_t>(m.num_points));
        cloud_sizes.push_back(m.x.size() + m.y.size() + m.z.size());
      },
      [](const std::string& r) { ADD_FAILURE() << r; });
  Subscribe<map_t>(
      *bus, "MAP", [&](const map_t& m) { plane_counts.push_back(m.planes.size()); },
      [](const std::string& r) { ADD_FAILURE() << r; });
  point_cloud_t full{};
  full.num_points = 3;
  full.x = full.y = full.z = {1, 2, 3};
  map_t map{};
  map.num_planes = 2;
  map.planes.resize(2);
  for (const point_cloud_t& cloud : {full, point_cloud_t{}, full}) {
    ASSERT_TRUE(Publish(*bus, "SENSOR_POINTS", cloud));
  }
  for (const map_t& m : {map, map_t{}}) ASSERT_TRUE(Publish(*bus, "MAP", m));
  while (bus->Handle(20) > 0) {
  }
  EXPECT_EQ(cloud_sizes, (std::vector<size_t>{9, 0, 9}));
  EXPECT_EQ(plane_counts, (std::vector<size_t>{2, 0}));
}

TEST(Bus, ForeignTypeIsRejectedNotDelivered) {
  auto bus = OpenLcmBus("memq://");
  int delivered = 0;
  std::vector<std::string> rejects;
  Subscribe<pose_t>(
      *bus, "POSE", [&](const pose_t&) { ++delivered; },
      [&](const std::string& r) { rejects.push_back(r); });
  point_cloud_t cloud{};
  cloud.num_points = 1;
  cloud.x = {1};
  cloud.y = {2};
  cloud.z = {3};
  ASSERT_TRUE(Publish(*bus, "POSE", cloud));
  const uint8_t junk[5] = {1, 2, 3, 4, 5};
  ASSERT_TRUE(bus->PublishRaw("POSE", junk, sizeof junk));
  while (bus->Handle(20) > 0) {
  }
  EXPECT_EQ(delivered, 0);
  EXPECT_EQ(rejects.size(), 2u);
}

TEST(Decode, AbsurdArrayLengthIsAReasonNotACrash) {
  point_cloud_t cloud{};
  cloud.num_points = 2;
  cloud.x = {1, 2};
  cloud.y = {1, 2};
  cloud.z = {1, 2};
  std::vector<uint8_t> buf(cloud.getEncodedSize());
  cloud.encode(buf.data(), 0, buf.size());
  // num_points sits after the 8-byte fingerprint, utime and seq; make it negative.
  buf[24] = 0xff;
  point_cloud_t out;
  std::string reason;
  EXPECT_FALSE(Decode(buf.data(), buf.size(), &out, &reason));
  EXPECT_FALSE(reason.empty());
  // And a huge positive length with a short buffer.
  buf[24] = 0x7f;
  EXPECT_FALSE(Decode(buf.data(), buf.size(), &out, &reason));
}

TEST(Decode, TrailingBytesAndOversize) {
  pose_t pose{};
  std::vector<uint8_t> buf(pose.getEncodedSize() + 3);
  pose.encode(buf.data(), 0, pose.getEncodedSize());
  pose_t out;
  std::string reason;
  EXPECT_FALSE(Decode(buf.data(), buf.size(), &out, &reason));
  EXPECT_NE(reason.find("trailing"), std::string::npos);
  EXPECT_FALSE(Decode(buf.data(), buf.size(), &out, &reason, 10));
  EXPECT_NE(reason.find("limit"), std::string::npos);
}

}  // namespace
}  // namespace relplane::bus

namespace relplane::bus {
namespace {

// Encodes a map with one plane of two vertices and one group of three members.
std::vector<uint8_t> EncodedMap() {
  map_t map{};
  plane_t plane{};
  plane.num_vertices = 2;
  plane.vertices = {{0, 0, 0}, {1, 1, 1}};
  map.planes = {plane};
  map.num_planes = 1;
  group_t group{};
  group.num_members = 3;
  group.members = {1, 2, 3};
  map.groups = {group};
  map.num_groups = 1;
  std::vector<uint8_t> buf(map.getEncodedSize());
  map.encode(buf.data(), 0, buf.size());
  return buf;
}

TEST(Decode, MapRoundTripsAndHostileNestedLengthsAreRefused) {
  std::vector<uint8_t> buf = EncodedMap();
  map_t out;
  std::string reason;
  ASSERT_TRUE(Decode(buf.data(), buf.size(), &out, &reason)) << reason;
  ASSERT_EQ(out.groups.size(), 1u);
  EXPECT_EQ(out.groups[0].members[2], 3);

  // plane_t.num_vertices sits after hash, utime, seq, num_planes and 36 bytes of the plane.
  std::vector<uint8_t> hostile = buf;
  hostile[28 + 36] = 0x40;  // about a billion vertices
  EXPECT_FALSE(Decode(hostile.data(), hostile.size(), &out, &reason));
  EXPECT_NE(reason.find("vertices"), std::string::npos) << reason;

  // The last group's member count: 3 members * 8 bytes before the end.
  hostile = buf;
  hostile[hostile.size() - 24 - 4] = 0x7f;
  EXPECT_FALSE(Decode(hostile.data(), hostile.size(), &out, &reason));
  EXPECT_NE(reason.find("members"), std::string::npos) << reason;

  // Truncation anywhere is refused.
  for (size_t cut = 0; cut < buf.size(); ++cut) {
    EXPECT_FALSE(Decode(buf.data(), cut, &out, &reason)) << cut;
  }
}

}  // namespace
}  // namespace relplane::bus

namespace relplane::bus {
namespace {

TEST(Decode, StatusRoundTripsAndZeroStringLengthIsRefused) {
  status_t status{};
  status.service = "relplane-test";
  status.detail = "";
  status.last_seq = 7;
  std::vector<uint8_t> buf(status.getEncodedSize());
  status.encode(buf.data(), 0, buf.size());
  status_t out;
  std::string reason;
  ASSERT_TRUE(Decode(buf.data(), buf.size(), &out, &reason)) << reason;
  EXPECT_EQ(out.service, "relplane-test");
  EXPECT_EQ(out.last_seq, 7);
  // A NUL inside the service string, or none at its end, would not encode back: refused.
  // The string's length field follows the hash and utime; its bytes follow the length.
  std::vector<uint8_t> inner = buf;
  inner[20 + 3] = 0;
  EXPECT_FALSE(Decode(inner.data(), inner.size(), &out, &reason));
  std::vector<uint8_t> unterminated = buf;
  unterminated[20 + status.service.size()] = 'x';
  EXPECT_FALSE(Decode(unterminated.data(), unterminated.size(), &out, &reason));
  // A zero length is refused.
  buf[16] = buf[17] = buf[18] = buf[19] = 0;
  EXPECT_FALSE(Decode(buf.data(), buf.size(), &out, &reason));
}

}  // namespace
}  // namespace relplane::bus
