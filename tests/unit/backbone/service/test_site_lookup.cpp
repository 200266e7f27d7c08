// Looking the backbone's site up in a real PostGIS database: found, missing,
// or not known while the database cannot be reached.
#include <gtest/gtest.h>

#include "backbone/service/site_lookup.h"
#include "tests/support/test_database.h"

namespace lineloc {
namespace {

TEST(SiteLookup, FindsTheSiteInTheDatabase) {
  test::TestDatabase database("site_lookup");
  const int id = test::insertCubeBuilding(database.conninfo(), 85000, 447000, 0, 0);
  const SiteLookup lookup = lookUpSite(database.conninfo(), "test");
  ASSERT_EQ(lookup.outcome, SiteLookup::Outcome::kFound) << lookup.error;
  ASSERT_TRUE(lookup.site.has_value());
  EXPECT_EQ(lookup.site->id, id);
  EXPECT_EQ(lookup.site->srid, 7415);
  EXPECT_EQ(lookup.site->origin.x(), 85000.0);
}

TEST(SiteLookup, SaysASiteTheDatabaseDoesNotHoldIsMissing) {
  test::TestDatabase database("site_lookup_missing");
  test::insertCubeBuilding(database.conninfo(), 85000, 447000, 0, 0);
  const SiteLookup lookup = lookUpSite(database.conninfo(), "atlantis");
  EXPECT_EQ(lookup.outcome, SiteLookup::Outcome::kMissing);
  EXPECT_FALSE(lookup.site.has_value());
  EXPECT_EQ(lookup.error, "site 'atlantis' is not in the database");
}

TEST(SiteLookup, DoesNotKnowWhileTheDatabaseCannotBeReached) {
  const SiteLookup lookup =
      lookUpSite("host=127.0.0.1 port=1 user=nobody dbname=none connect_timeout=2", "test");
  EXPECT_EQ(lookup.outcome, SiteLookup::Outcome::kUnreachable);
  EXPECT_NE(lookup.error.find("site 'test' not looked up"), std::string::npos) << lookup.error;
}

}  // namespace
}  // namespace lineloc
