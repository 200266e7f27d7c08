// The rotation nearest to a 3x3 matrix in the Frobenius norm: R = U diag(1, 1,
// det(U V^T)) V^T for M = U S V^T (Umeyama, "Least-squares estimation of
// transformation parameters between two point patterns", PAMI 1991, eq. 39-41),
// used to project the linear and planar starts' rotation estimates onto SO(3).
#pragma once

#include <Eigen/Core>

namespace lineloc {

Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& M);

}  // namespace lineloc
