// Pose from 4 coplanar points (lineloc's planar start + refinement against
// cv::solvePnP IPPE and ITERATIVE) and from 50 lines + 20 points (lineloc's
// refinement, and its full estimate with the linear start, against
// cv::solvePnPRefineLM and solvePnP ITERATIVE on the 20 points alone, OpenCV
// having no line pose). All on the same 16 scenes with 0.5 px noise; medians
// of 9 repetitions and the ratios lineloc / OpenCV of the median CPU times are
// printed at the end.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <opencv2/calib3d.hpp>
#include <string>
#include <vector>

#include "common/pose/pose_estimator.h"
#include "common/pose/pose_refinement.h"
#include "tests/unit/common/pose/opencv_pnp.h"
#include "tests/unit/common/pose/pose_test_scene.h"

namespace lineloc {
namespace {

constexpr int kScenes = 16;

std::vector<test::Scene> makeScenes(int points, int lines, bool planar) {
  std::vector<test::Scene> scenes;
  for (int seed = 1; seed <= kScenes; ++seed) {
    scenes.push_back(test::makeScene({points, lines, planar, 0.5, static_cast<uint32_t>(seed)}));
  }
  return scenes;
}

const std::vector<test::Scene>& fourPointScenes() {
  static const std::vector<test::Scene> scenes = makeScenes(4, 0, true);
  return scenes;
}

const std::vector<test::Scene>& lineAndPointScenes() {
  static const std::vector<test::Scene> scenes = makeScenes(20, 50, false);
  return scenes;
}

// Object and image points of a scene in OpenCV's types.
struct OpenCvPoints {
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  cv::Matx33d K;
};

OpenCvPoints toOpenCv(const PoseProblem& problem) {
  OpenCvPoints points;
  for (const auto& point : problem.points) {
    points.object.emplace_back(point.p_world.x(), point.p_world.y(), point.p_world.z());
    points.image.emplace_back(point.pixel.x(), point.pixel.y());
  }
  const PinholeCamera& c = problem.camera;
  points.K = cv::Matx33d(c.fx, c.skew, c.cx, 0.0, c.fy, c.cy, 0.0, 0.0, 1.0);
  return points;
}

void BM_Lineloc4Points(benchmark::State& state) {
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(estimatePose(fourPointScenes()[i++ % kScenes].problem));
  }
}

void openCvSolvePnP(benchmark::State& state, const std::vector<test::Scene>& scenes, int flag) {
  std::vector<OpenCvPoints> points;
  for (const auto& scene : scenes)
    points.push_back(toOpenCv(scene.problem));
  int i = 0;
  cv::Vec3d rvec;
  cv::Vec3d tvec;
  for (auto _ : state) {
    const OpenCvPoints& p = points[i++ % kScenes];
    benchmark::DoNotOptimize(
        cv::solvePnP(p.object, p.image, p.K, cv::noArray(), rvec, tvec, false, flag));
  }
}

void openCv4Points(benchmark::State& state, int flag) {
  openCvSolvePnP(state, fourPointScenes(), flag);
}

void BM_OpenCvIppe4Points(benchmark::State& state) {
  openCv4Points(state, cv::SOLVEPNP_IPPE);
}
void BM_OpenCvIterative4Points(benchmark::State& state) {
  openCv4Points(state, cv::SOLVEPNP_ITERATIVE);
}

// Refinement from the true pose moved by 0.02 rad and 0.1 m.
void BM_LinelocRefine50Lines20Points(benchmark::State& state) {
  std::vector<Eigen::Isometry3d> starts;
  std::mt19937 random(1);
  for (const auto& scene : lineAndPointScenes()) {
    starts.push_back(test::perturbPose(scene.T_world_camera, 0.02, 0.1, random));
  }
  int i = 0;
  for (auto _ : state) {
    const int k = i++ % kScenes;
    benchmark::DoNotOptimize(refinePose(lineAndPointScenes()[k].problem, starts[k]));
  }
}

void BM_LinelocEstimate50Lines20Points(benchmark::State& state) {
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(estimatePose(lineAndPointScenes()[i++ % kScenes].problem));
  }
}

void BM_OpenCvRefineLM20Points(benchmark::State& state) {
  std::vector<OpenCvPoints> scenes;
  std::vector<std::pair<cv::Vec3d, cv::Vec3d>> starts;
  std::mt19937 random(1);
  for (const auto& scene : lineAndPointScenes()) {
    scenes.push_back(toOpenCv(scene.problem));
    const Eigen::Isometry3d T_camera_world =
        test::perturbPose(scene.T_world_camera, 0.02, 0.1, random).inverse();
    const Eigen::AngleAxisd rotation(T_camera_world.linear());
    const Eigen::Vector3d rvec = rotation.angle() * rotation.axis();
    const Eigen::Vector3d tvec = T_camera_world.translation();
    starts.push_back({{rvec.x(), rvec.y(), rvec.z()}, {tvec.x(), tvec.y(), tvec.z()}});
  }
  int i = 0;
  for (auto _ : state) {
    const int k = i++ % kScenes;
    cv::Vec3d rvec = starts[k].first;
    cv::Vec3d tvec = starts[k].second;
    cv::solvePnPRefineLM(scenes[k].object, scenes[k].image, scenes[k].K, cv::noArray(), rvec, tvec);
    benchmark::DoNotOptimize(rvec);
  }
}

void BM_OpenCvIterative20Points(benchmark::State& state) {
  openCvSolvePnP(state, lineAndPointScenes(), cv::SOLVEPNP_ITERATIVE);
}

constexpr int kRepetitions = 9;
BENCHMARK(BM_Lineloc4Points)->Repetitions(kRepetitions)->ReportAggregatesOnly(true);
BENCHMARK(BM_OpenCvIppe4Points)->Repetitions(kRepetitions)->ReportAggregatesOnly(true);
BENCHMARK(BM_OpenCvIterative4Points)->Repetitions(kRepetitions)->ReportAggregatesOnly(true);
BENCHMARK(BM_LinelocRefine50Lines20Points)->Repetitions(kRepetitions)->ReportAggregatesOnly(true);
BENCHMARK(BM_LinelocEstimate50Lines20Points)->Repetitions(kRepetitions)->ReportAggregatesOnly(true);
BENCHMARK(BM_OpenCvRefineLM20Points)->Repetitions(kRepetitions)->ReportAggregatesOnly(true);
BENCHMARK(BM_OpenCvIterative20Points)->Repetitions(kRepetitions)->ReportAggregatesOnly(true);

// Console output plus the median CPU time of every benchmark, for the ratios
// (CPU time: the machine may be shared).
class MedianCollector : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.aggregate_name == "median") {
        median_ns_[run.run_name.function_name] = run.GetAdjustedCPUTime();
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }

  void printRatio(const std::string& ours, const std::string& theirs) const {
    const auto a = median_ns_.find(ours);
    const auto b = median_ns_.find(theirs);
    if (a != median_ns_.end() && b != median_ns_.end()) {
      std::printf("%-36s / %-28s = %.2f (medians %.2f / %.2f us)\n", ours.c_str(), theirs.c_str(),
                  a->second / b->second, a->second / 1e3, b->second / 1e3);
    }
  }

 private:
  std::map<std::string, double> median_ns_;
};

}  // namespace
}  // namespace lineloc

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  lineloc::MedianCollector reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  std::printf("\nratios lineloc / OpenCV (target: 4 points within 2x of IPPE)\n");
  reporter.printRatio("BM_Lineloc4Points", "BM_OpenCvIppe4Points");
  reporter.printRatio("BM_Lineloc4Points", "BM_OpenCvIterative4Points");
  reporter.printRatio("BM_LinelocRefine50Lines20Points", "BM_OpenCvRefineLM20Points");
  reporter.printRatio("BM_LinelocEstimate50Lines20Points", "BM_OpenCvIterative20Points");
  benchmark::Shutdown();
  return 0;
}
