// Where a frame's time goes, stage by stage, on frames of a simulated drive
// through the bundled Delft model: the robot's front end (lines and corners
// from the image), the LineSet's encoding, and on the backbone hidden-line
// removal from the predicted pose, matching, the pose estimate — and the
// search a DGPS + compass start needs (pose_search.h, pose_acquisition.h).
// The DDS hop and the PostGIS map are measured by bench_dds_round_trip and
// bench_db; the backbone's map stage is a cache hit in steady state.
//
// Tracking frames are predicted from the truth moved by the robot's tracking
// uncertainty (2 cm, 0.1 degree); searched frames by a DGPS error (4 m per
// axis) and a compass error (0.5 degree), as a start gives.
//
// Run: build/bin/bench_localization_stages (simulates its frames first, a few
// seconds). Each stage reports its median over the frames; the
// exposure -> fix budget of a 30 Hz robot is the sum of the tracking stages'
// wall times (Time) plus the DDS round trip. Stages on more than one thread
// (the front end's corners, threads:0) show less CPU than Time: the CPU
// column counts the calling thread's alone.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <array>
#include <opencv2/imgproc.hpp>
#include <random>

#include "backbone/matching/localizer.h"
#include "backbone/tracker/model_file.h"
#include "common/messages/messages.h"
#include "common/time/clock.h"
#include "robot/vision/features/feature_extractor.h"
#include "tests/bench/backbone/delft_frames.h"
#include "tests/support/delft_drive.h"

namespace lineloc {
namespace {

constexpr double kDriveSeconds = 12.0;
constexpr double kCameraRateHz = 2.0;
constexpr double kTrackingPositionSigmaM = 0.02;
constexpr double kTrackingRotationSigmaRad = 0.1 * M_PI / 180.0;
constexpr double kDgpsSigmaM = 4.0;
constexpr double kCompassSigmaRad = 0.5 * M_PI / 180.0;

using Frame = test::DelftFrame;

// A simulated drive's frames, the Delft model in the same site frame and its
// ray-casting scene: built once for every benchmark.
struct Drive {
  Drive() : simulated(test::simulateDelftFrames(kDriveSeconds, kCameraRateHz)) {
    model = readLocalModel(test::delftCityModel().string(), test::delftSiteOrigin(), std::nullopt)
                .model;
    scene = std::make_unique<OcclusionScene>(model.faces, model.face_building_ids);
    // The backbone knows the sun the drive is rendered under, as the demo's does.
    localizer.visibility.sunlight = simulated.sunlight;
  }

  // The truth moved by one draw of the given uncertainty.
  PoseWithCovariance predicted(const Frame& frame, double position_sigma_m,
                               double rotation_sigma_rad, std::mt19937& random) const {
    return test::predictedAround(frame.truth, position_sigma_m, rotation_sigma_rad, random);
  }

  test::DelftFrames simulated;
  const CameraCalibration& calibration = simulated.calibration;
  const std::vector<Frame>& frames = simulated.frames;
  TrackedModel model;
  std::unique_ptr<OcclusionScene> scene;
  LocalizerOptions localizer;
};

const Drive& drive() {
  static const Drive instance;
  return instance;
}

const Frame& frameAt(int64_t iteration) {
  return drive().frames[static_cast<size_t>(iteration) % drive().frames.size()];
}

void BM_RobotFrontEnd(benchmark::State& state) {
  FeatureExtractor extractor(drive().calibration);
  int64_t iteration = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(extractor.extract(frameAt(iteration++).image));
  }
}

void BM_LineSetEncoding(benchmark::State& state) {
  int64_t iteration = 0;
  for (auto _ : state) {
    LineSetData data;
    data.camera = drive().calibration.camera;
    const Frame& frame = frameAt(iteration++);
    data.segments = frame.segments;
    data.corners = frame.corners;
    LineSetMessage message(data);
    benchmark::DoNotOptimize(fromMessage(message.message()));
  }
}

// Its argument: the threads sharing the lines (0: one per core).
void BM_BackboneVisibility(benchmark::State& state) {
  std::mt19937 random(1);
  VisibilityOptions options = drive().localizer.visibility;
  options.threads = static_cast<int>(state.range(0));
  int64_t iteration = 0;
  for (auto _ : state) {
    const Frame& frame = frameAt(iteration++);
    const PoseWithCovariance prior =
        drive().predicted(frame, kTrackingPositionSigmaM, kTrackingRotationSigmaRad, random);
    benchmark::DoNotOptimize(visibleSegments(drive().model.lines, *drive().scene, prior,
                                             drive().calibration.camera, options));
  }
}

// Matching and the robust pose, timed apart by the alignment itself.
void BM_BackboneMatchingAndPose(benchmark::State& state) {
  std::mt19937 random(2);
  int64_t iteration = 0;
  int ok = 0;
  double matching_ms = 0.0;
  double pose_ms = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    const Frame& frame = frameAt(iteration++);
    const PoseWithCovariance prior =
        drive().predicted(frame, kTrackingPositionSigmaM, kTrackingRotationSigmaRad, random);
    const std::vector<VisibleSegment> visible =
        visibleSegments(drive().model.lines, *drive().scene, prior, drive().calibration.camera,
                        drive().localizer.visibility);
    state.ResumeTiming();
    const Alignment alignment =
        alignModel(frame.segments, visible, prior, drive().calibration.camera, {});
    ok += alignment.status == AlignmentStatus::kOk ? 1 : 0;
    matching_ms += toMilliseconds(alignment.matching_ns);
    pose_ms += toMilliseconds(alignment.pose_ns);
  }
  state.counters["ok_fraction"] = static_cast<double>(ok) / iteration;
  state.counters["matching_ms"] = matching_ms / iteration;
  state.counters["pose_ms"] = pose_ms / iteration;
}

// localize() on each frame from the truth moved by one draw of the given
// uncertainty: with a tracking prediction the whole tracking step the backbone
// runs on a frame (hidden-line removal, alignment from the prediction and its
// sigma points, coverage scoring when their alignments disagree:
// localizer.h); from a DGPS start the search and its verification.
void localizeFrames(benchmark::State& state, double position_sigma_m, double rotation_sigma_rad,
                    unsigned seed, const LocalizerOptions& options) {
  std::mt19937 random(seed);
  int64_t iteration = 0;
  int ok = 0;
  double search_ms = 0.0;
  for (auto _ : state) {
    const Frame& frame = frameAt(iteration++);
    const PoseWithCovariance prior =
        drive().predicted(frame, position_sigma_m, rotation_sigma_rad, random);
    const Localization localization =
        localize(frame.segments, frame.corners, drive().model.lines, *drive().scene, prior,
                 drive().calibration.camera, options);
    ok += localization.alignment.status == AlignmentStatus::kOk ? 1 : 0;
    search_ms += localization.search ? toMilliseconds(localization.search->search_ns) : 0.0;
  }
  state.counters["ok_fraction"] = static_cast<double>(ok) / iteration;
  state.counters["grid_search_ms"] = search_ms / iteration;
}

// Its argument: the threads sharing the tracking step (0: one per core).
void BM_BackboneTracking(benchmark::State& state) {
  LocalizerOptions options = drive().localizer;
  options.threads = static_cast<int>(state.range(0));
  localizeFrames(state, kTrackingPositionSigmaM, kTrackingRotationSigmaRad, 4, options);
}

void BM_BackboneSearchFromDgps(benchmark::State& state) {
  localizeFrames(state, kDgpsSigmaM, kCompassSigmaRad, 3, drive().localizer);
}

// The sharp oriented distance map that scores rival alignments, against what
// a user would write with OpenCV: each orientation bin's segments drawn into
// a binary image and cv::distanceTransform (exact, L2) over it.
void BM_VerificationMap(benchmark::State& state) {
  const DistanceMapOptions options = AcquisitionOptions{}.verification_distances;
  const PinholeCamera& camera = drive().calibration.camera;
  int64_t iteration = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        OrientedDistanceMap(frameAt(iteration++).segments, camera.width, camera.height, options));
  }
}

void BM_VerificationMapOpenCvDistanceTransform(benchmark::State& state) {
  const DistanceMapOptions options = AcquisitionOptions{}.verification_distances;
  const PinholeCamera& camera = drive().calibration.camera;
  int64_t iteration = 0;
  for (auto _ : state) {
    std::array<cv::Mat1b, OrientedDistanceMap::kOrientationBins> edges;
    for (cv::Mat1b& bin : edges) {
      bin = cv::Mat1b(camera.height, camera.width, uchar{255});
    }
    for (const ImageSegment& segment : frameAt(iteration++).segments) {
      const Eigen::Vector2f along = segment.end - segment.start;
      if (along.norm() < options.min_segment_length_px) {
        continue;
      }
      const int bin = OrientedDistanceMap::binOf(std::atan2(along.y(), along.x()));
      cv::line(edges[bin], {cvRound(segment.start.x()), cvRound(segment.start.y())},
               {cvRound(segment.end.x()), cvRound(segment.end.y())}, cv::Scalar(0));
    }
    std::array<cv::Mat1f, OrientedDistanceMap::kOrientationBins> distances;
    for (size_t bin = 0; bin < edges.size(); ++bin) {
      cv::distanceTransform(edges[bin], distances[bin], cv::DIST_L2, cv::DIST_MASK_PRECISE);
    }
    benchmark::DoNotOptimize(distances);
  }
}

// Each per-frame stage: five repetitions over the frames, their median reported.
void perFrameStage(benchmark::internal::Benchmark* stage) {
  stage->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly();
}

BENCHMARK(BM_RobotFrontEnd)->Apply(perFrameStage);
BENCHMARK(BM_LineSetEncoding)->Apply(perFrameStage);
BENCHMARK(BM_BackboneVisibility)->ArgName("threads")->Arg(1)->Arg(0)->Apply(perFrameStage);
BENCHMARK(BM_BackboneMatchingAndPose)->Apply(perFrameStage);
BENCHMARK(BM_BackboneTracking)->ArgName("threads")->Arg(1)->Arg(0)->Apply(perFrameStage);
BENCHMARK(BM_VerificationMap)->Apply(perFrameStage);
BENCHMARK(BM_VerificationMapOpenCvDistanceTransform)->Apply(perFrameStage);
BENCHMARK(BM_BackboneSearchFromDgps)->Unit(benchmark::kMillisecond)->Iterations(8);

}  // namespace
}  // namespace lineloc

BENCHMARK_MAIN();
