#include "robot/vision/stereo/pfm_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>

namespace lineloc {
namespace {

std::vector<uint8_t> bytesOf(const std::string& text) {
  return {text.begin(), text.end()};
}

std::string decodeError(const std::vector<uint8_t>& bytes) {
  try {
    decodePfm(bytes);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "";
}

TEST(PfmIo, RoundTripKeepsEveryFloatAndTheRowOrder) {
  cv::Mat image(3, 4, CV_32FC1);
  for (int i = 0; i < 12; ++i) {
    image.at<float>(i / 4, i % 4) = 0.25f * i - 1.0f;
  }
  image.at<float>(1, 2) = std::numeric_limits<float>::infinity();
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("pfm_io_test_" + std::to_string(::getpid()) + ".pfm");
  writePfm(path.string(), image);
  const cv::Mat back = readPfm(path.string());
  std::filesystem::remove(path);
  ASSERT_EQ(back.type(), CV_32FC1);
  ASSERT_EQ(back.size(), image.size());
  EXPECT_EQ(std::memcmp(back.data, image.data, 12 * sizeof(float)), 0);
  // The first stored row is the image's bottom row.
  const std::vector<uint8_t> bytes = encodePfm(image);
  float first_stored;
  std::memcpy(&first_stored, bytes.data() + std::string("Pf\n4 3\n-1\n").size(), sizeof(float));
  EXPECT_EQ(first_stored, image.at<float>(2, 0));
}

TEST(PfmIo, ThreeChannelsAndBigEndianAreRead) {
  std::vector<uint8_t> bytes = bytesOf("PF\n1 1\n1.0\n");
  for (float value : {1.5f, -2.0f, 3.25f}) {
    uint32_t word;
    std::memcpy(&word, &value, 4);
    word = __builtin_bswap32(word);
    const auto* p = reinterpret_cast<const uint8_t*>(&word);
    bytes.insert(bytes.end(), p, p + 4);
  }
  const cv::Mat image = decodePfm(bytes);
  ASSERT_EQ(image.type(), CV_32FC3);
  EXPECT_EQ(image.at<cv::Vec3f>(0, 0), cv::Vec3f(1.5f, -2.0f, 3.25f));
}

TEST(PfmIo, InvalidPixelsBecomeInfinity) {
  cv::Mat disparity(1, 2, CV_32F, cv::Scalar(5.0f));
  cv::Mat valid = (cv::Mat_<uint8_t>(1, 2) << 255, 0);
  const cv::Mat out = disparityForPfm(disparity, valid);
  EXPECT_EQ(out.at<float>(0, 0), 5.0f);
  EXPECT_TRUE(std::isinf(out.at<float>(0, 1)));
}

TEST(PfmIo, MalformedFilesAreRejectedWithTheReason) {
  const std::string data(8, '\0');
  EXPECT_NE(decodeError({}).find("magic"), std::string::npos);
  EXPECT_NE(decodeError(bytesOf("P6\n1 1\n-1\n" + data)).find("neither Pf nor PF"),
            std::string::npos);
  EXPECT_NE(decodeError(bytesOf("Pf\n-1 1\n-1\n" + data)).find("width"), std::string::npos);
  EXPECT_NE(decodeError(bytesOf("Pf\n1 0\n-1\n" + data)).find("height"), std::string::npos);
  EXPECT_NE(decodeError(bytesOf("Pf\n99999999 99999999\n-1\n")).find("range"), std::string::npos);
  EXPECT_NE(decodeError(bytesOf("Pf\n1 1\nabc\n" + data)).find("scale"), std::string::npos);
  EXPECT_NE(decodeError(bytesOf("Pf\n1 1\n0\n" + data)).find("scale"), std::string::npos);
  EXPECT_NE(decodeError(bytesOf("Pf\n2 1\n-1\n" + data.substr(0, 5))).find("needs 8 bytes"),
            std::string::npos);
  EXPECT_NE(decodeError(bytesOf("Pf\n1 1\n-1")).find("scale"), std::string::npos);
  EXPECT_THROW(readPfm("/nonexistent/disparity.pfm"), std::runtime_error);
  EXPECT_THROW(encodePfm(cv::Mat(2, 2, CV_8U)), std::runtime_error);
}

}  // namespace
}  // namespace lineloc
