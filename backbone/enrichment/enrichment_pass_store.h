// A site's enrichment as a learner sees it (db/enrichment_store.h), through
// the enricher role: the stored lines a pass may be expected to see, and a
// pass's learnt lines and expectations written as the sightings of one robot.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "backbone/enrichment/line_learner.h"
#include "db/connection.h"
#include "db/enrichment_store.h"
#include "db/site.h"

namespace lineloc {

class EnrichmentPassStore {
 public:
  // `database_buildings`: the learnt lines' building ids are the database's
  // (the faces came from its tiles) and are stored with them; else (a model
  // read from a file) they are not. Throws db::DatabaseError when the
  // database cannot be reached, and std::runtime_error naming the site when
  // it holds no such site.
  EnrichmentPassStore(const std::string& conninfo, const std::string& site,
                      bool database_buildings);

  const db::Site& site() const { return site_; }

  // The stored lines that are not retired and touch `area_world` (x, y).
  std::vector<KnownLearntLine> knownLines(const Eigen::AlignedBox2d& area_world);

  // Throws as writeEnrichmentPass does; nothing is written then.
  db::EnrichmentWriteReport write(const std::string& pass, const std::string& robot,
                                  const LearntPass& learnt);

 private:
  db::Connection connection_;
  db::Site site_;
  bool database_buildings_;
};

}  // namespace lineloc
