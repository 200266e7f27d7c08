// The sample camera at a quarter of its resolution (160x120): the same lens,
// 16 times fewer rays, for the tests that do not measure geometry.
#pragma once

#include "sim/render/sample_camera.h"

namespace lineloc {

inline CameraCalibration quarterCamera() {
  CameraCalibration calibration = opencvSampleCamera();
  PinholeCamera& camera = calibration.camera;
  camera = {camera.fx / 4, camera.fy / 4, camera.cx / 4, camera.cy / 4, 0.0, 160, 120};
  return calibration;
}

}  // namespace lineloc
