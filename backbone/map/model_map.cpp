#include "backbone/map/model_map.h"

#include <fmt/format.h>

#include <utility>

namespace lineloc {

ModelMap::ModelMap(std::string conninfo, std::string site_name)
    : conninfo_(std::move(conninfo)), site_name_(std::move(site_name)) {}

ModelMap::~ModelMap() = default;

void ModelMap::connect() {
  auto connection = std::make_unique<db::Connection>(conninfo_);
  const std::optional<db::Site> site = db::findSite(*connection, site_name_);
  if (!site) {
    throw db::DatabaseError(fmt::format("site '{}' is not in the database", site_name_));
  }
  query_ = std::make_unique<db::ModelLineQuery>(*connection, *site);
  connection_ = std::move(connection);
}

std::vector<db::ModelLine> ModelMap::linesNear(const Eigen::Vector3d& center_world,
                                               double radius_m) {
  if (!query_) {
    connect();
  }
  try {
    return query_->linesWithin(center_world, radius_m);
  } catch (const db::DatabaseError&) {
    query_.reset();
    connection_.reset();
    throw;
  }
}

}  // namespace lineloc
