#include "backbone/visibility/visible_lines.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <span>

#include "common/camera/camera_frustum.h"
#include "common/parallel/parallel_for.h"

namespace lineloc {
namespace {

constexpr int kStateDimension = 3;
constexpr int kViewpoints = 2 * kStateDimension + 1;
// Runs of lines shared out among the threads: lines near occluders take
// several times longer to sample, so more runs than threads even the work out.
constexpr int kVisibilityChunks = 16;

// The camera centre and the sigma points of its position uncertainty; the
// centre alone for a position known exactly.
struct Viewpoints {
  std::array<Eigen::Vector3d, kViewpoints> points;
  int count = 1;
};

Viewpoints viewpoints(const PoseWithCovariance& T_world_camera) {
  Viewpoints viewpoints;
  const Eigen::Vector3d centre = T_world_camera.pose.translation();
  viewpoints.points.fill(centre);
  const Eigen::Matrix3d position_covariance = T_world_camera.covariance.topLeftCorner<3, 3>();
  if (position_covariance.isZero()) {
    return viewpoints;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(position_covariance);
  for (int i = 0; i < kStateDimension; ++i) {
    const double spread = std::sqrt(kStateDimension * std::max(0.0, eigen.eigenvalues()[i]));
    const Eigen::Vector3d offset = spread * eigen.eigenvectors().col(i);
    viewpoints.points[1 + 2 * i] = centre + offset;
    viewpoints.points[2 + 2 * i] = centre - offset;
  }
  viewpoints.count = kViewpoints;
  return viewpoints;
}

// Fraction of the viewpoints that see `point`, which the centre sees.
double visibleFraction(const OcclusionScene& scene, const Viewpoints& from,
                       const Eigen::Vector3d& point, double clearance_m) {
  const std::span<const Eigen::Vector3d> sigma_points(from.points.data() + 1,
                                                      static_cast<size_t>(from.count - 1));
  const int seen = 1 + scene.countClearPaths(sigma_points, point, clearance_m);
  return static_cast<double>(seen) / from.count;
}

// A ray towards the sun this long leaves every building of a map view behind.
constexpr double kSunRayLength_m = 2000.0;

// Whether the surfaces seen through two pixels may differ (see the header):
// false when both rays meet faces of one building that share an orientation
// or, under a known sun, receive the same light.
class ContrastProbe {
 public:
  ContrastProbe(const OcclusionScene& scene, const Eigen::Isometry3d& T_world_camera,
                const PinholeCamera& camera, const VisibilityOptions& options)
      : scene_(scene),
        T_world_camera_(T_world_camera),
        K_inverse_(camera.K().inverse()),
        same_plane_cos_(std::cos(options.same_plane_angle_rad)),
        sunlight_(options.sunlight),
        min_irradiance_difference_(options.min_irradiance_difference),
        surface_clearance_m_(options.surface_clearance_m) {}

  bool differ(const Eigen::Vector2d& pixel_a, const Eigen::Vector2d& pixel_b) const {
    const std::optional<SeenSurface> a = surfaceAt(pixel_a);
    const std::optional<SeenSurface> b = surfaceAt(pixel_b);
    if (!a || !b || a->building_id != b->building_id) {
      return true;
    }
    return std::abs(a->seen_normal.dot(b->seen_normal)) < same_plane_cos_ && !litAlike(*a, *b);
  }

 private:
  // Where a ray meets a face, with the unit normal of the side the ray sees.
  struct SeenSurface {
    Eigen::Vector3d point_world;
    Eigen::Vector3d seen_normal;
    int64_t building_id;
  };

  std::optional<SeenSurface> surfaceAt(const Eigen::Vector2d& pixel) const {
    const Eigen::Vector3d ray_world =
        (T_world_camera_.linear() * (K_inverse_ * pixel.homogeneous())).normalized();
    const std::optional<SurfaceHit> hit =
        scene_.firstSurface(T_world_camera_.translation(), ray_world);
    if (!hit) {
      return std::nullopt;
    }
    const double facing = hit->unit_normal.dot(ray_world) < 0.0 ? 1.0 : -1.0;
    return SeenSurface{T_world_camera_.translation() + hit->distance_m * ray_world,
                       facing * hit->unit_normal, hit->building_id};
  }

  // E(n) of sunlight.h, in shadow where a face stands between the surface and
  // the sun (cast only for a surface that faces the sun).
  double irradiance(const SeenSurface& surface) const {
    const Eigen::Vector3d& towards_sun = sunlight_->direction_world;
    const bool in_shadow = surface.seen_normal.dot(towards_sun) > 0.0 &&
                           scene_.blocked(surface.point_world + kSunRayLength_m * towards_sun,
                                          surface.point_world, surface_clearance_m_);
    return sunlight_->irradiance(surface.seen_normal, in_shadow);
  }

  bool litAlike(const SeenSurface& a, const SeenSurface& b) const {
    return sunlight_ && std::abs(irradiance(a) - irradiance(b)) < min_irradiance_difference_;
  }

  const OcclusionScene& scene_;
  const Eigen::Isometry3d& T_world_camera_;
  Eigen::Matrix3d K_inverse_;
  double same_plane_cos_;
  std::optional<Sunlight> sunlight_;
  double min_irradiance_difference_;
  double surface_clearance_m_;
};

HalfSpaces visibilityFrustum(const PinholeCamera& camera, const VisibilityOptions& options) {
  return cameraFrustum(camera, options.near_m, options.far_m, options.image_margin_px);
}

bool clipTo(const HalfSpaces& frustum, Eigen::Vector3d& start_camera, Eigen::Vector3d& end_camera) {
  const auto interval = clipSegment(frustum, start_camera, end_camera);
  if (!interval) {
    return false;
  }
  const Eigen::Vector3d direction = end_camera - start_camera;
  end_camera = start_camera + (*interval)[1] * direction;
  start_camera = start_camera + (*interval)[0] * direction;
  return true;
}

// Samples a line clipped to the frustum every sample_spacing_px, keeps the
// samples the camera centre sees where the line can show as an edge, weighs
// each by the fraction of viewpoints that see it, and cuts the line into runs
// of kept samples.
class LineSampler {
 public:
  LineSampler(const OcclusionScene& scene, const PoseWithCovariance& T_world_camera,
              const PinholeCamera& camera, const VisibilityOptions& options)
      : scene_(scene),
        T_world_camera_(T_world_camera.pose),
        camera_(camera),
        options_(options),
        viewpoints_(viewpoints(T_world_camera)),
        contrast_(scene, T_world_camera.pose, camera, options) {}

  void appendVisiblePieces(const ModelSegment& line, const Eigen::Vector3d& a_camera,
                           const Eigen::Vector3d& b_camera,
                           std::vector<VisibleSegment>& visible) const {
    const Eigen::Vector2d a_px = camera_.project(a_camera);
    const Eigen::Vector2d b_px = camera_.project(b_camera);
    const double length_px = (b_px - a_px).norm();
    if (length_px < options_.min_visible_length_px) {
      return;
    }
    const ProbedLine probed{a_camera, b_camera,
                            options_.contrast_probe_px *
                                Eigen::Vector2d(a_px.y() - b_px.y(), b_px.x() - a_px.x()) /
                                length_px,
                            options_.contrast_probe_px / length_px};
    const int samples =
        std::clamp(static_cast<int>(std::ceil(length_px / options_.sample_spacing_px)) + 1, 2,
                   options_.max_samples_per_line);
    const double step_px = length_px / (samples - 1);
    const auto at = [&](int i) {
      return T_world_camera_ *
             (a_camera + (b_camera - a_camera) * (static_cast<double>(i) / (samples - 1)));
    };
    int run_start = -1;
    double run_weight = 0.0;
    for (int i = 0; i <= samples; ++i) {
      const double fraction =
          i < samples ? sampleFraction(probed, at(i), static_cast<double>(i) / (samples - 1)) : 0.0;
      if (fraction > 0.0) {
        run_start = run_start < 0 ? i : run_start;
        run_weight += fraction;
        continue;
      }
      if (run_start >= 0 && (i - 1 - run_start) * step_px >= options_.min_visible_length_px) {
        visible.push_back(
            {line.id, line.kind, at(run_start), at(i - 1), run_weight / (i - run_start)});
      }
      run_start = -1;
      run_weight = 0.0;
    }
  }

 private:
  // A clipped line (camera frame) with its contrast probes' offset normal to
  // it (pixels) and their inset from its ends (fraction of its length), where
  // it meets a face's corner.
  struct ProbedLine {
    Eigen::Vector3d a_camera;
    Eigen::Vector3d b_camera;
    Eigen::Vector2d probe_offset_px;
    double probe_inset;
  };

  // The fraction of viewpoints that see the line's point p_world at t; 0
  // where the centre does not, or where the line cannot show as an edge.
  double sampleFraction(const ProbedLine& line, const Eigen::Vector3d& p_world, double t) const {
    if (scene_.blocked(viewpoints_.points[0], p_world, options_.surface_clearance_m)) {
      return 0.0;
    }
    const double t_probe = std::clamp(t, line.probe_inset, 1.0 - line.probe_inset);
    const Eigen::Vector2d p_px =
        camera_.project(line.a_camera + (line.b_camera - line.a_camera) * t_probe);
    if (!contrast_.differ(p_px + line.probe_offset_px, p_px - line.probe_offset_px)) {
      return 0.0;
    }
    return visibleFraction(scene_, viewpoints_, p_world, options_.surface_clearance_m);
  }

  const OcclusionScene& scene_;
  const Eigen::Isometry3d& T_world_camera_;
  const PinholeCamera& camera_;
  const VisibilityOptions& options_;
  Viewpoints viewpoints_;
  ContrastProbe contrast_;
};

}  // namespace

bool clipToFrustum(Eigen::Vector3d& start_camera, Eigen::Vector3d& end_camera,
                   const PinholeCamera& camera, const VisibilityOptions& options) {
  return clipTo(visibilityFrustum(camera, options), start_camera, end_camera);
}

std::vector<VisibleSegment> visibleSegments(const std::vector<ModelSegment>& lines,
                                            const OcclusionScene& scene,
                                            const PoseWithCovariance& T_world_camera,
                                            const PinholeCamera& camera,
                                            const VisibilityOptions& options) {
  const LineSampler sampler(scene, T_world_camera, camera, options);
  const Eigen::Isometry3d T_camera_world = T_world_camera.pose.inverse();
  const HalfSpaces frustum = visibilityFrustum(camera, options);
  // Consecutive runs of lines, one run's pieces per chunk, so the pieces keep
  // the lines' order whatever thread samples them.
  const int chunks = options.threads == 1 ? 1 : kVisibilityChunks;
  const size_t lines_per_chunk = (lines.size() + chunks - 1) / chunks;
  std::vector<std::vector<VisibleSegment>> pieces(chunks);
  parallelFor(chunks, options.threads, [&](int chunk) {
    const size_t end = std::min(lines.size(), (chunk + 1) * lines_per_chunk);
    for (size_t i = chunk * lines_per_chunk; i < end; ++i) {
      Eigen::Vector3d a = T_camera_world * lines[i].start_world;
      Eigen::Vector3d b = T_camera_world * lines[i].end_world;
      if (clipTo(frustum, a, b)) {
        sampler.appendVisiblePieces(lines[i], a, b, pieces[chunk]);
      }
    }
  });
  std::vector<VisibleSegment> visible;
  for (const std::vector<VisibleSegment>& chunk : pieces) {
    visible.insert(visible.end(), chunk.begin(), chunk.end());
  }
  return visible;
}

}  // namespace lineloc
