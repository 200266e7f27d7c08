#include "robot/vision/flow/flo_io.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>

namespace lineloc {
namespace {

std::vector<uint8_t> header(int32_t width, int32_t height) {
  std::vector<uint8_t> bytes = {'P', 'I', 'E', 'H', 0, 0, 0, 0, 0, 0, 0, 0};
  std::memcpy(bytes.data() + 4, &width, 4);
  std::memcpy(bytes.data() + 8, &height, 4);
  return bytes;
}

std::string decodeError(const std::vector<uint8_t>& bytes) {
  try {
    decodeFlo(bytes);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "";
}

TEST(FloIo, RoundTripKeepsEveryVectorAndMarksUnknownFlow) {
  cv::Mat flow(2, 3, CV_32FC2);
  for (int i = 0; i < 6; ++i) {
    flow.at<cv::Vec2f>(i / 3, i % 3) = cv::Vec2f(0.5f * i, -1.25f * i);
  }
  cv::Mat known(2, 3, CV_8U, cv::Scalar(255));
  known.at<uint8_t>(1, 0) = 0;
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("flo_io_test_" + std::to_string(::getpid()) + ".flo");
  writeFlo(path.string(), flow, known);
  const cv::Mat back = readFlo(path.string());
  std::filesystem::remove(path);
  ASSERT_EQ(back.type(), CV_32FC2);
  ASSERT_EQ(back.size(), flow.size());
  for (int i = 0; i < 6; ++i) {
    const cv::Vec2f expected =
        i == 3 ? cv::Vec2f(kUnknownFlow, kUnknownFlow) : flow.at<cv::Vec2f>(i / 3, i % 3);
    EXPECT_EQ(back.at<cv::Vec2f>(i / 3, i % 3), expected) << i;
  }
  // The tag read as a little-endian float is Middlebury's 202021.25.
  const std::vector<uint8_t> bytes = encodeFlo(flow);
  float tag;
  std::memcpy(&tag, bytes.data(), 4);
  EXPECT_EQ(tag, 202021.25f);
  EXPECT_EQ(bytes.size(), 12u + 6u * 8u);
}

TEST(FloIo, MalformedFilesAreRejectedWithTheReason) {
  EXPECT_NE(decodeError({'P', 'I', 'E'}).find("header"), std::string::npos);
  std::vector<uint8_t> wrong_tag = header(1, 1);
  wrong_tag[0] = 'X';
  wrong_tag.resize(20);
  EXPECT_NE(decodeError(wrong_tag).find("PIEH"), std::string::npos);
  EXPECT_NE(decodeError(header(0, 5)).find("size"), std::string::npos);
  EXPECT_NE(decodeError(header(-3, 5)).find("size"), std::string::npos);
  EXPECT_NE(decodeError(header(1 << 20, 1)).find("size"), std::string::npos);
  std::vector<uint8_t> short_data = header(2, 2);
  short_data.resize(12 + 31);
  EXPECT_NE(decodeError(short_data).find("needs 32 bytes"), std::string::npos);
  EXPECT_THROW(readFlo("/nonexistent/flow.flo"), std::runtime_error);
  EXPECT_THROW(encodeFlo(cv::Mat(2, 2, CV_32FC1)), std::runtime_error);
  EXPECT_THROW(encodeFlo(cv::Mat(2, 2, CV_32FC2), cv::Mat(3, 2, CV_8U)), std::runtime_error);
}

}  // namespace
}  // namespace lineloc
