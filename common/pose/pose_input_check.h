// Checks a PoseProblem before any estimate is attempted, so that hostile or
// degenerate input ends in a status naming what is wrong and where, never in a
// silent garbage pose: numbers (finite, within range), covariances (symmetric
// positive definite with bounded eigenvalues), segment lengths, and the model
// geometry (enough constraints; not all collinear; lines not all parallel or
// all through one point, which leave translation along a direction free).
#pragma once

#include <optional>
#include <string>

#include "common/pose/pose_problem.h"

namespace lineloc {

struct PoseFailure {
  PoseStatus status = PoseStatus::kInvalidInput;
  std::string message;
};

// Bounds of the accepted input, in the units of each quantity.
inline constexpr double kMaxAbsCoordinate = 1e8;          // metres and pixels
inline constexpr double kMinVariancePx2 = 1e-12;          // eigenvalue of a 2x2 covariance
inline constexpr double kMaxVariancePx2 = 1e12;           //
inline constexpr double kMinImageSegmentLengthPx = 1e-3;  // measured segment
inline constexpr double kMinModelSegmentLengthM = 1e-6;   // 3D model segment
inline constexpr double kRelativeDegeneracyTolerance = 1e-9;

// kInvalidInput for bad numbers, covariances or segment lengths.
std::optional<PoseFailure> checkPoseInput(const PoseProblem& problem);

// kNotEnoughCorrespondences when fewer than six scalar constraints (two per
// point, two per line); kDegenerate when all model points and endpoints are
// collinear, or the lines alone are all parallel or all concurrent.
std::optional<PoseFailure> checkPoseGeometry(const PoseProblem& problem);

}  // namespace lineloc
