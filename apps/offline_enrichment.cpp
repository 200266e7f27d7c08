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
#include "backbone/enrichment/expected_lines.h"
#include "backbone/enrichment/known_lines.h"
#include "backbone/enrichment/repeated_lines.h"
#include "backbone/tracker/model_file.h"
#include "common/camera/camera_calibration.h"
#include "common/config/option_values.h"
#include "common/image/image_file.h"
#include "common/trajectory/fix_log.h"
#include "db/citymodel/city_model.h"
#include "db/enrichment_store.h"
#include "db/site.h"
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

db::EnrichmentSighting sightingOf(const LineCandidate& candidate, const std::string& robot) {
  db::EnrichmentSighting sighting;
  sighting.start_world = candidate.line.start_world;
  sighting.end_world = candidate.line.end_world;
  sighting.start_covariance = candidate.line.start_covariance;
  sighting.end_covariance = candidate.line.end_covariance;
  sighting.plane_normal = candidate.plane.normal;
  sighting.plane_offset = candidate.plane.offset;
  sighting.robot = robot;
  sighting.views = candidate.views;
  sighting.first_seen_ns = candidate.first_stamp_ns;
  sighting.last_seen_ns = candidate.last_stamp_ns;
  return sighting;
}

// The site's enrichment the pass is stored in: its site, whose frame must be
// the model file's (the lines are stored in its CRS), and the learnt lines
// stored there before, which the pass may be expected to see again.
class PassStore {
 public:
  PassStore(const OfflineEnrichmentConfig& config, const Eigen::Vector3d& model_origin)
      : config_(config), connection_(config.db), site_(db::requireSite(connection_, config.site)) {
    if ((site_.origin - model_origin).norm() > 1e-6) {
      throw std::runtime_error(fmt::format(
          "site '{}' has its origin at ({:.3f}, {:.3f}, {:.3f}), the model's frame at ({:.3f}, "
          "{:.3f}, {:.3f}): give --site-origin as the site's",
          site_.name, site_.origin.x(), site_.origin.y(), site_.origin.z(), model_origin.x(),
          model_origin.y(), model_origin.z()));
    }
  }

  // The stored lines that are not retired within `area_world` (x, y).
  std::vector<KnownLearntLine> knownLines(const Eigen::AlignedBox2d& area_world) {
    db::EnrichmentFilter near;
    near.area_world = area_world;
    std::vector<KnownLearntLine> known;
    for (const db::StoredEnrichmentLine& line : db::readEnrichment(connection_, site_, near)) {
      if (line.status != db::EnrichmentStatus::kRetired) {
        known.push_back(
            {line.id, line.start_world, line.end_world, {line.plane_normal, line.plane_offset}});
      }
    }
    return known;
  }

  db::EnrichmentWriteReport write(const std::vector<LineCandidate>& lines,
                                  const std::vector<ExpectedLine>& expected) {
    std::vector<db::EnrichmentSighting> sightings;
    for (const LineCandidate& line : lines) {
      sightings.push_back(sightingOf(line, config_.robot));
    }
    std::vector<db::EnrichmentExpectation> expectations;
    for (const ExpectedLine& line : expected) {
      expectations.push_back({line.id, line.expected_at_ns});
    }
    return db::writeEnrichmentPass(connection_, site_, config_.pass, sightings, expectations);
  }

 private:
  const OfflineEnrichmentConfig& config_;
  db::Connection connection_;
  db::Site site_;
};

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
  std::optional<PassStore> store;
  if (!config.db.empty()) {
    if (config.site.empty() || config.pass.empty()) {
      throw std::runtime_error(
          "--db needs --site and --pass (the drive or day the lines are from)");
    }
    store.emplace(config, local.origin);
  }
  // Only lines near the drive can be expected of it.
  Eigen::AlignedBox2d driven;
  for (const auto& [stamp_ns, fix] : fixes) {
    driven.extend(fix.T_world_camera.pose.translation().head<2>());
  }
  const Eigen::AlignedBox2d reach(
      driven.min() - Eigen::Vector2d::Constant(config.expected.max_depth_m),
      driven.max() + Eigen::Vector2d::Constant(config.expected.max_depth_m));
  ExpectedLines expected(
      store && !driven.isEmpty() ? store->knownLines(reach) : std::vector<KnownLearntLine>(),
      config.expected);
  FeatureExtractor extractor(calibration, config.extractor);
  SurfaceLineTracks tracks(config.tracks);
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
    expected.observe(frame, scene);
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
  std::vector<LearntLineRow> rows;
  for (const LineCandidate& line : summary.lines) {
    rows.push_back(rowOf(line));
  }
  writeLearntLineFile(config.out, rows);
  out << fmt::format(
      "lineloc-enrich: {} frames, {} with an OK fix, {} of them placing segments precisely; {} "
      "segments: {} explained by model lines, {} off the model's surface, {} on its cast "
      "shadows' edges, {} placed too imprecisely by the fix, {} learnt from in {} tracks; {} "
      "lines ({} more were model lines, {} of a repeating pattern) -> {}\n",
      summary.frames, summary.fixed_frames, summary.precise_frames, summary.segments,
      summary.explained, summary.off_surface, summary.shadow_edges, summary.imprecise,
      summary.on_surface, summary.tracks, summary.lines.size(), summary.model_lines_seen,
      summary.repeated_lines, config.out);
  if (store) {
    const db::EnrichmentWriteReport stored = store->write(summary.lines, expected.expected());
    out << fmt::format(
        "lineloc-enrich: pass '{}' in site '{}': {} new candidates, {} lines seen again ({} "
        "confirmed by it), {} written before; {} expected lines missed ({} retired)\n",
        config.pass, config.site, stored.added, stored.joined, stored.confirmed,
        stored.already_written, stored.missed, stored.retired);
  }
  return summary;
}

}  // namespace lineloc
