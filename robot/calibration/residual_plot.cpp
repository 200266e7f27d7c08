#include "robot/calibration/residual_plot.h"

#include <fmt/format.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace lineloc {

namespace {

const cv::Scalar kBackground(255, 255, 255);
const cv::Scalar kText(0, 0, 0);

// Distinct hues around the colour wheel, one per view.
cv::Scalar viewColour(size_t view, size_t views) {
  cv::Mat hsv(1, 1, CV_8UC3,
              cv::Scalar(static_cast<double>(180 * view / std::max<size_t>(views, 1)), 220, 200));
  cv::Mat bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  const cv::Vec3b colour = bgr.at<cv::Vec3b>(0, 0);
  return {static_cast<double>(colour[0]), static_cast<double>(colour[1]),
          static_cast<double>(colour[2])};
}

cv::Point2d toPoint(const Eigen::Vector2d& p) {
  return {p.x(), p.y()};
}

}  // namespace

cv::Mat drawResidualPlot(const PlanarViews& views,
                         const std::vector<std::vector<Eigen::Vector2d>>& residuals_px,
                         double magnification) {
  cv::Mat plot(views.image_height, views.image_width, CV_8UC3, kBackground);
  for (size_t view = 0; view < residuals_px.size(); ++view) {
    const cv::Scalar colour = viewColour(view, residuals_px.size());
    for (size_t i = 0; i < residuals_px[view].size(); ++i) {
      const Eigen::Vector2d& measured = views.image_points[view][i];
      cv::circle(plot, toPoint(measured), 1, colour, cv::FILLED, cv::LINE_AA);
      cv::line(plot, toPoint(measured), toPoint(measured + magnification * residuals_px[view][i]),
               colour, 1, cv::LINE_AA);
    }
  }
  const cv::Point bar_start(10, views.image_height - 10);
  cv::line(plot, bar_start, bar_start + cv::Point(static_cast<int>(magnification), 0), kText, 2);
  cv::putText(plot, fmt::format("1 px residual (x{:g})", magnification),
              bar_start + cv::Point(static_cast<int>(magnification) + 6, 4),
              cv::FONT_HERSHEY_SIMPLEX, 0.4, kText, 1, cv::LINE_AA);
  return plot;
}

void writeResidualPlot(const std::string& path, const PlanarViews& views,
                       const std::vector<std::vector<Eigen::Vector2d>>& residuals_px,
                       double magnification) {
  bool written = false;
  try {
    written = cv::imwrite(path, drawResidualPlot(views, residuals_px, magnification));
  } catch (const cv::Exception& error) {
    throw std::runtime_error(fmt::format("cannot write '{}': {}", path, error.what()));
  }
  if (!written) {
    throw std::runtime_error(fmt::format("cannot write residual plot '{}'", path));
  }
}

}  // namespace lineloc
