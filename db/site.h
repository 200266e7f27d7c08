// A site: a named area with a projected CRS and an origin. World coordinates
// in lineloc are the site CRS minus this origin (x east, y north, z up).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "db/connection.h"

namespace lineloc::db {

struct Site {
  int id = 0;
  std::string name;
  int srid = 0;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
};

std::optional<Site> findSite(Connection& connection, const std::string& name);

// The site of that name; throws DatabaseError naming it when there is none.
Site requireSite(Connection& connection, const std::string& name);

// Creates the site, or returns the existing one when name, CRS and origin agree;
// throws DatabaseError when a site of that name exists with another CRS or origin.
Site ensureSite(Connection& connection, const std::string& name, int srid,
                const Eigen::Vector3d& origin);

}  // namespace lineloc::db
