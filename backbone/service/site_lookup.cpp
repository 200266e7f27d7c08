#include "backbone/service/site_lookup.h"

#include <fmt/format.h>

#include <exception>

namespace lineloc {

SiteLookup lookUpSite(const std::string& conninfo, const std::string& site_name) {
  SiteLookup lookup;
  try {
    db::Connection connection(conninfo);
    lookup.site = db::findSite(connection, site_name);
  } catch (const std::exception& error) {
    lookup.error = fmt::format("site '{}' not looked up: {}", site_name, error.what());
    return lookup;
  }
  if (!lookup.site) {
    lookup.outcome = SiteLookup::Outcome::kMissing;
    lookup.error = fmt::format("site '{}' is not in the database", site_name);
    return lookup;
  }
  lookup.outcome = SiteLookup::Outcome::kFound;
  return lookup;
}

}  // namespace lineloc
