#include "sim/eval/evaluation_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

namespace lineloc {
namespace {

const cv::Scalar kBackground(255, 255, 255);
const cv::Scalar kFootprint(205, 205, 205);
const cv::Scalar kTruthColour(40, 160, 40);     // green (BGR)
const cv::Scalar kEstimateColour(30, 30, 220);  // red
const cv::Scalar kThresholdColour(0, 140, 255);
const cv::Scalar kInk(40, 40, 40);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kNsPerSecond = 1e9;

// World xy -> pixel in the map panel: uniform scale, y up.
class MapProjection {
 public:
  MapProjection(const Eigen::AlignedBox2d& bounds, const cv::Size& panel) {
    scale_ = std::min(panel.width / bounds.sizes().x(), panel.height / bounds.sizes().y());
    origin_ = bounds.center();
    centre_ = cv::Point2d(panel.width / 2.0, panel.height / 2.0);
  }
  cv::Point operator()(const Eigen::Vector2d& xy) const {
    const Eigen::Vector2d d = (xy - origin_) * scale_;
    return {static_cast<int>(std::lround(centre_.x + d.x())),
            static_cast<int>(std::lround(centre_.y - d.y()))};
  }
  double pixelsPerMetre() const { return scale_; }

 private:
  double scale_;
  Eigen::Vector2d origin_;
  cv::Point2d centre_;
};

std::vector<cv::Point> polyline(const std::vector<StampedPose>& poses, const MapProjection& map) {
  std::vector<cv::Point> points;
  for (const StampedPose& pose : poses) {
    points.push_back(map(pose.pose.translation().head<2>()));
  }
  return points;
}

void drawFootprints(cv::Mat& panel, const SceneMesh& buildings, const MapProjection& map) {
  for (size_t i = 0; i < buildings.triangleCount(); ++i) {
    const SurfaceKind kind = buildings.tag(i).kind;
    if (kind != SurfaceKind::kWall && kind != SurfaceKind::kRoof) {
      continue;
    }
    cv::Point corners[3];
    for (int k = 0; k < 3; ++k) {
      corners[k] = map(buildings.vertices()[3 * i + k].head<2>().cast<double>());
    }
    cv::fillConvexPoly(panel, corners, 3, kFootprint, cv::LINE_AA);
  }
}

void drawScaleBar(cv::Mat& panel, const MapProjection& map) {
  // The round length (1, 2 or 5 x 10^k m) closest to a fifth of the panel.
  const double target_m = panel.cols / 5.0 / map.pixelsPerMetre();
  const double decade = std::pow(10.0, std::floor(std::log10(target_m)));
  double length_m = decade;
  for (const double step : {2.0, 5.0}) {
    if (step * decade <= target_m) {
      length_m = step * decade;
    }
  }
  const int length_px = static_cast<int>(std::lround(length_m * map.pixelsPerMetre()));
  const cv::Point start(20, panel.rows - 20);
  cv::line(panel, start, start + cv::Point(length_px, 0), kInk, 3);
  cv::putText(panel, fmt::format("{:g} m", length_m), start + cv::Point(0, -10), kFont, 0.6, kInk,
              1, cv::LINE_AA);
}

void drawMap(cv::Mat& panel, const std::vector<StampedPose>& ground_truth,
             const std::vector<StampedPose>& estimate, const SceneMesh* buildings,
             double margin_m) {
  Eigen::AlignedBox2d bounds;
  for (const auto* poses : {&ground_truth, &estimate}) {
    for (const StampedPose& pose : *poses) {
      bounds.extend(pose.pose.translation().head<2>());
    }
  }
  bounds.extend(bounds.min() - Eigen::Vector2d::Constant(margin_m));
  bounds.extend(bounds.max() + Eigen::Vector2d::Constant(margin_m));
  const MapProjection map(bounds, panel.size());
  if (buildings != nullptr) {
    drawFootprints(panel, *buildings, map);
  }
  for (const cv::Point& point : polyline(estimate, map)) {
    cv::circle(panel, point, 3, kEstimateColour, cv::FILLED, cv::LINE_AA);
  }
  // The truth on top, thinner, so both show where they overlap.
  cv::polylines(panel, polyline(ground_truth, map), false, kTruthColour, 2, cv::LINE_AA);
  if (!ground_truth.empty()) {
    cv::circle(panel, map(ground_truth.front().pose.translation().head<2>()), 8, kTruthColour, 2,
               cv::LINE_AA);
  }
  cv::putText(panel, "ground truth (start: circle)", {20, 30}, kFont, 0.7, kTruthColour, 2,
              cv::LINE_AA);
  cv::putText(panel, "estimate", {20, 60}, kFont, 0.7, kEstimateColour, 2, cv::LINE_AA);
  drawScaleBar(panel, map);
}

// One error series over time, with its target as a dashed line.
void drawSeries(cv::Mat& panel, const std::vector<double>& times_s,
                const std::vector<double>& values, double threshold, const std::string& title) {
  const cv::Rect plot(70, 40, panel.cols - 100, panel.rows - 80);
  cv::rectangle(panel, plot, kInk, 1);
  cv::putText(panel, title, {plot.x, 25}, kFont, 0.6, kInk, 1, cv::LINE_AA);
  if (times_s.empty()) {
    return;
  }
  const double t0 = times_s.front();
  const double span_s = std::max(times_s.back() - t0, 1e-3);
  const double top =
      std::max(2.0 * threshold, 1.1 * *std::max_element(values.begin(), values.end()));
  const auto point = [&](double t, double value) {
    return cv::Point(
        plot.x + static_cast<int>((t - t0) / span_s * plot.width),
        plot.y + plot.height - static_cast<int>(std::min(value, top) / top * plot.height));
  };
  for (int x = plot.x; x < plot.x + plot.width; x += 12) {
    const int y = point(t0, threshold).y;
    cv::line(panel, {x, y}, {std::min(x + 6, plot.x + plot.width), y}, kThresholdColour, 1);
  }
  std::vector<cv::Point> points;
  for (size_t i = 0; i < times_s.size(); ++i) {
    points.push_back(point(times_s[i], values[i]));
  }
  cv::polylines(panel, points, false, kEstimateColour, 1, cv::LINE_8);
  cv::putText(panel, fmt::format("{:.3g}", top), {5, plot.y + 10}, kFont, 0.45, kInk, 1,
              cv::LINE_AA);
  cv::putText(panel, "0", {50, plot.y + plot.height}, kFont, 0.45, kInk, 1, cv::LINE_AA);
  cv::putText(panel, fmt::format("{:.1f} s", span_s), {plot.x + plot.width - 60, panel.rows - 15},
              kFont, 0.45, kInk, 1, cv::LINE_AA);
}

}  // namespace

cv::Mat drawEvaluationPlot(const std::vector<StampedPose>& ground_truth,
                           const std::vector<StampedPose>& estimate,
                           const TrajectoryEvaluation& evaluation, const EvaluationOptions& options,
                           const SceneMesh* buildings, const PlotLayout& layout) {
  cv::Mat image(layout.map_height_px + layout.graph_height_px, layout.width_px, CV_8UC3,
                kBackground);
  cv::Mat map_panel = image(cv::Rect(0, 0, layout.width_px, layout.map_height_px));
  drawMap(map_panel, ground_truth, estimate, buildings, layout.map_margin_m);
  std::vector<double> times_s;
  std::vector<double> position_m;
  std::vector<double> rotation_deg;
  for (const FrameError& frame : evaluation.frames) {
    times_s.push_back(static_cast<double>(frame.stamp_ns) / kNsPerSecond);
    position_m.push_back(frame.position_error_m.norm());
    rotation_deg.push_back(frame.rotation_error_rad * 180.0 / std::numbers::pi);
  }
  const int half = layout.width_px / 2;
  cv::Mat position_panel = image(cv::Rect(0, layout.map_height_px, half, layout.graph_height_px));
  cv::Mat rotation_panel =
      image(cv::Rect(half, layout.map_height_px, layout.width_px - half, layout.graph_height_px));
  drawSeries(position_panel, times_s, position_m, options.position_threshold_m,
             "position error [m] over time (dashed: target)");
  drawSeries(rotation_panel, times_s, rotation_deg,
             options.rotation_threshold_rad * 180.0 / std::numbers::pi,
             "attitude error [deg] over time (dashed: target)");
  return image;
}

}  // namespace lineloc
