// The front end's line segments on real photographs against the line
// detectors a user would pick instead (OpenCV's LSD, ximgproc's
// FastLineDetector and EdgeDrawing's EDLines), scored on the York Urban Line
// Segment Database's training split (Denis, Elder & Estrada, ECCV 2008;
// ../shared/data/york_urban_train: 640x480 images P*.jpg, hand-labelled
// Manhattan segments P*_lines.txt, 1-based pixel coordinates).
//
// Score by pixels (../shared/data/README.md): the labelled and the detected
// segments are drawn as 8-connected 1 px lines; a detected pixel is correct
// when a labelled pixel lies within max_distance (2 px), a labelled pixel is
// found when a detected pixel does. Counts are pooled over the images:
//   P = correct / detected pixels,  R = found / labelled pixels,
//   F = 2 P R / (P + R).
// The labels hold only Manhattan lines, so P is a lower bound.
// Every detector runs with its default options, the same on every image, on
// one thread; time = median over the images of one call's wall time.
// Scores are printed for all images and for the first and second halves in
// name order (the first half: the images thresholds may be tuned on).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "robot/vision/features/feature_extractor.h"

namespace {

namespace fs = std::filesystem;

constexpr double kMaxDistancePx = 2.0;
// York Urban's camera (its documentation): no distortion model is given.
constexpr double kFocalLengthPx = 674.918;
constexpr double kPrincipalPointXPx = 307.551;
constexpr double kPrincipalPointYPx = 251.454;

using Segments = std::vector<cv::Vec4f>;  // x1 y1 x2 y2, pixel centres at integers

struct LabelledImage {
  std::string name;
  cv::Mat grey;
  Segments labelled;
};

Segments readLabels(const fs::path& path) {
  std::ifstream in(path);
  if (!in) {
    throw std::runtime_error("cannot read " + path.string());
  }
  Segments segments;
  float x1, y1, x2, y2;
  while (in >> x1 >> y1 >> x2 >> y2) {
    segments.push_back({x1 - 1.0f, y1 - 1.0f, x2 - 1.0f, y2 - 1.0f});
  }
  if (!in.eof()) {
    throw std::runtime_error("malformed segment in " + path.string());
  }
  return segments;
}

std::vector<LabelledImage> readDataset(const fs::path& folder) {
  if (!fs::is_directory(folder)) {
    throw std::runtime_error("York Urban images missing: " + folder.string() +
                             " (set LINELOC_SHARED_DATA_DIR)");
  }
  std::vector<fs::path> images;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() == ".jpg") {
      images.push_back(entry.path());
    }
  }
  std::sort(images.begin(), images.end());
  std::vector<LabelledImage> dataset;
  for (const fs::path& image : images) {
    LabelledImage labelled{
        image.stem().string(), cv::imread(image.string(), cv::IMREAD_GRAYSCALE), {}};
    if (labelled.grey.empty()) {
      throw std::runtime_error("cannot read " + image.string());
    }
    fs::path labels = image;
    labels.replace_filename(image.stem().string() + "_lines.txt");
    labelled.labelled = readLabels(labels);
    dataset.push_back(std::move(labelled));
  }
  if (dataset.empty()) {
    throw std::runtime_error("no images in " + folder.string());
  }
  return dataset;
}

cv::Mat drawSegments(const Segments& segments, cv::Size size) {
  constexpr int kShift = 4;
  constexpr float kScale = 1 << kShift;
  cv::Mat pixels = cv::Mat::zeros(size, CV_8U);
  for (const cv::Vec4f& s : segments) {
    cv::line(pixels, cv::Point(cvRound(s[0] * kScale), cvRound(s[1] * kScale)),
             cv::Point(cvRound(s[2] * kScale), cvRound(s[3] * kScale)), 255, 1, cv::LINE_8, kShift);
  }
  return pixels;
}

struct PixelCounts {
  double detected = 0, correct = 0, labelled = 0, found = 0;
  PixelCounts& operator+=(const PixelCounts& o) {
    detected += o.detected;
    correct += o.correct;
    labelled += o.labelled;
    found += o.found;
    return *this;
  }
  double precision() const { return detected > 0 ? correct / detected : 0.0; }
  double recall() const { return labelled > 0 ? found / labelled : 0.0; }
  double f() const {
    const double p = precision(), r = recall();
    return p + r > 0 ? 2 * p * r / (p + r) : 0.0;
  }
};

// Pixels of `from` within kMaxDistancePx of a pixel of `to`, and all of `from`'s.
std::pair<double, double> near(const cv::Mat& from, const cv::Mat& to) {
  cv::Mat distance;
  cv::distanceTransform(255 - to, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  double within = 0, all = 0;
  for (int y = 0; y < from.rows; ++y) {
    const uint8_t* f = from.ptr<uint8_t>(y);
    const float* d = distance.ptr<float>(y);
    for (int x = 0; x < from.cols; ++x) {
      if (f[x] != 0) {
        ++all;
        within += d[x] <= kMaxDistancePx ? 1 : 0;
      }
    }
  }
  return {within, all};
}

PixelCounts score(const Segments& labelled, const Segments& detected, cv::Size size) {
  const cv::Mat labelled_pixels = drawSegments(labelled, size);
  const cv::Mat detected_pixels = drawSegments(detected, size);
  PixelCounts counts;
  std::tie(counts.correct, counts.detected) = near(detected_pixels, labelled_pixels);
  std::tie(counts.found, counts.labelled) = near(labelled_pixels, detected_pixels);
  return counts;
}

using Detector = std::function<Segments(const cv::Mat& grey)>;

struct NamedDetector {
  std::string name;
  Detector detect;
};

Detector lineloc(const lineloc::FeatureExtractorOptions& options, cv::Size size) {
  lineloc::CameraCalibration calibration;
  calibration.camera = {kFocalLengthPx, kFocalLengthPx, kPrincipalPointXPx, kPrincipalPointYPx, 0.0,
                        size.width,     size.height};
  auto extractor = std::make_shared<lineloc::FeatureExtractor>(calibration, options);
  return [extractor](const cv::Mat& grey) {
    Segments segments;
    for (const lineloc::ImageSegment& s : extractor->extract(grey).segments) {
      segments.push_back({s.start.x(), s.start.y(), s.end.x(), s.end.y()});
    }
    return segments;
  };
}

std::vector<NamedDetector> detectors(cv::Size size) {
  lineloc::FeatureExtractorOptions lines_only;
  lines_only.detect_corners = false;
  lineloc::FeatureExtractorOptions robot = lineloc::trackingFrontEndOptions();
  robot.detect_corners = false;
  const cv::Ptr<cv::LineSegmentDetector> lsd = cv::createLineSegmentDetector(cv::LSD_REFINE_STD);
  const cv::Ptr<cv::ximgproc::FastLineDetector> fld = cv::ximgproc::createFastLineDetector();
  const cv::Ptr<cv::ximgproc::EdgeDrawing> ed = cv::ximgproc::createEdgeDrawing();
  return {
      {"lineloc default", lineloc(lines_only, size)},
      {"lineloc robot", lineloc(robot, size)},
      {"OpenCV LSD",
       [lsd](const cv::Mat& grey) {
         Segments lines;
         lsd->detect(grey, lines);
         return lines;
       }},
      {"ximgproc FLD",
       [fld](const cv::Mat& grey) {
         Segments lines;
         fld->detect(grey, lines);
         return lines;
       }},
      {"EDLines",
       [ed](const cv::Mat& grey) {
         Segments lines;
         ed->detectEdges(grey);
         ed->detectLines(lines);
         return lines;
       }},
  };
}

struct ImageResult {
  PixelCounts counts;
  double time_ms;
  size_t segments;
};

void printRow(const std::string& name, const std::vector<ImageResult>& results, size_t begin,
              size_t end) {
  PixelCounts total;
  std::vector<double> times;
  double segments = 0;
  for (size_t i = begin; i < end; ++i) {
    total += results[i].counts;
    times.push_back(results[i].time_ms);
    segments += static_cast<double>(results[i].segments);
  }
  std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
  fmt::print("  {:<16} {:6.3f} {:6.3f} {:6.3f} {:8.2f} ms {:7.1f}\n", name, total.precision(),
             total.recall(), total.f(), times[times.size() / 2],
             segments / static_cast<double>(end - begin));
}

}  // namespace

int main() {
  try {
    cv::setNumThreads(1);
    const std::vector<LabelledImage> dataset =
        readDataset(fs::path(LINELOC_SHARED_DATA_DIR) / "york_urban_train");
    const cv::Size size = dataset.front().grey.size();
    const std::vector<NamedDetector> all = detectors(size);
    std::vector<std::vector<ImageResult>> results(all.size());
    for (size_t d = 0; d < all.size(); ++d) {
      for (const LabelledImage& image : dataset) {
        if (image.grey.size() != size) {
          throw std::runtime_error(image.name + " is not the size of the first image");
        }
        all[d].detect(image.grey);  // warm caches and buffers
        const auto start = std::chrono::steady_clock::now();
        const Segments detected = all[d].detect(image.grey);
        const std::chrono::duration<double, std::milli> elapsed =
            std::chrono::steady_clock::now() - start;
        results[d].push_back(
            {score(image.labelled, detected, size), elapsed.count(), detected.size()});
      }
    }
    const size_t half = dataset.size() / 2;
    const struct {
      std::string title;
      size_t begin, end;
    } subsets[] = {
        {fmt::format("all {} images", dataset.size()), 0, dataset.size()},
        {fmt::format("first {} (tuning)", half), 0, half},
        {fmt::format("last {} (held out)", dataset.size() - half), half, dataset.size()}};
    for (const auto& subset : subsets) {
      fmt::print(
          "\nYork Urban, {}: pixel precision, recall, F within {} px; median time per "
          "image; segments per image\n",
          subset.title, kMaxDistancePx);
      fmt::print("  {:<16} {:>6} {:>6} {:>6} {:>11} {:>7}\n", "detector", "P", "R", "F", "time",
                 "lines");
      for (size_t d = 0; d < all.size(); ++d) {
        printRow(all[d].name, results[d], subset.begin, subset.end);
      }
    }
    return 0;
  } catch (const std::exception& error) {
    fmt::print(stderr, "bench_york_urban: {}\n", error.what());
    return 1;
  }
}
