#include "backbone/tracker/model_file.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "db/loader/loader.h"

namespace lineloc {
namespace {

constexpr double kOriginGridM = 100.0;

Eigen::Vector3d lowestCorner(const citymodel::CityModel& model) {
  Eigen::Vector3d lowest = Eigen::Vector3d::Constant(INFINITY);
  for (const citymodel::Building& building : model.buildings) {
    for (const citymodel::Face& face : building.faces) {
      for (const Eigen::Vector3d& p : face.rings.front())
        lowest = lowest.cwiseMin(p);
    }
  }
  if (!lowest.allFinite()) {
    return Eigen::Vector3d::Zero();
  }
  return {std::floor(lowest.x() / kOriginGridM) * kOriginGridM,
          std::floor(lowest.y() / kOriginGridM) * kOriginGridM, std::floor(lowest.z())};
}

}  // namespace

LocalModel readLocalModel(const std::string& path, std::optional<Eigen::Vector3d> origin,
                          std::optional<int> file_epsg, citymodel::UpAxis up_axis) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) {
    throw std::runtime_error(fmt::format("cannot read model file '{}'", path));
  }
  std::stringstream buffer;
  buffer << stream.rdbuf();
  const std::string text = buffer.str();
  db::LoadOptions options;
  options.file_epsg = file_epsg;
  options.read.invalid_objects = citymodel::InvalidObjectPolicy::kSkip;
  options.read.up_axis = up_axis;
  options.local_frame_allowed = true;
  const db::PreparedModel prepared =
      db::prepareModel(text, path, db::detectFormat(path, text), options, std::nullopt);

  LocalModel local;
  local.local_frame = prepared.source_epsg == 0;
  if (up_axis == citymodel::UpAxis::kY) {
    local.T_model_local.linear() =
        Eigen::AngleAxisd(-M_PI / 2.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  }
  const Eigen::Vector3d origin_z_up =
      origin ? citymodel::zUpPoint(*origin, up_axis)
             : (local.local_frame ? Eigen::Vector3d::Zero() : lowestCorner(prepared.model));
  local.origin = local.T_model_local.linear() * origin_z_up;
  local.buildings = static_cast<int>(prepared.model.buildings.size());
  for (size_t b = 0; b < prepared.model.buildings.size(); ++b) {
    for (const citymodel::Face& face : prepared.model.buildings[b].faces) {
      FaceRing ring;
      for (const Eigen::Vector3d& p : face.rings.front())
        ring.push_back(p - origin_z_up);
      local.model.faces.push_back(std::move(ring));
      local.model.face_building_ids.push_back(static_cast<int64_t>(b));
    }
    for (const citymodel::ExtractedLine& line : prepared.lines[b]) {
      local.model.lines.push_back({static_cast<int64_t>(local.model.lines.size()),
                                   static_cast<int>(line.kind), line.start - origin_z_up,
                                   line.end - origin_z_up});
    }
  }
  return local;
}

}  // namespace lineloc
