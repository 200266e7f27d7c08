// What lineloc-track and lineloc-enrich read alike: a city model file and the
// site frame it is taken in, a recorded camera (its images and calibration)
// and, when known, the sun; the options that name them, with one name each
// across both programs.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "backbone/tracker/model_file.h"
#include "common/config/program_options.h"
#include "common/geometry/sunlight.h"
#include "db/citymodel/city_model.h"

namespace lineloc {

struct RecordedDrive {
  // CityJSON, CityJSON Lines, OBJ or GeoJSON footprints.
  std::string city_model;
  // "EPSG:N" for a model file that names no CRS; empty for such a file: the
  // model is an object in its own metric frame.
  std::string city_model_crs;
  // Model coordinates x y z of the site origin: poses are in the model's
  // frame minus it. Empty: the model's lowest corner, rounded down, for a
  // model with a CRS; zero for one in its own frame.
  std::vector<double> site_origin;
  // Image folder or EuRoC/ASL camera folder.
  std::string images;
  // OpenCV YAML layout.
  std::string camera_calibration;
  // Sun azimuth clockwise from grid north and elevation (deg); empty: unknown.
  std::vector<double> sun_deg;
  // With a sun: fraction of the light in the shade, 0..1.
  double ambient = 0.35;
};

// Declares city_model, city_model_crs, site_origin, images,
// camera_calibration, sun and ambient.
void addRecordedDriveOptions(ProgramOptions& options, RecordedDrive& drive);

// The model in its site frame, z-up (its file's coordinates held `up_axis`
// up). Throws std::runtime_error naming the option or file that is malformed
// or unreadable.
LocalModel readDriveModel(const RecordedDrive& drive,
                          citymodel::UpAxis up_axis = citymodel::UpAxis::kZ);

// The sun of `sun` and `ambient`, when given; throws naming them when
// malformed.
std::optional<Sunlight> driveSun(const RecordedDrive& drive);

}  // namespace lineloc
