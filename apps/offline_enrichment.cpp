#include "apps/offline_enrichment.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <ostream>
#include <stdexcept>

#include "backbone/enrichment/known_lines.h"
#include "backbone/enrichment/repeated_lines.h"
#include "backbone/tracker/model_file.h"
#include "common/camera/camera_calibration.h"
#include "common/config/option_values.h"
#include "common/image/image_file.h"
#include "common/trajectory/fix_log.h"
#include "db/citymodel/city_model.h"
#include "robot/input/image_sequence.h"

namespace lineloc {
namespace {

// A fix belongs to the frame exposed within this of its stamp.
constexpr int64_t kStampTolerance_ns = 1'000'000;

double sigmaAcross(const Eigen::Matrix3d& covariance) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  return std::sqrt(std::max(0.0, eigen.eigenvalues().maxCoeff()));
}

void writeLines(const std::string& path, const std::vector<LineCandidate>& lines) {
  std::ofstream file(path);
  if (!file) {
    throw std::runtime_error(fmt::format("cannot write the learnt lines to {}", path));
  }
  file << "# x0 y0 z0 x1 y1 z1 (m, site frame) building views robots sigma0_m sigma1_m "
          "(largest standard deviation of each end across the line)\n";
  for (const LineCandidate& candidate : lines) {
    const TriangulatedLine& line = candidate.line;
    file << fmt::format("{:.4f} {:.4f} {:.4f} {:.4f} {:.4f} {:.4f} {} {} {} {:.4f} {:.4f}\n",
                        line.start_world.x(), line.start_world.y(), line.start_world.z(),
                        line.end_world.x(), line.end_world.y(), line.end_world.z(),
                        candidate.building_id, candidate.views, candidate.robots,
                        sigmaAcross(line.start_covariance), sigmaAcross(line.end_covariance));
  }
}

}  // namespace

OfflineEnrichmentSummary runOfflineEnrichment(const OfflineEnrichmentConfig& config,
                                              std::ostream& out) {
  const std::optional<int> file_epsg =
      config.city_model_crs.empty()
          ? std::nullopt
          : std::optional<int>(citymodel::parseEpsgCode(config.city_model_crs));
  const LocalModel local =
      readLocalModel(config.city_model, pointOption(config.site_origin, "site_origin"), file_epsg);
  const OcclusionScene scene(local.model.faces, local.model.face_building_ids);
  const CameraCalibration calibration = readCameraCalibration(config.camera_calibration);
  VisibilityOptions visibility;
  visibility.sunlight = sunOption(config.sun_deg, config.ambient, "sun");
  std::map<int64_t, LoggedFix> fixes;
  for (LoggedFix& fix : readFixLog(config.fix_log)) {
    if (fix.status == "ok") {
      fixes.emplace(fix.stamp_ns, std::move(fix));
    }
  }
  FeatureExtractor extractor(calibration, config.extractor);
  SurfaceLineTracks tracks(config.tracks);
  OfflineEnrichmentSummary summary;
  for (const FrameRef& frame_ref : listImageSequence(config.images)) {
    ++summary.frames;
    if (!frame_ref.stamp_ns) {
      throw std::runtime_error(
          fmt::format("{}: a frame without a stamp cannot be matched with a fix", frame_ref.path));
    }
    const auto fix = fixes.lower_bound(*frame_ref.stamp_ns - kStampTolerance_ns);
    if (fix == fixes.end() || fix->first > *frame_ref.stamp_ns + kStampTolerance_ns) {
      continue;
    }
    ++summary.fixed_frames;
    EnrichmentFrame frame;
    frame.robot_id = "recorded";
    frame.stamp_ns = *frame_ref.stamp_ns;
    frame.camera = calibration.camera;
    frame.T_world_camera = fix->second.T_world_camera;
    if (visibility.sunlight) {
      frame.towards_sun_world = visibility.sunlight->direction_world;
    }
    const cv::Mat image = readImageFile(frame_ref.path, cv::IMREAD_GRAYSCALE);
    frame.segments = extractor.extract(image).segments;
    frame.visible = visibleSegments(local.model.lines, scene, frame.T_world_camera,
                                    calibration.camera, visibility);
    const SurfaceObservations observed = observeSurfaceSegments(frame, scene, config.observation);
    summary.precise_frames += observed.segments.empty() ? 0 : 1;
    summary.segments += static_cast<int>(frame.segments.size());
    summary.explained += observed.explained;
    summary.off_surface += observed.off_surface;
    summary.imprecise += observed.imprecise;
    summary.shadow_edges += observed.shadow_edges;
    summary.on_surface += static_cast<int>(observed.segments.size());
    for (const SurfaceSegment& segment : observed.segments) {
      tracks.add(segment);
    }
  }
  summary.tracks = tracks.trackCount();
  const std::vector<LineCandidate> candidates = tracks.candidates();
  const std::vector<LineCandidate> distinct = withoutRepeatedLines(candidates);
  summary.repeated_lines = static_cast<int>(candidates.size() - distinct.size());
  summary.lines = withoutModelLines(distinct, local.model.lines);
  summary.model_lines_seen = static_cast<int>(distinct.size() - summary.lines.size());
  writeLines(config.out, summary.lines);
  out << fmt::format(
      "lineloc-enrich: {} frames, {} with an OK fix, {} of them placing segments precisely; {} "
      "segments: {} explained by model lines, {} off the model's surface, {} on its cast "
      "shadows' edges, {} placed too imprecisely by the fix, {} learnt from in {} tracks; {} "
      "lines ({} more were model lines, {} of a repeating pattern) -> {}\n",
      summary.frames, summary.fixed_frames, summary.precise_frames, summary.segments,
      summary.explained, summary.off_surface, summary.shadow_edges, summary.imprecise,
      summary.on_surface, summary.tracks, summary.lines.size(), summary.model_lines_seen,
      summary.repeated_lines, config.out);
  return summary;
}

}  // namespace lineloc
