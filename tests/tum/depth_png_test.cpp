// 16-bit depth PNGs (libpng), TUM calibration and depth.txt files, and depth images as clouds.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "relplane/tum/depth_png.hpp"
#include "relplane/tum/tum_folder.hpp"

namespace relplane::tum {
namespace {

class TumFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("relplane_tum_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  void Write(const std::string& name, const std::string& text) const {
    std::ofstream(Path(name)) << text;
  }
  std::filesystem::path dir_;
};

template <class F>
std::string ErrorOf(F&& f) {
  try {
    f();
  } catch (const DepthImageError& e) {
    return e.what();
  }
  return "";
}

TEST_F(TumFiles, SixteenBitValuesSurviveAWriteAndARead) {
  DepthImage image;
  image.width = 5;
  image.height = 3;
  // 0 (no depth), both bytes set (endianness), the extremes.
  image.values = {0, 1, 258, 65535, 5000, 12345, 256, 255, 7, 0, 40000, 2, 3, 4, 65534};
  WriteDepthPng(Path("d.png"), image);
  const DepthImage back = ReadDepthPng(Path("d.png"));
  EXPECT_EQ(back.width, 5);
  EXPECT_EQ(back.height, 3);
  EXPECT_EQ(back.values, image.values);
  EXPECT_EQ(back.At(3, 0), 65535);
  EXPECT_EQ(back.At(0, 2), 40000);
}

TEST_F(TumFiles, BadFilesAreOneLineErrorsNamingTheFile) {
  EXPECT_NE(ErrorOf([&] { ReadDepthPng(Path("missing.png")); }).find("missing.png: cannot open"),
            std::string::npos);
  Write("text.png", "not a png at all");
  EXPECT_NE(ErrorOf([&] { ReadDepthPng(Path("text.png")); }).find("not a PNG"), std::string::npos);
  // A PNG cut short after its signature: libpng's own error, through the callback.
  DepthImage image;
  image.width = 64;
  image.height = 64;
  image.values.assign(64 * 64, 1234);
  WriteDepthPng(Path("whole.png"), image);
  std::ifstream whole(Path("whole.png"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(whole)), std::istreambuf_iterator<char>());
  std::ofstream(Path("cut.png"), std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  const std::string cut = ErrorOf([&] { ReadDepthPng(Path("cut.png")); });
  EXPECT_NE(cut.find("cut.png: "), std::string::npos) << cut;
  EXPECT_EQ(cut.find('\n'), std::string::npos);
  DepthImage wrong;
  wrong.width = 2;
  wrong.height = 2;
  EXPECT_FALSE(ErrorOf([&] { WriteDepthPng(Path("w.png"), wrong); }).empty());
}

TEST_F(TumFiles, CalibrationFiles) {
  Write("k.txt", "# fx fy cx cy scale\n\n  517.3 516.5 318.6 255.3\n");
  const Intrinsics k = ReadCalibration(Path("k.txt"));
  EXPECT_DOUBLE_EQ(k.fx, 517.3);
  EXPECT_DOUBLE_EQ(k.cy, 255.3);
  EXPECT_DOUBLE_EQ(k.depth_scale, 5000.0) << "TUM's default when not given";
  Write("s.txt", "481.2 -480 319.5 239.5 1000\n");
  EXPECT_NE(ErrorOf([&] { ReadCalibration(Path("s.txt")); }).find("s.txt:1"), std::string::npos);
  Write("t.txt", "481.2 480 319.5\n");
  EXPECT_NE(ErrorOf([&] { ReadCalibration(Path("t.txt")); }).find("t.txt:1"), std::string::npos);
  Write("e.txt", "# nothing\n");
  EXPECT_FALSE(ErrorOf([&] { ReadCalibration(Path("e.txt")); }).empty());
  Intrinsics written;
  written.fx = 290.123456789;
  written.depth_scale = 1000.0;
  WriteCalibration(Path("w.txt"), written);
  EXPECT_DOUBLE_EQ(ReadCalibration(Path("w.txt")).fx, written.fx);
  EXPECT_DOUBLE_EQ(ReadCalibration(Path("w.txt")).depth_scale, 1000.0);
}

TEST_F(TumFiles, DepthListsInTheirOrder) {
  Write("depth.txt",
        "# depth maps\n# timestamp filename\n1305031102.160407 depth/1305031102.160407.png\n"
        "1305031102.194330 depth/1305031102.194330.png\n");
  const std::vector<DepthFrame> frames = ReadDepthList(dir_.string());
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_DOUBLE_EQ(frames[1].timestamp, 1305031102.194330);
  EXPECT_EQ(frames[0].path, dir_.string() + "/depth/1305031102.160407.png");
  Write("depth.txt", "1.0 a.png\nbroken\n");
  EXPECT_NE(ErrorOf([&] { ReadDepthList(dir_.string()); }).find("depth.txt:2"), std::string::npos);
}

TEST(DepthToCloud, PixelsGoToTheSensorFrame) {
  DepthImage image;
  image.width = 4;
  image.height = 3;
  image.values.assign(12, 0);
  Intrinsics k;
  k.fx = 2.0;
  k.fy = 4.0;
  k.cx = 1.0;
  k.cy = 1.0;
  image.values[1 * 4 + 1] = 10000;  // (u, v) = (1, 1): the principal point, 2 m ahead
  image.values[0 * 4 + 3] = 5000;   // (3, 0): 1 m ahead, right and up of it
  const pcd::PcdCloud c = DepthToCloud(image, k);
  ASSERT_EQ(c.size(), 12u);
  EXPECT_EQ(c.width, 4);
  EXPECT_FLOAT_EQ(c.x[5], 2.0f);
  EXPECT_FLOAT_EQ(c.y[5], 0.0f);
  EXPECT_FLOAT_EQ(c.z[5], 0.0f);
  EXPECT_FLOAT_EQ(c.x[3], 1.0f);
  EXPECT_FLOAT_EQ(c.y[3], -1.0f);  // u - cx = 2 pixels right: y (left) = -2 / fx
  EXPECT_FLOAT_EQ(c.z[3], 0.25f);  // v - cy = 1 pixel up: z = 1 / fy
  EXPECT_TRUE(std::isnan(c.x[0]));
}

}  // namespace
}  // namespace relplane::tum
