// ImagePrefetcher: each frame comes back as it is on disk, in order or after
// skips, nothing is decoded ahead between a take and the resume after it, a
// corrupt frame's error comes back for that frame only, and stopping with
// frames in flight is clean.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <thread>

#include "robot/input/image_prefetcher.h"

namespace fs = std::filesystem;

namespace lineloc {
namespace {

class ImagePrefetcherTest : public ::testing::Test {
 protected:
  static constexpr int kFrames = 12;

  void SetUp() override {
    root_ = fs::temp_directory_path() / ("prefetcher_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    for (int i = 0; i < kFrames; ++i) {
      const fs::path path = root_ / (std::to_string(i) + ".png");
      cv::imwrite(path.string(), cv::Mat(24, 32, CV_8UC1, cv::Scalar(10 * i)));
      frames_.push_back({path.string(), i});
    }
  }
  void TearDown() override { fs::remove_all(root_); }

  // Every frame is a flat image of grey level 10 i.
  static int greyOf(const cv::Mat& image) { return image.at<uchar>(5, 5); }

  fs::path root_;
  std::vector<FrameRef> frames_;
};

TEST_F(ImagePrefetcherTest, GivesEveryFrameInOrder) {
  ImagePrefetcher prefetcher(frames_);
  for (int i = 0; i < kFrames; ++i) {
    const cv::Mat image = prefetcher.take(static_cast<size_t>(i));
    ASSERT_EQ(image.type(), CV_8UC1);
    EXPECT_EQ(greyOf(image), 10 * i);
  }
}

TEST_F(ImagePrefetcherTest, SkipsForwardToAnyFrame) {
  ImagePrefetcher prefetcher(frames_, 3);
  EXPECT_EQ(greyOf(prefetcher.take(0)), 0);
  EXPECT_EQ(greyOf(prefetcher.take(2)), 20);
  EXPECT_EQ(greyOf(prefetcher.take(9)), 90);
  EXPECT_EQ(greyOf(prefetcher.take(10)), 100);
  EXPECT_THROW(prefetcher.take(kFrames), std::out_of_range);
}

// Frame 2 is rewritten after frame 1 is taken: it comes back as rewritten
// only if nothing was decoded before resume(), however long the wait.
TEST_F(ImagePrefetcherTest, DecodesNothingAheadUntilResumed) {
  ImagePrefetcher prefetcher(frames_);
  EXPECT_EQ(greyOf(prefetcher.take(0)), 0);
  EXPECT_EQ(greyOf(prefetcher.take(1)), 10);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  cv::imwrite(frames_[2].path, cv::Mat(24, 32, CV_8UC1, cv::Scalar(222)));
  prefetcher.resume();
  EXPECT_EQ(greyOf(prefetcher.take(2)), 222);
  prefetcher.resume();
  EXPECT_EQ(greyOf(prefetcher.take(3)), 30);
}

TEST_F(ImagePrefetcherTest, ACorruptFrameFailsAloneWithItsName) {
  std::ofstream(frames_[4].path, std::ios::trunc) << "\x89PNG\r\n\x1a\n garbage";
  ImagePrefetcher prefetcher(frames_);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(greyOf(prefetcher.take(static_cast<size_t>(i))), 10 * i);
  }
  try {
    prefetcher.take(4);
    ADD_FAILURE() << "a corrupt frame was decoded";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("4.png"), std::string::npos) << error.what();
  }
  EXPECT_EQ(greyOf(prefetcher.take(5)), 50);
}

TEST_F(ImagePrefetcherTest, StopsWithFramesInFlight) {
  for (int run = 0; run < 20; ++run) {
    ImagePrefetcher prefetcher(frames_, 4);
    EXPECT_EQ(greyOf(prefetcher.take(static_cast<size_t>(run % kFrames))), 10 * (run % kFrames));
  }
}

}  // namespace
}  // namespace lineloc
