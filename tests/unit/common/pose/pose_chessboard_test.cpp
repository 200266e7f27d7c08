// Real images: OpenCV's left*.jpg chessboard views (opencv-doc) with the
// intrinsics, distortion and per-view extrinsics of its left_intrinsics.yml.
// Corners are detected and refined as OpenCV's calibration sample does,
// undistorted to pixels of the same camera (the backbone's input), and the
// pose from the 54 coplanar corners (planar start + refinement) must reproduce
// the file's extrinsics within 1e-3 rad and 2e-4 m, as solvePnP ITERATIVE does
// within 8e-4 rad and 1.1e-4 m on the distorted corners.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "common/pose/pose_estimator.h"
#include "tests/unit/common/pose/opencv_pnp.h"
#include "tests/unit/common/pose/pose_test_scene.h"

namespace lineloc {
namespace {

constexpr double kRotationToleranceRad = 1e-3;
constexpr double kTranslationToleranceM = 2e-4;
const cv::Size kBoardSize(9, 6);

std::filesystem::path dataDir() {
  return LINELOC_OPENCV_DOC_DATA_DIR;
}

std::vector<cv::Point2f> detectCorners(const cv::Mat& gray) {
  std::vector<cv::Point2f> corners;
  if (!cv::findChessboardCorners(gray, kBoardSize, corners,
                                 cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE)) {
    return {};
  }
  cv::cornerSubPix(gray, corners, cv::Size(11, 11), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 1e-4));
  return corners;
}

TEST(ChessboardPoseTest, ReproducesOpenCvExtrinsics) {
  const std::filesystem::path intrinsics_path = dataDir() / "left_intrinsics.yml";
  ASSERT_TRUE(std::filesystem::exists(intrinsics_path))
      << intrinsics_path << " is missing: install Debian's opencv-doc";
  cv::FileStorage storage(intrinsics_path.string(), cv::FileStorage::READ);
  cv::Mat K;
  cv::Mat distortion;
  cv::Mat extrinsics;
  double square_size_m = 0.0;
  storage["camera_matrix"] >> K;
  storage["distortion_coefficients"] >> distortion;
  storage["extrinsic_parameters"] >> extrinsics;
  storage["square_size"] >> square_size_m;
  ASSERT_EQ(extrinsics.rows, 13);
  PinholeCamera camera;
  camera.fx = K.at<double>(0, 0);
  camera.fy = K.at<double>(1, 1);
  camera.cx = K.at<double>(0, 2);
  camera.cy = K.at<double>(1, 2);
  int view = 0;
  for (const int image_number : {1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14}) {
    const std::string name = cv::format("left%02d.jpg", image_number);
    const cv::Mat gray = cv::imread((dataDir() / name).string(), cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(gray.empty()) << name;
    const std::vector<cv::Point2f> corners = detectCorners(gray);
    ASSERT_EQ(corners.size(), 54u) << name;
    std::vector<cv::Point2f> undistorted;
    cv::undistortPoints(corners, undistorted, K, distortion, cv::noArray(), K);
    PoseProblem problem;
    problem.camera = camera;
    for (int i = 0; i < kBoardSize.height; ++i) {
      for (int j = 0; j < kBoardSize.width; ++j) {
        const cv::Point2f& pixel = undistorted[i * kBoardSize.width + j];
        problem.points.push_back({Eigen::Vector3d(j * square_size_m, i * square_size_m, 0.0),
                                  Eigen::Vector2d(pixel.x, pixel.y), Eigen::Matrix2d::Identity()});
      }
    }
    const PoseEstimate estimate = estimatePose(problem);
    ASSERT_EQ(estimate.status, PoseStatus::kConverged) << name << ": " << estimate.message;
    const Eigen::Isometry3d expected = test::worldCameraFromRvecTvec(
        {extrinsics.at<double>(view, 0), extrinsics.at<double>(view, 1),
         extrinsics.at<double>(view, 2)},
        {extrinsics.at<double>(view, 3), extrinsics.at<double>(view, 4),
         extrinsics.at<double>(view, 5)});
    // Compare T_camera_world, the quantity the file stores.
    const Eigen::Isometry3d T_camera_board = estimate.T_world_camera.pose.inverse();
    const Eigen::Isometry3d expected_T_camera_board = expected.inverse();
    EXPECT_LT(test::rotationErrorRad(T_camera_board, expected_T_camera_board),
              kRotationToleranceRad)
        << name;
    EXPECT_LT(test::translationErrorM(T_camera_board, expected_T_camera_board),
              kTranslationToleranceM)
        << name;
    ++view;
  }
}

}  // namespace
}  // namespace lineloc
