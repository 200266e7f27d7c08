// Image sizes read from the headers of images OpenCV encoded, of crafted
// headers claiming huge sizes, and of truncated and garbage files.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/image/image_header.h"

namespace lineloc {
namespace {

std::string encoded(const std::string& extension, int channels = 1) {
  cv::Mat image(23, 37, channels == 1 ? CV_8UC1 : CV_8UC3);
  cv::randu(image, 0, 255);
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(extension, image, bytes)) << extension;
  return {bytes.begin(), bytes.end()};
}

ImageHeader headerOf(const std::string& bytes) {
  std::istringstream in(bytes);
  return readImageHeader(in, "test image");
}

std::string headerError(const std::string& bytes) {
  try {
    headerOf(bytes);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

void putBigEndian16(std::string& bytes, size_t at, int value) {
  bytes[at] = static_cast<char>(value >> 8);
  bytes[at + 1] = static_cast<char>(value & 0xFF);
}

// The offset of the first JPEG frame header's height field.
size_t jpegHeightOffset(const std::string& jpeg) {
  const size_t sof = jpeg.find("\xFF\xC0");
  EXPECT_NE(sof, std::string::npos);
  return sof + 5;
}

TEST(ImageHeader, ReadsTheSizeOfEveryFormatOpenCvWrites) {
  for (const auto& [extension, format, channels] :
       std::vector<std::tuple<std::string, std::string, int>>{{".png", "PNG", 1},
                                                              {".png", "PNG", 3},
                                                              {".jpg", "JPEG", 1},
                                                              {".jpg", "JPEG", 3},
                                                              {".bmp", "BMP", 1},
                                                              {".bmp", "BMP", 3},
                                                              {".pgm", "Netpbm", 1},
                                                              {".ppm", "Netpbm", 3},
                                                              {".pbm", "Netpbm", 1}}) {
    const ImageHeader header = headerOf(encoded(extension, channels));
    EXPECT_EQ(header.format, format) << extension;
    EXPECT_EQ(header.width_px, 37) << extension;
    EXPECT_EQ(header.height_px, 23) << extension;
  }
}

TEST(ImageHeader, SkipsJpegSegmentsFillBytesAndNetpbmComments) {
  std::string jpeg = encoded(".jpg");
  // An APP1 segment of 1000 bytes, fill bytes and a stray byte before the next marker.
  std::string app1 = "\xFF\xE1";
  app1 += std::string("\x03\xE8", 2) + std::string(998, '\xFF');
  jpeg.insert(2, app1 + "\x42\xFF\xFF");
  EXPECT_EQ(headerOf(jpeg).width_px, 37);
  const ImageHeader pgm = headerOf("P5 # width\n# then height\n 640\t# more\n480 255\n");
  EXPECT_EQ(pgm.width_px, 640);
  EXPECT_EQ(pgm.height_px, 480);
}

// A '#' right after a number ends it, and what follows is the next number,
// as OpenCV decodes it: a header that hid a huge height behind it
// ("32000#32000") would otherwise pass as one row and be decoded at 1 GP,
// within OpenCV's own limit (CV_IO_MAX_IMAGE_PIXELS, 2^30).
TEST(ImageHeader, ANetpbmNumberEndsAtTheByteAfterItAsOpenCvReadsIt) {
  const std::string pgm = std::string("P5\n10#6\n255\n") + std::string(60, '\x07');
  EXPECT_EQ(headerOf(pgm).width_px, 10);
  EXPECT_EQ(headerOf(pgm).height_px, 6);
  const std::vector<uint8_t> bytes(pgm.begin(), pgm.end());
  const cv::Mat decoded = cv::imdecode(bytes, cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR);
  ASSERT_FALSE(decoded.empty());
  EXPECT_EQ(decoded.cols, 10);
  EXPECT_EQ(decoded.rows, 6);
  EXPECT_EQ(headerOf("P5 32000#32000\n1\n").height_px, 32000);
}

TEST(ImageHeader, CraftedHeadersGiveTheHugeSizeTheyClaim) {
  std::string jpeg = encoded(".jpg");
  putBigEndian16(jpeg, jpegHeightOffset(jpeg), 20000);
  putBigEndian16(jpeg, jpegHeightOffset(jpeg) + 2, 20000);
  EXPECT_EQ(headerOf(jpeg).width_px * headerOf(jpeg).height_px, 400'000'000);
  std::string png = encoded(".png");
  png.replace(16, 8, std::string("\x7F\xFF\xFF\xFF\x00\x01\x00\x00", 8));
  EXPECT_EQ(headerOf(png).width_px, 0x7FFFFFFF);
  EXPECT_EQ(headerOf(png).height_px, 65536);
  std::string bmp = encoded(".bmp");
  bmp.replace(18, 8, std::string("\x00\xCA\x9A\x3B\x00\x36\x65\xC4", 8));
  EXPECT_EQ(headerOf(bmp).width_px, 1'000'000'000);
  EXPECT_EQ(headerOf(bmp).height_px, 1'000'000'000) << "negative: rows stored top-down";
  EXPECT_EQ(headerOf("P6\n999999999 999999999\n255\n").width_px, 999999999);
}

TEST(ImageHeader, TruncatedHeadersAreNamedErrors) {
  for (const std::string extension : {".png", ".jpg", ".bmp", ".pgm"}) {
    const std::string image = encoded(extension);
    // Every prefix ending before the size has been read.
    const size_t size_end = extension == ".jpg"   ? jpegHeightOffset(image) + 4
                            : extension == ".pgm" ? 9
                                                  : 24;
    for (size_t length = 0; length < size_end; ++length) {
      const std::string message = headerError(image.substr(0, length));
      EXPECT_NE(message.find("image 'test image'"), std::string::npos)
          << extension << " cut at " << length << ": " << message;
    }
  }
}

TEST(ImageHeader, GarbageAndInvalidSizesAreNamedErrors) {
  EXPECT_NE(headerError("GIF89a...").find("not a PNG, JPEG, BMP or Netpbm"), std::string::npos);
  EXPECT_NE(headerError(std::string("\x89PNG\r\n\x1b\n", 8)).find("not a PNG"), std::string::npos);
  std::string png = encoded(".png");
  png.replace(16, 4, std::string(4, '\0'));
  EXPECT_NE(headerError(png).find("invalid size 0 x 23"), std::string::npos) << headerError(png);
  std::string bmp = encoded(".bmp");
  bmp.replace(22, 4, std::string("\x00\x00\x00\x80", 4));  // INT32_MIN rows
  EXPECT_NE(headerError(bmp).find("invalid size 37 x 2147483648"), std::string::npos)
      << headerError(bmp);
  png.replace(12, 4, "IDAT");
  EXPECT_NE(headerError(png).find("IHDR"), std::string::npos);
  std::string jpeg = encoded(".jpg");
  jpeg.replace(jpeg.find("\xFF\xC0"), 2, "\xFF\xDA");
  EXPECT_NE(headerError(jpeg).find("no frame header"), std::string::npos) << headerError(jpeg);
  EXPECT_NE(headerError(std::string("\xFF\xD8\xFF\xE0\x00\x01", 6)).find("length 1"),
            std::string::npos);
  EXPECT_NE(headerError("P5\n640 -480\n").find("no size"), std::string::npos);
  EXPECT_NE(headerError("P5\n99999999999 480\n").find("out of range"), std::string::npos);
}

}  // namespace
}  // namespace lineloc
