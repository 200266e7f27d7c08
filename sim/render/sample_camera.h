// The simulator's default camera: OpenCV's own calibration of its sample
// 640x480 camera (opencv-doc left_intrinsics.yml, 13 chessboard views, RMS
// 0.39 px), a real lens with strong barrel distortion.
#pragma once

#include "common/camera/camera_calibration.h"

namespace lineloc {

inline CameraCalibration opencvSampleCamera() {
  CameraCalibration calibration;
  calibration.camera = {535.9157, 535.9157, 342.2832, 235.5708, 0.0, 640, 480};
  calibration.distortion = {-2.6637260909660682e-01, -3.8588898922304653e-02,
                            1.7831947042852964e-03, -2.8122100441115472e-04,
                            2.3839153080878486e-01};
  return calibration;
}

}  // namespace lineloc
