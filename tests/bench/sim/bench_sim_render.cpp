// Rendering a 60 s drive through Delft on one core, and the pieces a user
// would otherwise take from a library:
// - BM_DelftDrive60s: full frames (shading, shadows, noise) along the whole
//   drive, frames/s of thread CPU time, with and without shadows and with
//   edge pixels integrated over their area or one ray per pixel (the target
//   was >= 30 with one ray; the integration costs about half of that, and
//   the simulator renders one frame per core).
// - BM_EdgeAntialiasing: lineloc's 16 lattice rays in the pixels a geometric
//   edge crosses (edges placed to 1/16 px) against supersampling every pixel
//   with a 4x4 grid (edges to 1/4 px): a 4x render reduced by cv::resize's
//   pixel-area average.
// - BM_PrimaryRays: lineloc's 4x4 Embree packets against one rtcIntersect1
//   per pixel, the same rays and scene.
// - BM_LensDistortion: lineloc's inverse-mapped rays (distortion costs nothing
//   per frame) against a pinhole render warped by cv::remap with
//   cv::initUndistortRectifyMap's maps.
// Each reports medians over repetitions and the ratio.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>

#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "common/time/clock.h"
#include "sim/render/city_renderer.h"
#include "sim/render/sample_camera.h"
#include "sim/world/city_mesh.h"
#include "sim/world/occupancy_map.h"
#include "sim/world/route_trajectory.h"
#include "sim/world/street_clutter.h"
#include "sim/world/street_route.h"

namespace lineloc {
namespace {

double threadCpuSeconds() {
  return 1e-9 * static_cast<double>(threadCpuClockNs());
}

// Delft with street clutter along a 60 s drive, camera 1.5 m up looking ahead.
struct DelftDrive {
  SceneMesh scene;
  float ground_z_m = 0.0f;
  std::vector<Eigen::Isometry3d> camera_poses;  // 20 Hz

  DelftDrive() {
    const std::filesystem::path path =
        std::filesystem::path(LINELOC_SOURCE_DIR) / "data" / "citymodels" / "delft.json";
    const citymodel::CityModel model = readCityModelFile(path.string());
    const CityMesh city = buildCityMesh(model, defaultSiteOrigin(model));
    const OccupancyMap map(city.mesh);
    StreetRouteOptions route_options;
    route_options.length_m = 140.0;
    const StreetRoute route =
        planStreetRoute(buildStreetNetwork(map, StreetNetworkOptions{}), map, route_options);
    scene = city.mesh;
    const auto ground_height_m = [&city](const Eigen::Vector2d& xy) {
      return groundHeightAt(city, xy);
    };
    addStreetClutter(map, route.waypoints, ground_height_m, StreetClutterOptions{},
                     kFirstClutterObjectId, scene);
    ground_z_m = static_cast<float>(city.ground_z_m);
    RouteDriveOptions drive;
    drive.duration_s = 60.0;
    const RouteTrajectory trajectory(route.waypoints, ground_height_m, drive);
    Eigen::Matrix3d R_body_camera;
    R_body_camera << 0, 0, 1, -1, 0, 0, 0, -1, 0;
    for (int64_t t = trajectory.startStamp_ns(); t <= trajectory.endStamp_ns(); t += 50'000'000) {
      const sim::TruthSample sample = trajectory.at(t);
      Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
      T_world_camera.linear() = sample.q_world_body.toRotationMatrix() * R_body_camera;
      T_world_camera.translation() = sample.p_world_body + Eigen::Vector3d(0.0, 0.0, 1.2);
      camera_poses.push_back(T_world_camera);
    }
  }

  RenderOptions options(bool shadows = true,
                        int edge_pixel_samples = RenderOptions{}.edge_pixel_samples) const {
    RenderOptions render;
    render.ground_z_m = ground_z_m;
    render.shadows = shadows;
    render.edge_pixel_samples = edge_pixel_samples;
    return render;
  }
};

const DelftDrive& delft() {
  static const DelftDrive drive;
  return drive;
}

void BM_DelftDrive60s(benchmark::State& state) {
  const DelftDrive& drive = delft();
  const CityRenderer renderer(drive.scene, opencvSampleCamera(),
                              drive.options(state.range(0) != 0, static_cast<int>(state.range(1))));
  // Every 4th frame of the 20 Hz drive: 300 frames spread over the whole minute.
  constexpr size_t kStride = 4;
  for (auto _ : state) {
    const double start_s = threadCpuSeconds();
    int frames = 0;
    for (size_t i = 0; i < drive.camera_poses.size(); i += kStride, ++frames) {
      const Eigen::Isometry3d& pose = drive.camera_poses[i];
      benchmark::DoNotOptimize(renderer.renderImage(pose, pose, i).data);
    }
    state.counters["frames_per_s"] = frames / (threadCpuSeconds() - start_s);
  }
}
BENCHMARK(BM_DelftDrive60s)
    ->Args({1, 16})
    ->Args({0, 16})
    ->Args({1, 1})
    ->ArgNames({"shadows", "edge_pixel_samples"})
    ->Iterations(1)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kSecond);

// The naive alternative: one Embree ray per pixel with rtcIntersect1.
class SingleRayCaster {
 public:
  explicit SingleRayCaster(const SceneMesh& mesh) : device_(rtcNewDevice("threads=1")) {
    scene_ = rtcNewScene(device_);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.vertices().size() + 1));
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.triangleCount()));
    for (size_t i = 0; i < mesh.vertices().size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        vertices[3 * i + k] = mesh.vertices()[i][k];
      }
    }
    for (size_t i = 0; i < 3 * mesh.triangleCount(); ++i) {
      indices[i] = static_cast<unsigned>(i);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    rtcCommitScene(scene_);
  }
  ~SingleRayCaster() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }

  // Hits of every pixel's ray; returns how many hit the mesh.
  int cast(const CameraRays& rays, const Eigen::Isometry3d& T_world_camera) const {
    const Eigen::Matrix3f R = T_world_camera.linear().cast<float>();
    const Eigen::Vector3f origin = T_world_camera.translation().cast<float>();
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    int hits = 0;
    for (int v = 0; v < rays.height(); ++v) {
      for (int u = 0; u < rays.width(); ++u) {
        const Eigen::Vector3f d = R * rays.direction(u, v);
        RTCRayHit ray_hit{};
        ray_hit.ray = {origin.x(), origin.y(), origin.z(), 0.0f, d.x(), d.y(),
                       d.z(),      0.0f,       1e30f,      ~0u,  0u,    0u};
        ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_, &context, &ray_hit);
        hits += ray_hit.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      }
    }
    return hits;
  }

 private:
  RTCDevice device_;
  RTCScene scene_;
};

// Runs lineloc's and the alternative's work on the same frame every
// iteration, timing each on the thread's CPU clock, and reports both in ms
// per frame and the alternative / lineloc ratio.
template <typename Lineloc, typename Alternative>
void sideBySide(benchmark::State& state, const std::string& lineloc_name,
                const std::string& alternative_name, Lineloc lineloc, Alternative alternative) {
  const DelftDrive& drive = delft();
  double lineloc_s = 0.0;
  double alternative_s = 0.0;
  size_t frame = 0;
  for (auto _ : state) {
    const Eigen::Isometry3d& pose = drive.camera_poses[(frame += 37) % drive.camera_poses.size()];
    double start_s = threadCpuSeconds();
    lineloc(pose);
    lineloc_s += threadCpuSeconds() - start_s;
    start_s = threadCpuSeconds();
    alternative(pose);
    alternative_s += threadCpuSeconds() - start_s;
  }
  const auto frames = static_cast<double>(state.iterations());
  state.counters[lineloc_name + "_ms"] = 1e3 * lineloc_s / frames;
  state.counters[alternative_name + "_ms"] = 1e3 * alternative_s / frames;
  state.counters["ratio"] = alternative_s / lineloc_s;
}

void BM_PrimaryRays(benchmark::State& state) {
  const DelftDrive& drive = delft();
  const CityRenderer renderer(drive.scene, opencvSampleCamera(), drive.options());
  const SingleRayCaster single(drive.scene);
  sideBySide(
      state, "lineloc_packets", "embree_rtcIntersect1",
      [&](const Eigen::Isometry3d& pose) {
        benchmark::DoNotOptimize(renderer.castPrimaryRays(pose).triangle.data());
      },
      [&](const Eigen::Isometry3d& pose) {
        benchmark::DoNotOptimize(single.cast(renderer.rays(), pose));
      });
}
BENCHMARK(BM_PrimaryRays)
    ->Iterations(40)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMillisecond);

void BM_LensDistortion(benchmark::State& state) {
  const DelftDrive& drive = delft();
  const CameraCalibration distorted = opencvSampleCamera();
  CameraCalibration pinhole = distorted;
  pinhole.distortion.clear();
  const CityRenderer lineloc(drive.scene, distorted, drive.options());
  const CityRenderer pinhole_renderer(drive.scene, pinhole, drive.options());
  const cv::Matx33d K(pinhole.camera.fx, 0, pinhole.camera.cx, 0, pinhole.camera.fy,
                      pinhole.camera.cy, 0, 0, 1);
  // Maps from the distorted image to the pinhole render, as a user would build them.
  cv::Mat map_x;
  cv::Mat map_y;
  cv::initUndistortRectifyMap(K, distorted.distortion, cv::noArray(), K, {640, 480}, CV_32FC1,
                              map_x, map_y);
  sideBySide(
      state, "lineloc_inverse_mapped", "pinhole_plus_cv_remap",
      [&](const Eigen::Isometry3d& pose) {
        benchmark::DoNotOptimize(lineloc.renderRadiance(pose).data);
      },
      [&](const Eigen::Isometry3d& pose) {
        cv::Mat warped;
        cv::remap(pinhole_renderer.renderRadiance(pose), warped, map_x, map_y, cv::INTER_LINEAR);
        benchmark::DoNotOptimize(warped.data);
      });
}
BENCHMARK(BM_LensDistortion)
    ->Iterations(30)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMillisecond);

void BM_EdgeAntialiasing(benchmark::State& state) {
  const DelftDrive& drive = delft();
  const CityRenderer lineloc(drive.scene, opencvSampleCamera(), drive.options());
  // The same lens at 4x the resolution: its pixel centre U lies at
  // (U + 1/2) / 4 - 1/2 of the 640x480 image, so cx' = 4 cx + 3/2.
  constexpr int kScale = 4;
  CameraCalibration fine = opencvSampleCamera();
  PinholeCamera& camera = fine.camera;
  camera = {kScale * camera.fx,
            kScale * camera.fy,
            kScale * camera.cx + 1.5,
            kScale * camera.cy + 1.5,
            0.0,
            kScale * camera.width,
            kScale * camera.height};
  const CityRenderer supersampled(drive.scene, fine, drive.options(true, 1));
  sideBySide(
      state, "lineloc_edge_pixels", "supersampled_4x4_cv_resize",
      [&](const Eigen::Isometry3d& pose) {
        benchmark::DoNotOptimize(lineloc.renderRadiance(pose).data);
      },
      [&](const Eigen::Isometry3d& pose) {
        cv::Mat image;
        cv::resize(supersampled.renderRadiance(pose), image, {640, 480}, 0.0, 0.0, cv::INTER_AREA);
        benchmark::DoNotOptimize(image.data);
      });
}
BENCHMARK(BM_EdgeAntialiasing)
    ->Iterations(10)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lineloc

BENCHMARK_MAIN();
