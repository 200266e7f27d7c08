// Image files read within a pixel limit: real PNG and JPEG files decode as
// OpenCV decodes them; tiny files whose headers claim 20000 x 20000 pixels are
// refused by what their header claims, before any decoder runs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/image/image_file.h"

namespace lineloc {
namespace {

namespace fs = std::filesystem;

class ImageFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("image_file_" + std::to_string(getpid()));
    fs::create_directories(root_);
    image_ = cv::Mat(48, 64, CV_8UC1);
    cv::randu(image_, 0, 255);
  }
  void TearDown() override { fs::remove_all(root_); }

  std::string write(const std::string& name, const std::string& bytes) const {
    const std::string path = (root_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  std::string encoded(const std::string& extension) const {
    std::vector<uint8_t> bytes;
    EXPECT_TRUE(cv::imencode(extension, image_, bytes));
    return {bytes.begin(), bytes.end()};
  }

  static std::string errorOf(const std::string& path, int64_t max_pixels) {
    try {
      readImageFile(path, cv::IMREAD_UNCHANGED, max_pixels);
    } catch (const std::runtime_error& error) {
      return error.what();
    }
    ADD_FAILURE() << "no error for " << path;
    return "";
  }

  fs::path root_;
  cv::Mat image_;
};

TEST_F(ImageFileTest, RealImagesDecodeAsOpenCvDecodesThem) {
  const cv::Mat png = readImageFile(write("frame.png", encoded(".png")), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(cv::norm(png, image_, cv::NORM_INF), 0.0);
  const std::string jpeg_path = write("frame.jpg", encoded(".jpg"));
  const cv::Mat jpeg = readImageFile(jpeg_path, cv::IMREAD_COLOR);
  EXPECT_EQ(cv::norm(jpeg, cv::imread(jpeg_path, cv::IMREAD_COLOR), cv::NORM_INF), 0.0);
  EXPECT_EQ(jpeg.size(), image_.size());
  EXPECT_EQ(jpeg.channels(), 3);
}

TEST_F(ImageFileTest, SmallFilesClaimingHugeImagesAreRefusedByTheirHeader) {
  // A JPEG of a few hundred bytes whose frame header claims 20000 x 20000:
  // libjpeg would decode it, grey where the data ends, into 400 megapixels.
  std::string jpeg = encoded(".jpg");
  const size_t height = jpeg.find("\xFF\xC0") + 5;
  jpeg.replace(height, 4, std::string("\x4E\x20\x4E\x20", 4));
  const std::string jpeg_path = write("bomb.jpg", jpeg);
  const std::string jpeg_error = errorOf(jpeg_path, kDefaultMaxImagePixels);
  EXPECT_NE(jpeg_error.find(jpeg_path), std::string::npos) << jpeg_error;
  EXPECT_NE(jpeg_error.find("JPEG header claims 20000 x 20000 pixels"), std::string::npos)
      << jpeg_error;
  EXPECT_NE(jpeg_error.find("limit of 64000000"), std::string::npos) << jpeg_error;
  // Its IHDR's checksum no longer matches: only the header is ever read.
  std::string png = encoded(".png");
  png.replace(16, 8, std::string("\x00\x00\x4E\x20\x00\x00\x4E\x20", 8));
  const std::string png_error = errorOf(write("bomb.png", png), kDefaultMaxImagePixels);
  EXPECT_NE(png_error.find("PNG header claims 20000 x 20000 pixels"), std::string::npos)
      << png_error;
}

TEST_F(ImageFileTest, TheLimitCountsPixels) {
  const std::string path = write("frame.png", encoded(".png"));
  EXPECT_EQ(readImageFile(path, cv::IMREAD_GRAYSCALE, 64 * 48).size(), image_.size());
  EXPECT_NE(errorOf(path, 64 * 48 - 1).find("claims 64 x 48 pixels"), std::string::npos);
}

TEST_F(ImageFileTest, MissingGarbageAndCorruptFilesAreNamedErrors) {
  const std::string missing = (root_ / "missing.png").string();
  EXPECT_EQ(errorOf(missing, kDefaultMaxImagePixels), "cannot open image '" + missing + "'");
  const std::string garbage = write("garbage.png", "not an image at all");
  EXPECT_NE(errorOf(garbage, kDefaultMaxImagePixels).find("image '" + garbage + "': not a PNG"),
            std::string::npos);
  const std::string truncated = write("truncated.png", encoded(".png").substr(0, 20));
  EXPECT_NE(errorOf(truncated, kDefaultMaxImagePixels).find("truncated PNG IHDR chunk"),
            std::string::npos);
  // A valid header over a body that does not decode.
  const std::string corrupt = write("corrupt.png", encoded(".png").substr(0, 40));
  EXPECT_EQ(errorOf(corrupt, kDefaultMaxImagePixels), "cannot read image '" + corrupt + "'");
}

// An image in memory (a message's JPEG) is bounded and named alike.
TEST_F(ImageFileTest, BytesInMemoryAreBoundedByTheirHeaderAndNamed) {
  const std::string png = encoded(".png");
  const auto decode = [](const std::string& bytes, int64_t max_pixels) {
    return decodeImageBytes(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(),
                            cv::IMREAD_UNCHANGED, "camera frame 7", max_pixels);
  };
  EXPECT_EQ(cv::norm(decode(png, kDefaultMaxImagePixels), image_, cv::NORM_INF), 0.0);
  const auto errorOfBytes = [&](const std::string& bytes, int64_t max_pixels) -> std::string {
    try {
      decode(bytes, max_pixels);
    } catch (const std::runtime_error& error) {
      return error.what();
    }
    return "no error";
  };
  EXPECT_NE(errorOfBytes(png, 64 * 48 - 1).find("image 'camera frame 7': its PNG header claims"),
            std::string::npos);
  EXPECT_NE(errorOfBytes("garbage", kDefaultMaxImagePixels).find("camera frame 7"),
            std::string::npos);
  EXPECT_EQ(errorOfBytes(png.substr(0, 40), kDefaultMaxImagePixels),
            "cannot decode image 'camera frame 7'");
}

}  // namespace
}  // namespace lineloc
