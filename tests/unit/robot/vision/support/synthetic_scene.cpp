#include "synthetic_scene.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

namespace lineloc::testing {
namespace {

constexpr int kShiftBits = 8;

// Image point p -> fine-grid pixel coordinates (p + 1/2) s - 1/2, in fixed point.
cv::Point toFixedPoint(const Eigen::Vector2d& p, int s) {
  const double scale = 1 << kShiftBits;
  return {static_cast<int>(std::lround(((p.x() + 0.5) * s - 0.5) * scale)),
          static_cast<int>(std::lround(((p.y() + 0.5) * s - 0.5) * scale))};
}

ScenePolygon rectangle(const Eigen::Vector2d& centre, double width, double height, double angle,
                       double grey) {
  const Eigen::Vector2d u(std::cos(angle), std::sin(angle));
  const Eigen::Vector2d v(-u.y(), u.x());
  const Eigen::Vector2d a = 0.5 * width * u;
  const Eigen::Vector2d b = 0.5 * height * v;
  return {{centre - a - b, centre + a - b, centre + a + b, centre - a + b}, grey};
}

}  // namespace

SyntheticScene renderPolygons(const SceneOptions& options, double background_grey,
                              const std::vector<ScenePolygon>& polygons, uint32_t seed) {
  const int s = options.supersampling;
  cv::Mat fine(options.size.height * s, options.size.width * s, CV_8UC1,
               cv::Scalar(background_grey));
  SyntheticScene scene;
  for (const ScenePolygon& polygon : polygons) {
    std::vector<cv::Point> points;
    for (const Eigen::Vector2d& vertex : polygon.vertices) {
      points.push_back(toFixedPoint(vertex, s));
    }
    cv::fillPoly(fine, std::vector<std::vector<cv::Point>>{points}, cv::Scalar(polygon.grey),
                 cv::LINE_8, kShiftBits);
    const size_t n = polygon.vertices.size();
    for (size_t i = 0; i < n; ++i) {
      scene.segments.push_back({polygon.vertices[i], polygon.vertices[(i + 1) % n]});
      scene.corners.push_back(polygon.vertices[i]);
    }
  }
  cv::Mat coarse;
  cv::resize(fine, coarse, options.size, 0.0, 0.0, cv::INTER_AREA);
  cv::Mat blurred;
  coarse.convertTo(blurred, CV_32F);
  if (options.blur_sigma_px > 0.0) {
    cv::GaussianBlur(blurred, blurred, cv::Size(0, 0), options.blur_sigma_px);
  }
  cv::Mat noise(options.size, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, options.noise_sigma);
  blurred += noise;
  blurred.convertTo(scene.image, CV_8U);
  return scene;
}

SyntheticScene renderRectangles(const SceneOptions& options, int count, uint32_t seed,
                                const SideRange& sides) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  constexpr double kMarginPx = 8.0;
  std::vector<ScenePolygon> polygons;
  std::vector<std::pair<Eigen::Vector2d, double>> discs;
  for (int attempt = 0; attempt < 2000 && static_cast<int>(polygons.size()) < count; ++attempt) {
    const double width = sides.min_px + (sides.max_px - sides.min_px) * unit(random);
    const double height = sides.min_px + (sides.max_px - sides.min_px) * unit(random);
    const double radius = 0.5 * std::hypot(width, height);
    const Eigen::Vector2d centre(
        radius + kMarginPx + unit(random) * (options.size.width - 2 * (radius + kMarginPx)),
        radius + kMarginPx + unit(random) * (options.size.height - 2 * (radius + kMarginPx)));
    const bool clear = std::all_of(discs.begin(), discs.end(), [&](const auto& disc) {
      return (disc.first - centre).norm() > disc.second + radius + kMarginPx;
    });
    if (!clear || centre.x() < radius || centre.y() < radius) {
      continue;
    }
    const double grey =
        unit(random) < 0.5 ? 30.0 + 50.0 * unit(random) : 180.0 + 50.0 * unit(random);
    polygons.push_back(rectangle(centre, width, height, M_PI * unit(random), grey));
    discs.emplace_back(centre, radius);
  }
  return renderPolygons(options, 128.0, polygons, seed);
}

}  // namespace lineloc::testing
