#include <gtest/gtest.h>

#include "robot/calibration/planar_extrinsics.h"
#include "synthetic_views.h"

namespace lineloc {
namespace {

TEST(PlanarExtrinsics, RecoversPoseFromExactHomography) {
  const testing::SyntheticViews synthetic = testing::makeSyntheticViews(6, {}, 0.0, 1);
  const PinholeCamera& camera = synthetic.truth.calibration.camera;
  for (const Eigen::Isometry3d& T_true : synthetic.truth.T_camera_model) {
    // Any scale and sign of H gives the same pose.
    const Eigen::Matrix3d H = -3.7 * testing::viewHomography(camera, T_true);
    const Eigen::Isometry3d T = planePoseFromHomography(camera.K(), H);
    EXPECT_LT((T.linear() - T_true.linear()).norm(), 1e-12);
    EXPECT_LT((T.translation() - T_true.translation()).norm(), 1e-12);
  }
}

}  // namespace
}  // namespace lineloc
