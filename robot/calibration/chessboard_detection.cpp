#include "robot/calibration/chessboard_detection.h"

#include <fmt/format.h>
#include <glob.h>

#include <algorithm>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "common/config/size_pair.h"
#include "common/image/image_file.h"

namespace lineloc {

namespace {

// Sub-pixel refinement as in OpenCV's calibration sample: an 11x11 window,
// at most 30 iterations or a step below 1e-4 px.
const cv::Size kSubPixelWindow(11, 11);
const cv::TermCriteria kSubPixelCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 1e-4);

}  // namespace

ChessboardSize parseChessboardSize(const std::string& text) {
  const std::optional<SizePair> parsed = parseSizePair(text, 4);
  if (!parsed) {
    throw std::invalid_argument(
        fmt::format("board size '{}': expected COLUMNSxROWS of inner corners, e.g. 9x6", text));
  }
  const ChessboardSize size{parsed->first, parsed->second};
  if (size.columns < 2 || size.rows < 2) {
    throw std::invalid_argument(
        fmt::format("board size '{}': at least 2x2 inner corners are needed", text));
  }
  return size;
}

std::vector<std::string> expandImagePattern(const std::string& pattern) {
  glob_t matches{};
  const int status = glob(pattern.c_str(), 0, nullptr, &matches);
  std::vector<std::string> paths(matches.gl_pathv, matches.gl_pathv + matches.gl_pathc);
  globfree(&matches);
  if (status != 0 || paths.empty()) {
    throw std::runtime_error(fmt::format("no image matches '{}'", pattern));
  }
  std::sort(paths.begin(), paths.end());
  return paths;
}

std::vector<Eigen::Vector2d> chessboardModelPoints(ChessboardSize board, double square_m) {
  std::vector<Eigen::Vector2d> points;
  for (int row = 0; row < board.rows; ++row) {
    for (int column = 0; column < board.columns; ++column) {
      points.emplace_back(column * square_m, row * square_m);
    }
  }
  return points;
}

ChessboardViews detectChessboards(const std::vector<std::string>& image_paths, ChessboardSize board,
                                  double square_m) {
  struct Detection {
    std::string path;
    cv::Size size;
    std::vector<cv::Point2f> corners;
  };
  ChessboardViews result;
  std::vector<Detection> detections;
  std::map<std::pair<int, int>, int> views_per_size;
  const cv::Size pattern(board.columns, board.rows);
  for (const std::string& path : image_paths) {
    const cv::Mat grey = readImageFile(path, cv::IMREAD_GRAYSCALE);
    std::vector<cv::Point2f> corners;
    const bool found = cv::findChessboardCorners(
        grey, pattern, corners,
        cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_FAST_CHECK);
    if (!found) {
      result.images_without_board.push_back(path);
      continue;
    }
    cv::cornerSubPix(grey, corners, kSubPixelWindow, cv::Size(-1, -1), kSubPixelCriteria);
    ++views_per_size[{grey.cols, grey.rows}];
    detections.push_back({path, grey.size(), std::move(corners)});
  }
  if (detections.empty()) {
    return result;
  }
  // The camera's image size is the one most views have; views of other sizes
  // come from another camera.
  const auto most_common =
      std::max_element(views_per_size.begin(), views_per_size.end(),
                       [](const auto& a, const auto& b) { return a.second < b.second; });
  result.views.image_width = most_common->first.first;
  result.views.image_height = most_common->first.second;
  result.views.model_points = chessboardModelPoints(board, square_m);
  for (const Detection& detection : detections) {
    if (detection.size.width != result.views.image_width ||
        detection.size.height != result.views.image_height) {
      result.images_of_other_size.push_back(detection.path);
      continue;
    }
    std::vector<Eigen::Vector2d> image_points;
    for (const cv::Point2f& corner : detection.corners) {
      image_points.emplace_back(corner.x, corner.y);
    }
    result.views.image_points.push_back(std::move(image_points));
    result.images_with_board.push_back(detection.path);
  }
  return result;
}

}  // namespace lineloc
