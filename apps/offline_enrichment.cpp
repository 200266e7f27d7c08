#include "apps/offline_enrichment.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <ostream>
#include <stdexcept>

#include "apps/learnt_line_file.h"
#include "backbone/enrichment/enrichment_pass_store.h"
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

LearntLineRow rowOf(const LineCandidate& candidate) {
  return {candidate.line.start_world,
          candidate.line.end_world,
          candidate.building_id,
          candidate.views,
          candidate.robots,
          candidate.line.start_covariance,
          candidate.line.end_covariance};
}

// The site the pass is stored in must have the model file's frame: the lines
// are stored in its CRS.
void requireModelFrame(const EnrichmentPassStore& store, const OfflineEnrichmentConfig& config,
                       const Eigen::Vector3d& model_origin) {
  const Eigen::Vector3d& origin = store.site().origin;
  if ((origin - model_origin).norm() > 1e-6) {
    throw std::runtime_error(fmt::format(
        "site '{}' has its origin at ({:.3f}, {:.3f}, {:.3f}), the model's frame at ({:.3f}, "
        "{:.3f}, {:.3f}): give --site-origin as the site's",
        config.site, origin.x(), origin.y(), origin.z(), model_origin.x(), model_origin.y(),
        model_origin.z()));
  }
}

}  // namespace

OfflineEnrichmentSummary runOfflineEnrichment(const OfflineEnrichmentConfig& config,
                                              std::ostream& out) {
  const LocalModel local = readDriveModel(config.drive);
  const OcclusionScene scene(local.model.faces, local.model.face_building_ids);
  const CameraCalibration calibration = readCameraCalibration(config.drive.camera_calibration);
  VisibilityOptions visibility;
  visibility.sunlight = driveSun(config.drive);
  std::map<int64_t, LoggedFix> fixes;
  for (LoggedFix& fix : readFixLog(config.fix_log)) {
    if (fix.status == "ok") {
      fixes.emplace(fix.stamp_ns, std::move(fix));
    }
  }
  std::optional<EnrichmentPassStore> store;
  if (!config.db.empty()) {
    if (config.site.empty() || config.pass.empty()) {
      throw std::runtime_error(
          "--db needs --site and --pass (the drive or day the lines are from)");
    }
    store.emplace(config.db, config.site, false);
    requireModelFrame(*store, config, local.origin);
  }
  // Only lines near the drive can be expected of it.
  Eigen::AlignedBox2d driven;
  for (const auto& [stamp_ns, fix] : fixes) {
    driven.extend(fix.T_world_camera.pose.translation().head<2>());
  }
  const double reach_m = config.learner.expected.max_depth_m;
  LineLearner learner(store && !driven.isEmpty()
                          ? store->knownLines({driven.min() - Eigen::Vector2d::Constant(reach_m),
                                               driven.max() + Eigen::Vector2d::Constant(reach_m)})
                          : std::vector<KnownLearntLine>(),
                      config.learner);
  FeatureExtractor extractor(calibration, config.extractor);
  OfflineEnrichmentSummary summary;
  for (const FrameRef& frame_ref : listImageSequence(config.drive.images)) {
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
    frame.robot_id = config.robot;
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
    learner.observe(frame, scene);
  }
  summary.learning = learner.counts();
  summary.pass = learner.finish(local.model.lines);
  std::vector<LearntLineRow> rows;
  for (const LineCandidate& line : summary.pass.lines) {
    rows.push_back(rowOf(line));
  }
  writeLearntLineFile(config.out, rows);
  out << fmt::format(
      "lineloc-enrich: {} frames, {} with an OK fix, {} of them placing segments precisely; {} "
      "segments: {} explained by model lines, {} off the model's surface, {} on its cast "
      "shadows' edges, {} placed too imprecisely by the fix, {} learnt from in {} tracks; {} "
      "lines ({} more were model lines, {} of a repeating pattern) -> {}\n",
      summary.frames, summary.fixed_frames, summary.learning.precise_frames,
      summary.learning.segments, summary.learning.explained, summary.learning.off_surface,
      summary.learning.shadow_edges, summary.learning.imprecise, summary.learning.on_surface,
      summary.pass.tracks, summary.pass.lines.size(), summary.pass.model_lines_seen,
      summary.pass.repeated_lines, config.out);
  if (store) {
    const db::EnrichmentWriteReport stored = store->write(config.pass, config.robot, summary.pass);
    out << fmt::format(
        "lineloc-enrich: pass '{}' in site '{}': {} new candidates, {} lines seen again ({} "
        "confirmed by it), {} written before; {} expected lines missed ({} retired)\n",
        config.pass, config.site, stored.added, stored.joined, stored.confirmed,
        stored.already_written, stored.missed, stored.retired);
  }
  return summary;
}

}  // namespace lineloc
