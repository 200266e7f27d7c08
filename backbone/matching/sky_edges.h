// Image edges where a pose's model sees open sky: evidence against the pose
// that coverage alone does not give (paper §3.2: "a false match gives a
// precise but wrong pose").
//
// From the camera pose T_world_camera, the viewing ray of an image point q is
// d = R_world_camera K^-1 (q, 1) / |.|. The point is in open sky when d rises
// at least min_elevation_rad above the horizon and meets no building face,
// nor does the ray lowered by margin_px / f_x towards the ground: the roof
// line itself borders the sky, and a pixel of noise must not put it there.
// Sky is featureless but for what stands in it and no model holds (cables,
// lamps, signs, trees over the roofs), so an image edge there is either such
// clutter or something the pose does not explain. A search settled a house's
// width along a street, or a window row taken for a roof line, covers as many
// model lines as the true pose does, but it leaves façade detail where its
// model shows sky, next to its roof lines.
//
// How much clutter a frame's sky holds is measured in clear sky, the part of
// a pose's open sky still open when lowered by clear_margin_rad (farther
// above every roof line than a storey seen from across a street), where a
// pose near the truth puts no façade: its edge length per area
// lambda = K_clear / A_clear, where A_clear is at least min_clear_area_px2.
// The caller takes the least of its poses' densities as the frame's (the
// truth's clear sky holds nothing but clutter, a wrong pose's may hold a
// façade). An edge in a pose's open sky is then evidence against it of
// log(lambda_facade / lambda) nats: how much likelier such an edge is on a
// façade (facade_edge_density) than in a sky as cluttered as this one. The
// sky's edge length K counts against the pose weighed by that evidence,
// relative to a typical street sky's (typical_clutter_density):
//   K_weighed = w K,
//   w = clamp(log(lambda_facade / lambda) / log(lambda_facade / lambda_typical), 0, 1),
// so that a sky no more cluttered than a typical street's counts in full, one
// as dense in edges as a façade not at all.
//
// Below the horizon a ray that meets no face meets the ground, which the
// model does not hold, so nothing is counted there; min_elevation_rad also
// leaves out buildings far beyond the map around the robot, low over the
// horizon, which no hypothesis holds either.
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "backbone/visibility/occlusion_scene.h"
#include "common/camera/camera_calibration.h"
#include "common/messages/messages.h"

namespace lineloc {

struct SkyEdgeOptions {
  // About 6 degrees: a ten-storey building 300 m away rises no higher.
  double min_elevation_rad = 0.1;
  double margin_px = 4.0;
  // Samples along each image segment, and the shortest segment sampled.
  double sample_spacing_px = 6.0;
  double min_segment_length_px = 15.0;
  // The clear sky's area is sampled on a grid of this spacing.
  double area_spacing_px = 16.0;
  // About 11 degrees: a storey (3 m) seen from 15 m.
  double clear_margin_rad = 0.2;
  // The least clear sky (px^2) a clutter density is measured in: a patch of
  // 100 x 100 px, a thirtieth of a 640 x 480 image.
  double min_clear_area_px2 = 10000.0;
  // Edge length per area (1 / px) of a façade's detail (window frames,
  // sills, cornices), and of the clutter in a typical street's sky: an edge
  // every 25 px, and every 100 px (a cable, a lamp, a branch).
  double facade_edge_density = 0.04;
  double typical_clutter_density = 0.01;
  // A ray meeting no face within this distance meets none.
  double reach_m = 1000.0;
};

// The image edge length (pixels) in a pose's open sky, and in its clear part.
struct SkyEdges {
  double edge_px = 0.0;
  double clear_edge_px = 0.0;
};

// The open sky seen from T_world_camera, sampled along the image segments
// every options.sample_spacing_px.
SkyEdges measureSkyEdges(const std::vector<ImageSegment>& image,
                         const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera,
                         const OcclusionScene& scene, const SkyEdgeOptions& options);

// The area (pixels^2) of the image's clear sky seen from T_world_camera,
// sampled on a grid of options.area_spacing_px.
double clearSkyArea(const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera,
                    const OcclusionScene& scene, const SkyEdgeOptions& options);

// K_clear / A_clear, or nothing when the clear sky is smaller than
// options.min_clear_area_px2.
std::optional<double> clearSkyEdgeDensity(const SkyEdges& sky, double clear_area_px2,
                                          const SkyEdgeOptions& options);

// K_weighed: the sky's edge length weighed by the evidence an edge carries
// in a sky of clutter density `clutter_density` (1 / px).
double weighedSkyEdgeLength(const SkyEdges& sky, double clutter_density,
                            const SkyEdgeOptions& options);

}  // namespace lineloc
