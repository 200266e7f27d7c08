#include "robot/calibration/calibrate_tool.h"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <stdexcept>

#include "common/config/size_pair.h"
#include "robot/calibration/calibration_file.h"
#include "robot/calibration/chessboard_detection.h"
#include "robot/calibration/point_file.h"
#include "robot/calibration/residual_plot.h"
#include "robot/calibration/zhang_calibration.h"

namespace lineloc {

namespace {

struct LoadedViews {
  PlanarViews views;
  std::vector<std::string> names;
};

void parseImageSize(const std::string& text, PlanarViews* views) {
  const std::optional<SizePair> size = parseSizePair(text, 5);
  if (!size || size->first == 0 || size->second == 0) {
    throw std::runtime_error(
        fmt::format("--image-size '{}': expected WIDTHxHEIGHT in pixels, e.g. 640x480", text));
  }
  views->image_width = size->first;
  views->image_height = size->second;
}

LoadedViews loadPointFiles(const CalibrateToolConfig& config) {
  LoadedViews loaded;
  parseImageSize(config.image_size, &loaded.views);
  loaded.views.model_points = readPointFile(config.points.front());
  for (size_t i = 1; i < config.points.size(); ++i) {
    const std::string& path = config.points[i];
    std::vector<Eigen::Vector2d> image_points = readPointFile(path);
    if (image_points.size() != loaded.views.model_points.size()) {
      throw std::runtime_error(fmt::format("{}: {} points, but the model '{}' has {}", path,
                                           image_points.size(), config.points.front(),
                                           loaded.views.model_points.size()));
    }
    loaded.views.image_points.push_back(std::move(image_points));
    loaded.names.push_back(path);
  }
  return loaded;
}

LoadedViews loadChessboards(const CalibrateToolConfig& config, std::ostream& log) {
  if (!(config.square_m > 0.0)) {
    throw std::runtime_error(
        fmt::format("--square {}: must be positive (metres)", config.square_m));
  }
  const std::vector<std::string> paths = expandImagePattern(config.images);
  ChessboardViews detected =
      detectChessboards(paths, parseChessboardSize(config.board), config.square_m);
  for (const std::string& path : detected.images_without_board) {
    fmt::print(log, "no {} board found in '{}': skipped\n", config.board, path);
  }
  for (const std::string& path : detected.images_of_other_size) {
    fmt::print(log, "'{}' is not {}x{} like the other views: skipped\n", path,
               detected.views.image_width, detected.views.image_height);
  }
  if (detected.images_with_board.empty()) {
    throw std::runtime_error(fmt::format("no {} board found in any of the {} images matching '{}'",
                                         config.board, paths.size(), config.images));
  }
  return {std::move(detected.views), std::move(detected.images_with_board)};
}

LoadedViews loadViews(const CalibrateToolConfig& config, std::ostream& log) {
  if (config.images.empty() == config.points.empty()) {
    throw std::runtime_error("give either --images PATTERN or --points MODEL VIEW...");
  }
  if (!config.points.empty()) {
    if (config.points.size() < 2) {
      throw std::runtime_error("--points needs the model file and at least one view file");
    }
    return loadPointFiles(config);
  }
  return loadChessboards(config, log);
}

CalibrationOptions calibrationOptionsOf(const CalibrateToolConfig& config) {
  CalibrationOptions options;
  options.fix_skew = config.fix_skew;
  options.fix_aspect_ratio = config.fix_aspect_ratio;
  options.aspect_ratio = config.aspect_ratio;
  options.fix_principal_point = config.fix_principal_point;
  options.max_iterations = config.max_iterations;
  if (config.distortion == "k1k2") {
    options.distortion_model = DistortionModel::kRadialK1K2;
  } else if (config.distortion == "opencv5") {
    options.distortion_model = DistortionModel::kOpenCv5;
  } else {
    throw std::runtime_error(
        fmt::format("--distortion '{}': expected k1k2 or opencv5", config.distortion));
  }
  if (options.fix_aspect_ratio && !(options.aspect_ratio > 0.0)) {
    throw std::runtime_error(
        fmt::format("--aspect-ratio {}: must be positive", config.aspect_ratio));
  }
  if (options.max_iterations <= 0) {
    throw std::runtime_error("--max-iterations must be positive");
  }
  return options;
}

void printErrors(const CalibrationResult& result, const std::vector<std::string>& names,
                 std::ostream& log) {
  for (size_t view = 0; view < names.size(); ++view) {
    fmt::print(log, "  {:8.4f} px  {}\n", result.per_view_rms_error_px[view], names[view]);
  }
  fmt::print(log, "RMS reprojection error: {:.4f} px over {} views\n", result.rms_error_px,
             names.size());
}

void printCalibration(const CalibrationResult& result, std::ostream& log) {
  const PinholeCamera& camera = result.state.calibration.camera;
  const Eigen::Matrix<double, 5, 1> intrinsics(camera.fx, camera.fy, camera.cx, camera.cy,
                                               camera.skew);
  const char* intrinsic_names[] = {"fx", "fy", "cx", "cy", "skew"};
  const char* distortion_names[] = {"k1", "k2", "p1", "p2", "k3"};
  const CalibrationUncertainty& uncertainty = result.uncertainty;
  for (int i = 0; i < 5; ++i) {
    fmt::print(log, "  {:<4} = {:12.4f} +- {:.4f} px\n", intrinsic_names[i], intrinsics(i),
               uncertainty.intrinsics_std_dev(i));
  }
  for (int i = 0; i < 5; ++i) {
    fmt::print(log, "  {:<4} = {:12.6f} +- {:.6f}\n", distortion_names[i],
               result.state.calibration.distortion[i], uncertainty.distortion_std_dev(i));
  }
  if (uncertainty.available) {
    fmt::print(log, "  (standard deviations for an estimated image noise of {:.3f} px)\n",
               uncertainty.noise_sigma_px);
  } else {
    fmt::print(log, "  standard deviations unavailable: the covariance is rank deficient\n");
  }
  for (const std::string& warning : result.warnings) {
    fmt::print(log, "warning: {}\n", warning);
  }
}

int runCheck(const CalibrateToolConfig& config, const LoadedViews& loaded, std::ostream& log) {
  const CameraCalibration calibration = readCameraCalibration(config.check);
  if (calibration.camera.width != loaded.views.image_width ||
      calibration.camera.height != loaded.views.image_height) {
    throw std::runtime_error(fmt::format("{}: calibrated for {}x{} images, the views are {}x{}",
                                         config.check, calibration.camera.width,
                                         calibration.camera.height, loaded.views.image_width,
                                         loaded.views.image_height));
  }
  const CalibrationResult result = checkCalibration(loaded.views, calibration);
  if (result.status != CalibrationStatus::kConverged) {
    fmt::print(log, "check failed: {}: {}\n", toString(result.status), result.message);
    return 1;
  }
  fmt::print(log, "calibration '{}' on {} views:\n", config.check, loaded.names.size());
  printErrors(result, loaded.names, log);
  if (!config.report.empty()) {
    writeResidualPlot(config.report, loaded.views, result.residuals_px,
                      config.report_magnification);
  }
  return 0;
}

int runCalibration(const CalibrateToolConfig& config, const LoadedViews& loaded,
                   std::ostream& log) {
  if (static_cast<int>(loaded.names.size()) < kMinCalibrationViews) {
    throw std::runtime_error(fmt::format("only {} usable views: at least {} are needed",
                                         loaded.names.size(), kMinCalibrationViews));
  }
  const CalibrationOptions options = calibrationOptionsOf(config);
  const CalibrationResult result = calibrateCamera(loaded.views, options);
  if (result.status != CalibrationStatus::kConverged &&
      result.status != CalibrationStatus::kNoConvergence) {
    fmt::print(log, "calibration failed: {}: {}\n", toString(result.status), result.message);
    return 1;
  }
  if (result.status == CalibrationStatus::kNoConvergence) {
    fmt::print(log, "warning: {}\n", result.message);
  }
  printErrors(result, loaded.names, log);
  printCalibration(result, log);
  writeCalibrationFile(config.out, result, options, loaded.names);
  fmt::print(log, "wrote {}\n", config.out);
  if (!config.report.empty()) {
    writeResidualPlot(config.report, loaded.views, result.residuals_px,
                      config.report_magnification);
    fmt::print(log, "wrote {}\n", config.report);
  }
  return 0;
}

}  // namespace

int runCalibrateTool(const CalibrateToolConfig& config, std::ostream& log) {
  const LoadedViews loaded = loadViews(config, log);
  if (!config.check.empty()) {
    return runCheck(config, loaded, log);
  }
  return runCalibration(config, loaded, log);
}

}  // namespace lineloc
