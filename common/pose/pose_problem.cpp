#include "common/pose/pose_problem.h"

namespace lineloc {

const char* toString(PoseStatus status) {
  switch (status) {
    case PoseStatus::kConverged:
      return "converged";
    case PoseStatus::kInvalidInput:
      return "invalid input";
    case PoseStatus::kNotEnoughCorrespondences:
      return "not enough correspondences";
    case PoseStatus::kDegenerate:
      return "degenerate configuration";
    case PoseStatus::kAmbiguous:
      return "ambiguous";
    case PoseStatus::kBehindCamera:
      return "behind the camera";
    case PoseStatus::kDiverged:
      return "diverged";
    case PoseStatus::kIterationLimit:
      return "iteration limit";
    case PoseStatus::kInconsistent:
      return "inconsistent";
  }
  return "unknown";
}

PoseEstimate poseFailure(PoseStatus status, std::string message) {
  PoseEstimate estimate;
  estimate.status = status;
  estimate.message = std::move(message);
  return estimate;
}

}  // namespace lineloc
