// lineloc-calibrate: camera calibration from views of a planar pattern (Zhang).
#include <iostream>
#include <stdexcept>

#include "common/config/program_options.h"
#include "robot/calibration/calibrate_tool.h"

int main(int argc, char** argv) {
  lineloc::CalibrateToolConfig config;
  lineloc::ProgramOptions options("lineloc-calibrate",
                                  "camera calibration from views of a planar pattern (Zhang)");
  options.add("images", config.images, "shell pattern of chessboard images, e.g. 'dir/left*.jpg'");
  options.add("board", config.board, "chessboard inner corners, COLUMNSxROWS");
  options.add("square", config.square_m, "chessboard square side (m)");
  options.add("points", config.points,
              "point files MODEL VIEW1 VIEW2 ...: whitespace-separated X Y (model, Z = 0) and "
              "u v (views) pairs, in the same order");
  options.add("image_size", config.image_size, "image size WIDTHxHEIGHT (pixels), with --points");
  options.add("out", config.out, "calibration file to write (OpenCV YAML layout)");
  options.add("check", config.check,
              "existing calibration file: report its reprojection error on the views instead "
              "of calibrating");
  options.add("report", config.report, "residual plot PNG to write (empty: none)");
  options.add("report_magnification", config.report_magnification,
              "residual plot: image pixels drawn per pixel of residual");
  options.add("fix_skew", config.fix_skew, "hold the skew at zero");
  options.add("fix_aspect_ratio", config.fix_aspect_ratio, "hold fx / fy at --aspect-ratio");
  options.add("aspect_ratio", config.aspect_ratio, "fx / fy when --fix-aspect-ratio");
  options.add("fix_principal_point", config.fix_principal_point,
              "hold the principal point at the image centre");
  options.add("distortion", config.distortion,
              "distortion model: k1k2 (Zhang) or opencv5 (k1 k2 p1 p2 k3)");
  options.add("max_iterations", config.max_iterations,
              "Levenberg-Marquardt iterations of the final refinement at most");
  if (const auto exit_code = options.parse(argc, argv)) {
    return *exit_code;
  }
  try {
    return lineloc::runCalibrateTool(config, std::cout);
  } catch (const std::exception& error) {
    std::cerr << "lineloc-calibrate: " << error.what() << '\n';
    return 2;
  }
}
