#include "backbone/visibility/visible_lines.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>

#include "common/camera/camera_frustum.h"
#include "common/parallel/parallel_for.h"
#include "db/citymodel/line_extraction.h"

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

// What the probes either side of a model line predict: whether it can show as
// an edge, which side is brighter where the model tells, and which side the
// line's own façade is on (see the header). Sides: +1 the left (image, y
// down), -1 the right, 0 unknown or both.
struct ProbedEdge {
  bool differ = false;
  int polarity = 0;
  int facade_side = 0;
};

// Whether the surfaces seen through two pixels may differ (see the header):
// false when both rays meet faces of one building that share an orientation
// or, under a known sun, receive the same light. Which side is brighter: the
// sky (a ray upwards that meets no face) against a face.
class ContrastProbe {
 public:
  ContrastProbe(const OcclusionScene& scene, const Eigen::Isometry3d& T_world_camera,
                const PinholeCamera& camera, const VisibilityOptions& options)
      : scene_(scene),
        T_world_camera_(T_world_camera),
        K_inverse_(camera.K().inverse()),
        same_plane_cos_(std::cos(options.same_plane_angle_rad)),
        facade_depth_ratio_(options.facade_depth_ratio),
        sunlight_(options.sunlight),
        min_irradiance_difference_(options.min_irradiance_difference),
        surface_clearance_m_(options.surface_clearance_m) {}

  ProbedEdge probe(const Eigen::Vector2d& left_px, const Eigen::Vector2d& right_px) const {
    const Eigen::Vector3d left_ray = rayThrough(left_px);
    const Eigen::Vector3d right_ray = rayThrough(right_px);
    const std::optional<SeenSurface> left = surfaceAlong(left_ray);
    const std::optional<SeenSurface> right = surfaceAlong(right_ray);
    const int facade_side = nearerSide(left, right);
    if (!left || !right) {
      return {true, skySide(left_ray, left.has_value(), right_ray, right.has_value()), facade_side};
    }
    if (left->building_id != right->building_id) {
      return {true, 0, facade_side};
    }
    if (std::abs(left->seen_normal.dot(right->seen_normal)) >= same_plane_cos_) {
      return {false, 0, 0};
    }
    return {!litAlike(*left, *right), 0, facade_side};
  }

 private:
  // Where a ray meets a face, with the unit normal of the side the ray sees.
  struct SeenSurface {
    Eigen::Vector3d point_world;
    Eigen::Vector3d seen_normal;
    int64_t building_id;
    double distance_m;
  };

  Eigen::Vector3d rayThrough(const Eigen::Vector2d& pixel) const {
    return (T_world_camera_.linear() * (K_inverse_ * pixel.homogeneous())).normalized();
  }

  std::optional<SeenSurface> surfaceAlong(const Eigen::Vector3d& ray_world) const {
    const std::optional<SurfaceHit> hit =
        scene_.firstSurface(T_world_camera_.translation(), ray_world);
    if (!hit) {
      return std::nullopt;
    }
    const double facing = hit->unit_normal.dot(ray_world) < 0.0 ? 1.0 : -1.0;
    return SeenSurface{T_world_camera_.translation() + hit->distance_m * ray_world,
                       facing * hit->unit_normal, hit->building_id, hit->distance_m};
  }

  // The side whose ray meets a face where the other's meets none, or one
  // farther by facade_depth_ratio: the line's own façade. 0 for two faces at
  // about one depth (a crease) or none.
  int nearerSide(const std::optional<SeenSurface>& left,
                 const std::optional<SeenSurface>& right) const {
    const double left_m = left ? left->distance_m : std::numeric_limits<double>::infinity();
    const double right_m = right ? right->distance_m : std::numeric_limits<double>::infinity();
    if (left_m * facade_depth_ratio_ < right_m) {
      return 1;
    }
    return right_m * facade_depth_ratio_ < left_m ? -1 : 0;
  }

  // +1 when the left side sees the sky (a ray upwards that meets no face) and
  // the right a face, -1 for the converse; 0 otherwise (the ground, or things
  // the model lacks, may lie on a side that meets no face).
  static int skySide(const Eigen::Vector3d& left_ray, bool left_meets_face,
                     const Eigen::Vector3d& right_ray, bool right_meets_face) {
    if (!left_meets_face && left_ray.z() > 0.0 && right_meets_face) {
      return 1;
    }
    return !right_meets_face && right_ray.z() > 0.0 && left_meets_face ? -1 : 0;
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
  double facade_depth_ratio_;
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

// A model line in the camera frame, clipped to the frustum: a -> b, and
// whether each is still the line's own end.
struct ClippedLine {
  Eigen::Vector3d a_camera;
  Eigen::Vector3d b_camera;
  bool a_is_start = false;
  bool b_is_end = false;
};

std::optional<ClippedLine> clipLine(const HalfSpaces& frustum,
                                    const Eigen::Isometry3d& T_camera_world,
                                    const ModelSegment& line) {
  const Eigen::Vector3d start_camera = T_camera_world * line.start_world;
  const Eigen::Vector3d end_camera = T_camera_world * line.end_world;
  ClippedLine clipped{start_camera, end_camera};
  if (!clipTo(frustum, clipped.a_camera, clipped.b_camera)) {
    return std::nullopt;
  }
  // An end the frustum keeps moves by rounding only (t = 0 or 1).
  constexpr double kSameEndM = 1e-6;
  clipped.a_is_start = (clipped.a_camera - start_camera).norm() < kSameEndM;
  clipped.b_is_end = (clipped.b_camera - end_camera).norm() < kSameEndM;
  return clipped;
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

  void appendVisiblePieces(const ModelSegment& line, const ClippedLine& clipped,
                           std::vector<VisibleSegment>& visible) const {
    const Eigen::Vector3d& a_camera = clipped.a_camera;
    const Eigen::Vector3d& b_camera = clipped.b_camera;
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
                            options_.contrast_probe_px / length_px,
                            line.kind == static_cast<int>(citymodel::LineKind::kLearnt)};
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
    SideVotes polarity_votes;
    SideVotes facade_side_votes;
    for (int i = 0; i <= samples; ++i) {
      const SampledPoint sampled =
          i < samples ? samplePoint(probed, at(i), static_cast<double>(i) / (samples - 1))
                      : SampledPoint{};
      if (sampled.fraction > 0.0) {
        run_start = run_start < 0 ? i : run_start;
        run_weight += sampled.fraction;
        polarity_votes.add(sampled.polarity);
        facade_side_votes.add(sampled.facade_side);
        continue;
      }
      if (run_start >= 0 && (i - 1 - run_start) * step_px >= options_.min_visible_length_px) {
        visible.push_back({line.id, line.kind, at(run_start), at(i - 1),
                           run_weight / (i - run_start), polarity_votes.side(),
                           facade_side_votes.side(), clipped.a_is_start && run_start == 0,
                           clipped.b_is_end && i == samples, line.sigma_m});
      }
      run_start = -1;
      run_weight = 0.0;
      polarity_votes = {};
      facade_side_votes = {};
    }
  }

 private:
  // A clipped line (camera frame) with its contrast probes' offset normal to
  // it (pixels) and their inset from its ends (fraction of its length), where
  // it meets a face's corner; a painted line (a learnt one) needs no probe.
  struct ProbedLine {
    Eigen::Vector3d a_camera;
    Eigen::Vector3d b_camera;
    Eigen::Vector2d probe_offset_px;
    double probe_inset;
    bool painted;
  };

  struct SampledPoint {
    double fraction = 0.0;
    int polarity = 0;
    int facade_side = 0;
  };

  // A piece's polarity or façade side: the one every one of its samples
  // predicts. A silhouette has the sky behind it above the horizon and the
  // ground below, where it shows the other polarity or none.
  struct SideVotes {
    int samples = 0;
    int left = 0;
    int right = 0;
    void add(int side) {
      ++samples;
      left += side > 0 ? 1 : 0;
      right += side < 0 ? 1 : 0;
    }
    int side() const {
      if (left == samples) {
        return 1;
      }
      return right == samples ? -1 : 0;
    }
  };

  // The fraction of viewpoints that see the line's point p_world at t (0
  // where the centre does not, or where the line cannot show as an edge), and
  // the polarity the probes predict there. probe_offset_px points to the
  // right of a -> b (image, y down).
  SampledPoint samplePoint(const ProbedLine& line, const Eigen::Vector3d& p_world, double t) const {
    if (scene_.blocked(viewpoints_.points[0], p_world, options_.surface_clearance_m)) {
      return {};
    }
    if (line.painted) {
      return {visibleFraction(scene_, viewpoints_, p_world, options_.surface_clearance_m), 0, 0};
    }
    const double t_probe = std::clamp(t, line.probe_inset, 1.0 - line.probe_inset);
    const Eigen::Vector2d p_px =
        camera_.project(line.a_camera + (line.b_camera - line.a_camera) * t_probe);
    const ProbedEdge edge =
        contrast_.probe(p_px - line.probe_offset_px, p_px + line.probe_offset_px);
    if (!edge.differ) {
      return {};
    }
    return {visibleFraction(scene_, viewpoints_, p_world, options_.surface_clearance_m),
            options_.predict_polarity ? edge.polarity : 0, edge.facade_side};
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
      const std::optional<ClippedLine> clipped = clipLine(frustum, T_camera_world, lines[i]);
      if (clipped) {
        sampler.appendVisiblePieces(lines[i], *clipped, pieces[chunk]);
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
