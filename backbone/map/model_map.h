// The backbone's access to the building model: the model lines near a position,
// read from PostGIS. Connects lazily and reconnects after a failure, so a
// database restart costs the frames that arrive while it is down, not the service.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "db/connection.h"
#include "db/model_line_query.h"
#include "db/site.h"

namespace lineloc {

class ModelMap {
 public:
  ModelMap(std::string conninfo, std::string site_name);
  ~ModelMap();

  // Throws db::DatabaseError when the database cannot answer (the next call
  // reconnects) or the site does not exist.
  std::vector<db::ModelLine> linesNear(const Eigen::Vector3d& center_world, double radius_m);

 private:
  void connect();

  std::string conninfo_;
  std::string site_name_;
  std::unique_ptr<db::Connection> connection_;
  std::unique_ptr<db::ModelLineQuery> query_;
};

}  // namespace lineloc
