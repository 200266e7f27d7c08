#include "backbone/matching/line_matcher.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lineloc {

ProjectedPoint projectPoint(const Eigen::Vector3d& p_world,
                            const PoseWithCovariance& T_world_camera, const PinholeCamera& camera) {
  const Eigen::Matrix3d R = T_world_camera.pose.linear();
  const Eigen::Vector3d x = p_world - T_world_camera.pose.translation();
  const Eigen::Vector3d p_camera = R.transpose() * x;
  const double z = p_camera.z();
  Eigen::Matrix<double, 2, 3> d_pixel_d_camera;
  d_pixel_d_camera << camera.fx / z, camera.skew / z,
      -(camera.fx * p_camera.x() + camera.skew * p_camera.y()) / (z * z), 0.0, camera.fy / z,
      -camera.fy * p_camera.y() / (z * z);
  Eigen::Matrix<double, 3, 6> d_camera_d_error;
  d_camera_d_error << -R.transpose(), R.transpose() * skew(x);
  const Eigen::Matrix<double, 2, 6> J = d_pixel_d_camera * d_camera_d_error;
  return {camera.project(p_camera), J * T_world_camera.covariance * J.transpose()};
}

ProjectedSegment projectSegment(const Eigen::Vector3d& start_world,
                                const Eigen::Vector3d& end_world,
                                const PoseWithCovariance& T_world_camera,
                                const PinholeCamera& camera) {
  const ProjectedPoint start = projectPoint(start_world, T_world_camera, camera);
  const ProjectedPoint end = projectPoint(end_world, T_world_camera, camera);
  return {start.pixel, end.pixel, start.covariance, end.covariance};
}

namespace {

// A projected model segment in the form the gate reads: its line's direction
// and normal, its length, and the normal variance n^T Sigma n + floor^2 of
// each endpoint, which interpolates linearly along it as the covariance does.
struct GatedLine {
  Eigen::Vector2d start_px;
  Eigen::Vector2d direction;
  Eigen::Vector2d normal;
  double length_px = 0.0;
  double start_normal_variance = 0.0;
  double end_normal_variance = 0.0;
  int polarity = 0;
};

std::vector<GatedLine> gatedLines(const std::vector<VisibleSegment>& model,
                                  const PoseWithCovariance& T_world_camera,
                                  const PinholeCamera& camera, double floor_px) {
  const double floor_variance = floor_px * floor_px;
  std::vector<GatedLine> lines;
  lines.reserve(model.size());
  for (const VisibleSegment& segment : model) {
    const ProjectedSegment p =
        projectSegment(segment.start_world, segment.end_world, T_world_camera, camera);
    GatedLine line;
    line.start_px = p.start_px;
    line.length_px = (p.end_px - p.start_px).norm();
    line.direction = (p.end_px - p.start_px) / line.length_px;
    line.normal = {-line.direction.y(), line.direction.x()};
    line.start_normal_variance = line.normal.dot(p.start_covariance * line.normal) + floor_variance;
    line.end_normal_variance = line.normal.dot(p.end_covariance * line.normal) + floor_variance;
    line.polarity = segment.polarity;
    lines.push_back(line);
  }
  return lines;
}

// sum over the image segment's endpoints q_i of d_i^2 / (n^T (Sigma_q_i +
// Sigma_model(t_i)) n + floor^2), d_i = n . (q_i - start).
double gateChi2(const GatedLine& line, const ImageSegment& segment) {
  double chi2 = 0.0;
  for (const auto& [point, covariance] : {std::pair{&segment.start, &segment.start_covariance},
                                          std::pair{&segment.end, &segment.end_covariance}}) {
    const Eigen::Vector2d offset = point->cast<double>() - line.start_px;
    const double t = std::clamp(line.direction.dot(offset) / line.length_px, 0.0, 1.0);
    const double variance = line.normal.dot(covariance->cast<double>() * line.normal) +
                            (1.0 - t) * line.start_normal_variance + t * line.end_normal_variance;
    const double distance = line.normal.dot(offset);
    chi2 += distance * distance / variance;
  }
  return chi2;
}

// The lines' start test, in arrays a loop over all lines reads in step: the
// start q0 of an image segment lies too far from line m for the gate,
// whatever t, when d_0^2 / variance_0 > gate with variance_0 at most
// trace(Sigma_q0) plus the line's larger endpoint variance (floor included).
// Cheaper than the overlap, it turns away most pairs.
class StartGate {
 public:
  explicit StartGate(const std::vector<GatedLine>& lines) {
    for (const GatedLine& line : lines) {
      const bool usable = line.length_px >= 1e-9;
      normal_x_.push_back(line.normal.x());
      normal_y_.push_back(line.normal.y());
      offset_.push_back(line.normal.dot(line.start_px));
      // A line too short to have a direction passes no start.
      variance_.push_back(usable ? std::max(line.start_normal_variance, line.end_normal_variance)
                                 : -std::numeric_limits<double>::infinity());
    }
    passes_.resize(lines.size());
  }

  // For each line m, 1 when q0 (its covariance's trace `q0_variance_bound`)
  // may pass the gate, else 0; valid until the next call.
  const std::vector<double>& passing(const Eigen::Vector2d& q0, double q0_variance_bound,
                                     double gate_chi2) {
    const double* __restrict normal_x = normal_x_.data();
    const double* __restrict normal_y = normal_y_.data();
    const double* __restrict offset = offset_.data();
    const double* __restrict variance = variance_.data();
    double* __restrict passes = passes_.data();
    const double x = q0.x();
    const double y = q0.y();
    const size_t count = passes_.size();
    for (size_t m = 0; m < count; ++m) {
      const double distance = normal_x[m] * x + normal_y[m] * y - offset[m];
      passes[m] = distance * distance <= gate_chi2 * (q0_variance_bound + variance[m]) ? 1.0 : 0.0;
    }
    return passes_;
  }

 private:
  std::vector<double> normal_x_, normal_y_, offset_, variance_;
  // 1 or 0: doubles, so that the loop over the lines vectorizes.
  std::vector<double> passes_;
};

// Length of the image segment q0-q1's extent along the line that lies on it.
double overlapPx(const GatedLine& line, const Eigen::Vector2d& q0, const Eigen::Vector2d& q1) {
  const double t0 = line.direction.dot(q0 - line.start_px);
  const double t1 = line.direction.dot(q1 - line.start_px);
  return std::min(std::max(t0, t1), line.length_px) - std::max(std::min(t0, t1), 0.0);
}

// False when the model line and the image segment (q0 -> q1) both have a
// polarity and they differ once read along the line's direction.
bool polaritiesAgree(const GatedLine& line, const ImageSegment& segment, const Eigen::Vector2d& q0,
                     const Eigen::Vector2d& q1) {
  if (line.polarity == 0 || segment.polarity == 0) {
    return true;
  }
  const int along_line = line.direction.dot(q1 - q0) >= 0.0 ? segment.polarity : -segment.polarity;
  return along_line == line.polarity;
}

}  // namespace

std::vector<std::vector<LineMatch>> gateCandidates(const std::vector<ImageSegment>& image,
                                                   const std::vector<VisibleSegment>& model,
                                                   const PoseWithCovariance& T_world_camera,
                                                   const PinholeCamera& camera,
                                                   const MatchingOptions& options) {
  const std::vector<GatedLine> lines =
      gatedLines(model, T_world_camera, camera, options.model_sigma_floor_px);
  StartGate start_gate(lines);
  std::vector<std::vector<LineMatch>> candidates(image.size());
  for (size_t i = 0; i < image.size(); ++i) {
    const Eigen::Vector2d q0 = image[i].start.cast<double>();
    const Eigen::Vector2d q1 = image[i].end.cast<double>();
    const double image_length = (q1 - q0).norm();
    if (!(image_length >= 1e-9)) {
      continue;
    }
    const std::vector<double>& passing =
        start_gate.passing(q0, image[i].start_covariance.trace(), options.gate_chi2);
    for (size_t m = 0; m < lines.size(); ++m) {
      if (passing[m] == 0.0 ||
          overlapPx(lines[m], q0, q1) < options.min_overlap_fraction * image_length ||
          (options.use_polarity && !polaritiesAgree(lines[m], image[i], q0, q1))) {
        continue;
      }
      const double chi2 = gateChi2(lines[m], image[i]);
      if (chi2 <= options.gate_chi2) {
        candidates[i].push_back({static_cast<int>(i), static_cast<int>(m), chi2});
      }
    }
    std::sort(candidates[i].begin(), candidates[i].end(),
              [](const LineMatch& a, const LineMatch& b) { return a.chi2 < b.chi2; });
  }
  return candidates;
}

}  // namespace lineloc
