#include <gtest/gtest.h>

#include "sim/eval/evaluation_plot.h"
#include "tests/unit/sim/eval/circle_drive.h"

namespace lineloc {
namespace {

int countColour(const cv::Mat& image, const cv::Vec3b& colour) {
  int count = 0;
  for (int row = 0; row < image.rows; ++row) {
    for (int col = 0; col < image.cols; ++col) {
      count += image.at<cv::Vec3b>(row, col) == colour;
    }
  }
  return count;
}

TEST(EvaluationPlot, DrawsFootprintsBothTrajectoriesAndErrorGraphs) {
  const auto truth = circleDrive(10.0, 60.0);
  auto estimate = truth;
  for (StampedPose& pose : estimate) {
    pose.pose.translation().x() += 3.0;  // visibly apart from the truth
  }
  SceneMesh buildings;
  buildings.addBox(Eigen::Isometry3d::Identity(), Eigen::Vector3d(5.0, 5.0, 5.0),
                   SurfaceTag{SurfaceKind::kWall, 1, 0.0f, 10.0f});
  const EvaluationOptions options;
  const PlotLayout layout;
  const cv::Mat image = drawEvaluationPlot(
      truth, estimate, evaluateTrajectory(truth, estimate, options), options, &buildings, layout);
  ASSERT_EQ(image.type(), CV_8UC3);
  EXPECT_EQ(image.cols, layout.width_px);
  EXPECT_EQ(image.rows, layout.map_height_px + layout.graph_height_px);
  const cv::Mat map = image(cv::Rect(0, 0, layout.width_px, layout.map_height_px));
  // The 10 m box at the circle's centre: the map spans ~90 m over 800 px, so
  // ~ (10 * 800 / 90)^2 = 7,900 px of footprint grey.
  EXPECT_GT(countColour(map, {205, 205, 205}), 5000);
  EXPECT_GT(countColour(map, {40, 160, 40}), 1000);  // truth line
  EXPECT_GT(countColour(map, {30, 30, 220}), 500);   // estimate dots
  const cv::Mat graphs =
      image(cv::Rect(0, layout.map_height_px, layout.width_px, layout.graph_height_px));
  EXPECT_GT(countColour(graphs, {30, 30, 220}), 100);  // error series
  EXPECT_GT(countColour(graphs, {0, 140, 255}), 50);   // dashed target lines
}

}  // namespace
}  // namespace lineloc
