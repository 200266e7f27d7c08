// OpenCV's own calibration of the opencv-doc left*.jpg camera
// (left_intrinsics.yml): strong barrel distortion, the kind of lens the robot
// carries.
#pragma once

#include "common/camera/camera_calibration.h"

namespace lineloc {

inline CameraCalibration opencvLeftCamera() {
  CameraCalibration calibration;
  calibration.camera = {535.9157, 535.9157, 342.2832, 235.5708, 0.0, 640, 480};
  calibration.distortion = {-2.6637260909660682e-01, -3.8588898922304653e-02,
                            1.7831947042852964e-03, -2.8122100441115472e-04,
                            2.3839153080878486e-01};
  return calibration;
}

}  // namespace lineloc
