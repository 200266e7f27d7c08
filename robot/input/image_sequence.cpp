#include "robot/input/image_sequence.h"

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace fs = std::filesystem;

namespace lineloc {
namespace {

bool isImageFile(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
  return extension == ".png" || extension == ".jpg" || extension == ".jpeg" ||
         extension == ".pgm" || extension == ".bmp";
}

std::optional<int64_t> numericStamp(const fs::path& path) {
  const std::string stem = path.stem().string();
  if (stem.empty() || stem.size() > 18 ||
      stem.find_first_not_of("0123456789") != std::string::npos) {
    return std::nullopt;
  }
  return std::stoll(stem);
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
  std::vector<FrameRef> frames;
  std::string line;
  for (int line_number = 1; std::getline(stream, line); ++line_number) {
    const std::string row = trim(line);
    if (row.empty() || row[0] == '#') {
      continue;
    }
    const std::string where = fmt::format("{}:{}", csv.string(), line_number);
    const auto comma = row.find(',');
    const std::string stamp_text = trim(row.substr(0, comma));
    if (comma == std::string::npos || stamp_text.empty() ||
        stamp_text.find_first_not_of("0123456789") != std::string::npos ||
        stamp_text.size() > 18) {
      throw std::runtime_error(fmt::format("{}: expected 'timestamp_ns,filename'", where));
    }
    const int64_t stamp_ns = std::stoll(stamp_text);
    if (!frames.empty() && stamp_ns <= *frames.back().stamp_ns) {
      throw std::runtime_error(fmt::format("{}: timestamp does not increase", where));
    }
    const std::string file = trim(row.substr(comma + 1));
    if (file.empty() || file.find("..") != std::string::npos) {
      throw std::runtime_error(fmt::format("{}: bad file name '{}'", where, file));
    }
    frames.push_back({(camera_dir / "data" / file).string(), stamp_ns});
  }
  if (frames.empty()) {
    throw std::runtime_error(fmt::format("'{}' lists no frames", csv.string()));
  }
  return frames;
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
  const bool all_numeric = std::all_of(files.begin(), files.end(),
                                       [](const fs::path& p) { return numericStamp(p).has_value(); });
  std::vector<FrameRef> frames;
  for (const fs::path& file : files) {
    frames.push_back({file.string(), all_numeric ? numericStamp(file) : std::nullopt});
  }
  return frames;
}

}  // namespace

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
  cv::Mat image = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (image.empty()) {
    throw std::runtime_error(fmt::format("cannot read image '{}'", path));
  }
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
