#include "apps/recorded_drive.h"

#include "common/config/option_values.h"
#include "db/citymodel/city_model.h"

namespace lineloc {

void addRecordedDriveOptions(ProgramOptions& options, RecordedDrive& drive) {
  options.add("city_model", drive.city_model,
              "city model file (CityJSON, CityJSON Lines, OBJ, GeoJSON)");
  options.add("city_model_crs", drive.city_model_crs,
              "CRS of a city model file that names none (EPSG:N; empty: such a model is an "
              "object in its own metric frame)");
  options.addFixedSize("site_origin", drive.site_origin, 3,
                       "model coordinates x y z of the site origin, subtracted from the model "
                       "(default: the lowest corner of a model with a CRS, zero for one in its "
                       "own frame)");
  options.add("images", drive.images, "image folder or EuRoC/ASL camera folder");
  options.add("camera_calibration", drive.camera_calibration,
              "camera calibration (OpenCV YAML layout)");
  options.addFixedSize("sun", drive.sun_deg, 2,
                       "sun azimuth clockwise from grid north and elevation (deg): corners "
                       "between walls it lights alike are no edges (default: sun unknown)");
  options.add("ambient", drive.ambient, "with --sun: fraction of the light in the shade, 0..1");
}

LocalModel readDriveModel(const RecordedDrive& drive, citymodel::UpAxis up_axis) {
  const std::optional<int> file_epsg =
      drive.city_model_crs.empty()
          ? std::nullopt
          : std::optional<int>(citymodel::parseEpsgCode(drive.city_model_crs));
  return readLocalModel(drive.city_model, pointOption(drive.site_origin, "site_origin"), file_epsg,
                        up_axis);
}

std::optional<Sunlight> driveSun(const RecordedDrive& drive) {
  return sunOption(drive.sun_deg, drive.ambient, "sun");
}

}  // namespace lineloc
