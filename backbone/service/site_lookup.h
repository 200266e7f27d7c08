// The backbone's site in its building database, looked up by name: found,
// missing (the database answered and holds no such site, which the backbone
// refuses to serve), or not known yet (the database could not be reached or
// queried, which a backbone started before its database retries).
#pragma once

#include <optional>
#include <string>

#include "db/site.h"

namespace lineloc {

struct SiteLookup {
  enum class Outcome { kFound, kMissing, kUnreachable };
  Outcome outcome = Outcome::kUnreachable;
  // kFound: the site.
  std::optional<db::Site> site;
  // kMissing, kUnreachable: why, naming the site or the database's error.
  std::string error;
};

// Never throws: a failure to reach or query the database is kUnreachable.
SiteLookup lookUpSite(const std::string& conninfo, const std::string& site_name);

}  // namespace lineloc
