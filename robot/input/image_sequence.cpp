#include "robot/input/image_sequence.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "common/image/image_file.h"

namespace fs = std::filesystem;

namespace lineloc {
namespace {

bool isImageFile(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
  return extension == ".png" || extension == ".jpg" || extension == ".jpeg" ||
         extension == ".pgm" || extension == ".bmp";
}

// A non-negative decimal integer that fits int64 nanoseconds, or nullopt.
std::optional<int64_t> parseStampNs(const std::string& text) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
    return std::nullopt;
  }
  int64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) {
    return std::nullopt;
  }
  return value;
}

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  const auto last = text.find_last_not_of(" \t\r");
  return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

std::vector<FrameRef> readEurocCamera(const fs::path& camera_dir) {
  const fs::path csv = camera_dir / "data.csv";
  std::ifstream stream(csv);
  if (!stream) {
    throw std::runtime_error(fmt::format("cannot open '{}'", csv.string()));
  }
  return parseEurocCameraCsv(stream, csv.string(), (camera_dir / "data").string());
}

std::vector<FrameRef> readImageFolder(const fs::path& folder) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.is_regular_file() && isImageFile(entry.path())) {
      files.push_back(entry.path());
    }
  }
  if (files.empty()) {
    throw std::runtime_error(fmt::format("'{}' holds no images", folder.string()));
  }
  std::sort(files.begin(), files.end());
  const bool all_numeric = std::all_of(files.begin(), files.end(), [](const fs::path& p) {
    return parseStampNs(p.stem().string()).has_value();
  });
  std::vector<FrameRef> frames;
  for (const fs::path& file : files) {
    frames.push_back(
        {file.string(), all_numeric ? parseStampNs(file.stem().string()) : std::nullopt});
  }
  return frames;
}

}  // namespace

std::vector<FrameRef> parseEurocCameraCsv(std::istream& stream, const std::string& source,
                                          const std::string& data_dir) {
  std::vector<FrameRef> frames;
  std::string line;
  for (int line_number = 1; std::getline(stream, line); ++line_number) {
    const std::string row = trim(line);
    if (row.empty() || row[0] == '#') {
      continue;
    }
    const std::string where = fmt::format("{}:{}", source, line_number);
    const auto comma = row.find(',');
    const std::optional<int64_t> stamp_ns =
        comma == std::string::npos ? std::nullopt : parseStampNs(trim(row.substr(0, comma)));
    if (!stamp_ns) {
      throw std::runtime_error(fmt::format("{}: expected 'timestamp_ns,filename'", where));
    }
    if (!frames.empty() && *stamp_ns <= *frames.back().stamp_ns) {
      throw std::runtime_error(fmt::format("{}: timestamp does not increase", where));
    }
    const std::string file = trim(row.substr(comma + 1));
    if (file.empty() || file.find("..") != std::string::npos || file.front() == '/') {
      throw std::runtime_error(fmt::format("{}: bad file name '{}'", where, file));
    }
    frames.push_back({(fs::path(data_dir) / file).string(), stamp_ns});
  }
  if (frames.empty()) {
    throw std::runtime_error(fmt::format("'{}' lists no frames", source));
  }
  return frames;
}

std::vector<FrameRef> listImageSequence(const std::string& path) {
  const fs::path root(path);
  if (!fs::is_directory(root)) {
    throw std::runtime_error(fmt::format("image sequence '{}' is not a folder", path));
  }
  if (fs::is_regular_file(root / "cam0" / "data.csv")) {
    return readEurocCamera(root / "cam0");
  }
  if (fs::is_regular_file(root / "data.csv")) {
    return readEurocCamera(root);
  }
  return readImageFolder(root);
}

cv::Mat readGreyImage(const std::string& path) {
  cv::Mat image = readImageFile(path, cv::IMREAD_UNCHANGED);
  if (image.depth() != CV_8U) {
    throw std::runtime_error(fmt::format("image '{}' is not 8-bit", path));
  }
  if (image.channels() == 1) {
    return image;
  }
  cv::Mat grey;
  cv::cvtColor(image, grey, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return grey;
}

}  // namespace lineloc
