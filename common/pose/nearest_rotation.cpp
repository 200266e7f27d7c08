#include "common/pose/nearest_rotation.h"

#include <Eigen/LU>
#include <Eigen/SVD>

namespace lineloc {

Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& M) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  if ((U * svd.matrixV().transpose()).determinant() < 0.0) {
    U.col(2) = -U.col(2);
  }
  return U * svd.matrixV().transpose();
}

}  // namespace lineloc
