#include "db/site.h"

#include <fmt/format.h>

namespace lineloc::db {

std::optional<Site> findSite(Connection& connection, const std::string& name) {
  const Result result = connection.execParams(
      "SELECT id, srid, origin_x, origin_y, origin_z FROM site WHERE name = $1", {name});
  if (result.rows() == 0) {
    return std::nullopt;
  }
  Site site;
  site.id = std::stoi(result.text(0, 0));
  site.name = name;
  site.srid = std::stoi(result.text(0, 1));
  site.origin = {std::stod(result.text(0, 2)), std::stod(result.text(0, 3)),
                 std::stod(result.text(0, 4))};
  return site;
}

Site requireSite(Connection& connection, const std::string& name) {
  std::optional<Site> site = findSite(connection, name);
  if (!site) {
    throw DatabaseError(fmt::format("site '{}' is not in the database", name));
  }
  return *site;
}

Site ensureSite(Connection& connection, const std::string& name, int srid,
                const Eigen::Vector3d& origin) {
  if (std::optional<Site> existing = findSite(connection, name)) {
    if (existing->srid != srid || !existing->origin.isApprox(origin, 1e-12)) {
      throw DatabaseError(
          fmt::format("site '{}' exists with EPSG:{} origin ({}, {}, {}), not EPSG:{} ({}, {}, {})",
                      name, existing->srid, existing->origin.x(), existing->origin.y(),
                      existing->origin.z(), srid, origin.x(), origin.y(), origin.z()));
    }
    return *existing;
  }
  connection.execParams(
      "INSERT INTO site (name, srid, origin_x, origin_y, origin_z) VALUES ($1, $2, $3, $4, $5)",
      {name, std::to_string(srid), fmt::format("{:.17g}", origin.x()),
       fmt::format("{:.17g}", origin.y()), fmt::format("{:.17g}", origin.z())});
  return *findSite(connection, name);
}

}  // namespace lineloc::db
