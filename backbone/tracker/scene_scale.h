// The unit a scene is tracked in. A pinhole image does not change when the
// world and the camera's position are scaled alike about the world's origin,
// so the localizer's lengths (its gates, search ranges and steps, model
// accuracy and visibility limits, localizer.h, and the tracker's process
// noise), set for street views, serve a model of any size once it is
// expressed in units in which the camera sees it at a street view's depth.
// With d the median depth of the model's surfaces seen through a grid of
// pixels (the ray through each meets the model's first face at depth
// z = distance * ray_z, the ray a unit vector in the camera frame; rays that
// meet no face, into sky or ground, do not count),
//   s = d / street_depth_m   metres per scene unit,
// and a point p (m) is p / s in scene units: a 30 cm object seen from
// 0.9 m is tracked as a building seen from across a street.
#pragma once

#include <Eigen/Geometry>

#include "backbone/visibility/occlusion_scene.h"
#include "common/camera/camera_calibration.h"

namespace lineloc {

// s of the model `scene` (metres) seen from T_world_camera; 1 when no ray
// meets a face. Throws std::invalid_argument for a street depth that is not
// positive.
double sceneMetresPerUnit(const OcclusionScene& scene, const PinholeCamera& camera,
                          const Eigen::Isometry3d& T_world_camera, double street_depth_m);

}  // namespace lineloc
