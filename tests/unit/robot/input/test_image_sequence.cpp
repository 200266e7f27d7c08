#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "robot/input/image_sequence.h"

namespace fs = std::filesystem;

namespace lineloc {
namespace {

class ImageSequenceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("sequence_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  void writeImage(const fs::path& path, int channels = 3) {
    fs::create_directories(path.parent_path());
    cv::imwrite(path.string(), cv::Mat(24, 32, CV_8UC(channels), cv::Scalar::all(90)));
  }

  fs::path root_;
};

TEST_F(ImageSequenceTest, PlainFolderInNameOrderWithoutStamps) {
  writeImage(root_ / "b.png");
  writeImage(root_ / "a.jpg");
  std::ofstream(root_ / "notes.txt") << "not an image";
  const auto frames = listImageSequence(root_.string());
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(fs::path(frames[0].path).filename(), "a.jpg");
  EXPECT_FALSE(frames[0].stamp_ns.has_value());
}

TEST_F(ImageSequenceTest, NumericNamesAreStamps) {
  writeImage(root_ / "1403636579763555584.png");
  writeImage(root_ / "1403636579813555456.png");
  const auto frames = listImageSequence(root_.string());
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[1].stamp_ns, 1403636579813555456);
}

TEST_F(ImageSequenceTest, EurocDatasetRootAndCameraFolder) {
  writeImage(root_ / "cam0" / "data" / "100.png");
  writeImage(root_ / "cam0" / "data" / "200.png");
  std::ofstream(root_ / "cam0" / "data.csv") << "#timestamp [ns],filename\n100,100.png\r\n"
                                             << "200 , 200.png\n";
  for (const fs::path& path : {root_, root_ / "cam0"}) {
    const auto frames = listImageSequence(path.string());
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(frames[0].stamp_ns, 100);
    EXPECT_EQ(frames[1].path, (root_ / "cam0" / "data" / "200.png").string());
  }
}

TEST(EurocCsv, MalformedRowsNameFileAndLine) {
  const char* bad_files[] = {
      "100,a.png\nabc,b.png\n",        // stamp not a number
      "100,a.png\n100,b.png\n",        // stamp not increasing
      "100\n",                         // no file name
      "100,../../etc/passwd\n",        // escapes the data folder
      "100,/abs.png\n",                // absolute path
      "-5,a.png\n",                    // negative stamp
      "99999999999999999999,a.png\n",  // overflows int64
      "#only a comment\n",             // no frames
  };
  for (const char* text : bad_files) {
    std::istringstream stream(text);
    EXPECT_THROW(parseEurocCameraCsv(stream, "cam0/data.csv", "data"), std::runtime_error) << text;
  }
  std::istringstream stream("100,a.png\nxyz,b.png\n");
  try {
    parseEurocCameraCsv(stream, "cam0/data.csv", "data");
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("cam0/data.csv:2"), std::string::npos);
  }
}

TEST_F(ImageSequenceTest, ErrorsForMissingFolderAndEmptyFolder) {
  EXPECT_THROW(listImageSequence((root_ / "missing").string()), std::runtime_error);
  EXPECT_THROW(listImageSequence(root_.string()), std::runtime_error);
}

TEST_F(ImageSequenceTest, ReadGreyConvertsColourAndRejectsCorruptFiles) {
  writeImage(root_ / "colour.png", 3);
  const cv::Mat grey = readGreyImage((root_ / "colour.png").string());
  EXPECT_EQ(grey.type(), CV_8UC1);
  EXPECT_EQ(grey.cols, 32);
  std::ofstream(root_ / "corrupt.png") << "\x89PNG\r\n\x1a\n garbage";
  EXPECT_THROW(readGreyImage((root_ / "corrupt.png").string()), std::runtime_error);
  cv::imwrite((root_ / "deep.png").string(), cv::Mat(8, 8, CV_16UC1, cv::Scalar(1000)));
  EXPECT_THROW(readGreyImage((root_ / "deep.png").string()), std::runtime_error);
}

TEST_F(ImageSequenceTest, ReadGreyRefusesAFrameClaimingMorePixelsThanTheLimit) {
  // A PNG header claiming 20000 x 20000 pixels, and nothing after it.
  std::ofstream(root_ / "huge.png")
      << std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0N \0\0N \x08\0\0\0\0", 29);
  try {
    readGreyImage((root_ / "huge.png").string());
    FAIL() << "a 400-megapixel frame accepted";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("huge.png': its PNG header claims 20000 x 20000"),
              std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace lineloc
