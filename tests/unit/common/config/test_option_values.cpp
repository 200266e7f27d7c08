#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "common/config/option_values.h"

namespace lineloc {
namespace {

std::string errorOf(const std::function<void()>& parse) {
  try {
    parse();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(OptionValues, APointIsThreeNumbersOrNone) {
  EXPECT_FALSE(pointOption({}, "site_origin").has_value());
  EXPECT_EQ(pointOption({84900.0, 447600.0, 1.0}, "site_origin"),
            Eigen::Vector3d(84900.0, 447600.0, 1.0));
  EXPECT_EQ(errorOf([] {
              pointOption({84900.0, 447600.0}, "site_origin");
            }),
            "site_origin needs 3 numbers: x y z (got 2)");
}

TEST(OptionValues, APoseIsSevenNumbersWithAUnitQuaternion) {
  const double half = std::sqrt(0.5);
  const PoseWithCovariance pose =
      poseOption({1.0, 2.0, 1.5, 0.0, 0.0, half, half}, 0.5, 2.0, "predicted_pose");
  EXPECT_EQ(pose.pose.translation(), Eigen::Vector3d(1.0, 2.0, 1.5));
  EXPECT_TRUE(pose.pose.linear().isApprox(
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix()));
  EXPECT_DOUBLE_EQ(pose.covariance(0, 0), 0.25);
  EXPECT_NEAR(pose.covariance(5, 5), std::pow(2.0 * M_PI / 180.0, 2), 1e-15);
  EXPECT_NE(errorOf([] {
              poseOption({1.0, 2.0, 1.5, 0.0, 0.0, 0.0}, 0.5, 2.0, "predicted_pose");
            }).find("predicted_pose needs 7 numbers"),
            std::string::npos);
  EXPECT_NE(errorOf([] {
              poseOption({1, 2, 1.5, 0, 0, 0, 0.5}, 0.5, 2.0, "predicted_pose");
            }).find("not of unit norm"),
            std::string::npos);
}

TEST(OptionValues, TheSunIsAzimuthAndElevationOrUnknown) {
  EXPECT_FALSE(sunOption({}, 0.35, "sun").has_value());
  const std::optional<Sunlight> sun = sunOption({90.0, 0.0}, 0.35, "sun");
  ASSERT_TRUE(sun.has_value());
  EXPECT_NEAR((sun->direction_world - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-12) << "east";
  EXPECT_DOUBLE_EQ(sun->ambient_fraction, 0.35);
  EXPECT_EQ(errorOf([] { sunOption({90.0}, 0.35, "sun"); }),
            "sun needs 2 numbers: azimuth elevation (deg) (got 1)");
}

}  // namespace
}  // namespace lineloc
