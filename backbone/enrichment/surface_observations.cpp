#include "backbone/enrichment/surface_observations.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <optional>

namespace lineloc {
namespace {

// Whether a visible model line, projected, lies along the segment (see the
// header).
bool explains(const Eigen::Vector2d& line_a, const Eigen::Vector2d& line_b,
              const Eigen::Vector2d& start, const Eigen::Vector2d& end,
              const SurfaceObservationOptions& options) {
  const Eigen::Vector2d along = line_b - line_a;
  const double length = along.norm();
  if (length < 1e-9) {
    return false;
  }
  const Eigen::Vector2d unit = along / length;
  const Eigen::Vector2d direction = (end - start).normalized();
  if (std::abs(unit.x() * direction.y() - unit.y() * direction.x()) >
      std::sin(options.explained_angle_rad)) {
    return false;
  }
  const Eigen::Vector2d normal(-unit.y(), unit.x());
  if (std::abs(normal.dot(start - line_a)) > options.explained_distance_px ||
      std::abs(normal.dot(end - line_a)) > options.explained_distance_px) {
    return false;
  }
  const double s0 = unit.dot(start - line_a), s1 = unit.dot(end - line_a);
  return std::max(s0, s1) > 0.0 && std::min(s0, s1) < length;
}

// The unit direction in the plane across a line through `point` along
// `direction`, and P = I - r n^T / (n . r): a ray from `camera` through the
// point, moved by d, meets the plane moved by P d.
struct WallProjection {
  Eigen::Vector3d across_line;
  Eigen::Matrix3d P;
};

WallProjection wallProjection(const Eigen::Vector3d& camera, const Plane& plane,
                              const Eigen::Vector3d& point, const Eigen::Vector3d& direction) {
  const Eigen::Vector3d& n = plane.normal;
  const Eigen::Vector3d ray = (point - camera).normalized();
  return {n.cross(direction).normalized(),
          Eigen::Matrix3d::Identity() - ray * n.transpose() / n.dot(ray)};
}

// A ray towards the sun this long leaves every building of a map view behind;
// shadow probes start this far off the wall.
constexpr double kSunRayLength_m = 2000.0;
constexpr double kProbeLift_m = 0.02;

class SurfacePlacer {
 public:
  SurfacePlacer(const EnrichmentFrame& frame, const OcclusionScene& scene,
                const SurfaceObservationOptions& options)
      : frame_(frame),
        scene_(scene),
        options_(options),
        K_inverse_(frame.camera.K().inverse()),
        T_camera_world_(frame.T_world_camera.pose.inverse()) {
    for (const VisibleSegment& line : frame.visible) {
      const Eigen::Vector3d a = T_camera_world_ * line.start_world;
      const Eigen::Vector3d b = T_camera_world_ * line.end_world;
      if (a.z() > 0.0 && b.z() > 0.0) {
        projected_.emplace_back(frame.camera.project(a), frame.camera.project(b));
      }
    }
  }

  bool explained(const Eigen::Vector2d& start, const Eigen::Vector2d& end) const {
    return std::any_of(projected_.begin(), projected_.end(), [&](const auto& line) {
      return explains(line.first, line.second, start, end, options_);
    });
  }

  // The standard deviations of the placed segment's place across the line, in
  // its plane, that the pose causes and that pose and pixels cause together
  // (see the header).
  struct PlacementSigmas {
    double pose_m = 0.0;
    double total_m = 0.0;
  };
  PlacementSigmas placementSigmas(const SurfaceSegment& placed, const Eigen::Vector3d& middle,
                                  const ImageSegment& segment) const {
    const Eigen::Vector3d direction = placed.end_world - placed.start_world;
    const WallProjection wall =
        wallProjection(frame_.T_world_camera.pose.translation(), placed.plane, middle, direction);
    // A pixel across the segment moves the ray at depth d by d / f that way.
    const Eigen::Vector2f image_direction = (segment.end - segment.start).normalized();
    const Eigen::Vector2f image_normal(-image_direction.y(), image_direction.x());
    const double pixel_variance =
        0.5 * static_cast<double>(image_normal.dot(segment.start_covariance * image_normal) +
                                  image_normal.dot(segment.end_covariance * image_normal));
    const double depth = (middle - frame_.T_world_camera.pose.translation()).norm();
    const Eigen::Vector3d pixel_ray_move =
        frame_.T_world_camera.pose.linear() *
        Eigen::Vector3d(image_normal.x() / frame_.camera.fx, image_normal.y() / frame_.camera.fy,
                        0.0) *
        depth;
    const double pixel_moves = wall.across_line.dot(wall.P * pixel_ray_move);
    const double pose_sigma =
        posePlacementSigma(frame_.T_world_camera, placed.plane, middle, direction);
    return {pose_sigma,
            std::sqrt(pose_sigma * pose_sigma + pixel_moves * pixel_moves * pixel_variance)};
  }

  // Whether one side of the placed segment is lit and the other in a shadow
  // the model casts (see the header).
  bool onCastShadowBoundary(const SurfaceSegment& placed) const {
    if (!frame_.towards_sun_world) {
      return false;
    }
    const Eigen::Vector3d& sun = *frame_.towards_sun_world;
    const Eigen::Vector3d middle = 0.5 * (placed.start_world + placed.end_world);
    const Eigen::Vector3d camera = frame_.T_world_camera.pose.translation();
    const Eigen::Vector3d seen_normal = placed.plane.normal.dot(camera - middle) > 0.0
                                            ? placed.plane.normal
                                            : Eigen::Vector3d(-placed.plane.normal);
    if (seen_normal.dot(sun) <= 0.0) {
      return false;  // the whole wall faces away from the sun
    }
    const Eigen::Vector3d across =
        placed.plane.normal.cross(placed.end_world - placed.start_world).normalized();
    const auto lit = [&](double side) {
      const Eigen::Vector3d point =
          middle + side * options_.shadow_probe_m * across + kProbeLift_m * seen_normal;
      return !scene_.blocked(point + kSunRayLength_m * sun, point, 0.5 * kProbeLift_m);
    };
    return lit(1.0) != lit(-1.0);
  }

  std::optional<SurfaceSegment> place(const ImageSegment& segment) const {
    const Eigen::Vector2d start = segment.start.cast<double>();
    const Eigen::Vector2d end = segment.end.cast<double>();
    const std::optional<SurfaceHit> a = hitThrough(start + 0.1 * (end - start));
    const std::optional<SurfaceHit> b = hitThrough(end + 0.1 * (start - end));
    if (!a || !b || a->building_id != b->building_id ||
        a->unit_normal.dot(b->unit_normal) < std::cos(options_.plane_angle_rad)) {
      return std::nullopt;
    }
    const Eigen::Vector3d point_a = pointOf(start + 0.1 * (end - start), a->distance_m);
    const Eigen::Vector3d point_b = pointOf(end + 0.1 * (start - end), b->distance_m);
    if (std::abs(a->unit_normal.dot(point_b - point_a)) > options_.plane_offset_m ||
        std::abs(b->unit_normal.dot(point_a - point_b)) > options_.plane_offset_m) {
      return std::nullopt;
    }
    SurfaceSegment placed;
    placed.building_id = a->building_id;
    placed.plane = {a->unit_normal, a->unit_normal.dot(point_a)};
    const std::optional<Eigen::Vector3d> start_world = onPlane(start, placed.plane);
    const std::optional<Eigen::Vector3d> end_world = onPlane(end, placed.plane);
    const std::optional<Eigen::Vector3d> middle = onPlane(0.5 * (start + end), placed.plane);
    if (!start_world || !end_world || !middle) {
      return std::nullopt;
    }
    placed.start_world = *start_world;
    placed.end_world = *end_world;
    placed.depth_m = (*middle - frame_.T_world_camera.pose.translation()).norm();
    const PlacementSigmas sigmas = placementSigmas(placed, *middle, segment);
    placed.placement_sigma_m = sigmas.total_m;
    placed.pose_placement_sigma_m = sigmas.pose_m;
    if (segment.polarity != 0) {
      // Left of start -> end in an image with y down is (d.y, -d.x).
      const Eigen::Vector2d direction = (end - start).normalized();
      const Eigen::Vector2d left(direction.y(), -direction.x());
      if (const std::optional<Eigen::Vector3d> beside =
              onPlane(0.5 * (start + end) + left, placed.plane)) {
        const Eigen::Vector3d line = (placed.end_world - placed.start_world).normalized();
        Eigen::Vector3d across = *beside - *middle;
        across -= across.dot(line) * line;
        across -= across.dot(placed.plane.normal) * placed.plane.normal;
        if (across.norm() > 0.0) {
          placed.brighter_side = segment.polarity * across.normalized();
        }
      }
    }
    return placed;
  }

 private:
  Eigen::Vector3d rayThrough(const Eigen::Vector2d& pixel) const {
    return (frame_.T_world_camera.pose.linear() * (K_inverse_ * pixel.homogeneous())).normalized();
  }

  std::optional<SurfaceHit> hitThrough(const Eigen::Vector2d& pixel) const {
    return scene_.firstSurface(frame_.T_world_camera.pose.translation(), rayThrough(pixel));
  }

  Eigen::Vector3d pointOf(const Eigen::Vector2d& pixel, double distance_m) const {
    return frame_.T_world_camera.pose.translation() + distance_m * rayThrough(pixel);
  }

  // Where the ray through `pixel` meets the plane in front of the camera.
  std::optional<Eigen::Vector3d> onPlane(const Eigen::Vector2d& pixel, const Plane& plane) const {
    const Eigen::Vector3d origin = frame_.T_world_camera.pose.translation();
    const Eigen::Vector3d ray = rayThrough(pixel);
    const double denominator = plane.normal.dot(ray);
    if (std::abs(denominator) < 1e-6) {
      return std::nullopt;
    }
    const double distance = (plane.offset - plane.normal.dot(origin)) / denominator;
    if (!(distance > 0.0)) {
      return std::nullopt;
    }
    return origin + distance * ray;
  }

  const EnrichmentFrame& frame_;
  const OcclusionScene& scene_;
  const SurfaceObservationOptions& options_;
  Eigen::Matrix3d K_inverse_;
  Eigen::Isometry3d T_camera_world_;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> projected_;
};

}  // namespace

double posePlacementSigma(const PoseWithCovariance& T_world_camera, const Plane& plane,
                          const Eigen::Vector3d& point, const Eigen::Vector3d& direction) {
  const Eigen::Vector3d camera = T_world_camera.pose.translation();
  const WallProjection wall = wallProjection(camera, plane, point, direction);
  // A pose error e = [dp; dtheta] moves the ray at X by J e, J = [I, -[X - t]x].
  Eigen::Matrix<double, 3, 6> J;
  J << Eigen::Matrix3d::Identity(), -skew(point - camera);
  const Eigen::Matrix<double, 1, 6> moves = wall.across_line.transpose() * wall.P * J;
  return std::sqrt((moves * T_world_camera.covariance * moves.transpose())(0, 0));
}

SurfaceObservations observeSurfaceSegments(const EnrichmentFrame& frame,
                                           const OcclusionScene& scene,
                                           const SurfaceObservationOptions& options) {
  SurfaceObservations observations;
  const SurfacePlacer placer(frame, scene, options);
  for (const ImageSegment& segment : frame.segments) {
    const Eigen::Vector2d start = segment.start.cast<double>();
    const Eigen::Vector2d end = segment.end.cast<double>();
    if ((end - start).norm() < options.min_length_px) {
      ++observations.too_short;
      continue;
    }
    if (placer.explained(start, end)) {
      ++observations.explained;
      continue;
    }
    std::optional<SurfaceSegment> placed = placer.place(segment);
    if (!placed) {
      ++observations.off_surface;
      continue;
    }
    if (placer.onCastShadowBoundary(*placed)) {
      ++observations.shadow_edges;
      continue;
    }
    if (placed->pose_placement_sigma_m > options.max_placement_sigma_m) {
      ++observations.imprecise;
      continue;
    }
    placed->robot_id = frame.robot_id;
    placed->stamp_ns = frame.stamp_ns;
    placed->view = {frame.camera, frame.T_world_camera, segment};
    observations.segments.push_back(std::move(*placed));
  }
  return observations;
}

}  // namespace lineloc
