// The enrichment tables (db/migrations/0007_enrichment.sql): lines learnt
// from the robots' images, beside the model, with their sightings per pass
// and robot and their status.
//
// writeEnrichmentPass merges one pass's learnt lines into a site's enrichment
// in one transaction. A line joins a stored line that is not retired when the
// two run within max_angle_rad of each other, both its ends lie within
// max_distance_m of the stored line, and they overlap along it; else it
// becomes a new candidate. Joining records the sighting (pass, robot, views,
// first and last time seen) once, keyed by line, pass and robot, so writing a
// pass again changes nothing; a stored line keeps the geometry of its most
// precise sighting (smallest sum of its ends' covariance traces), over the
// union of the sightings' extents. A line seen on min_passes separate passes
// is confirmed.
//
// The caller also names the stored lines the pass should have seen (in view,
// near and unoccluded from enough of its frames). One that no sighting of the
// pass joined, in this write or an earlier one (a pass may be written piece
// by piece), is missed by the pass, once per pass; a line missed on
// retire_after_passes separate passes since it was last seen is retired, and
// no sighting joins it again (a line seen there anew is a new candidate).
//
// Coordinates are the site frame (the site's CRS minus its origin); times are
// nanoseconds since the Unix epoch (stored to the microsecond).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "db/connection.h"
#include "db/site.h"

namespace lineloc::db {

enum class EnrichmentStatus : int16_t { kCandidate = 0, kConfirmed = 1, kRetired = 2 };

// "candidate", "confirmed", "retired"; parse throws std::invalid_argument
// naming the others.
std::string toString(EnrichmentStatus status);
EnrichmentStatus parseEnrichmentStatus(const std::string& name);

// One pass's sighting of a learnt line.
struct EnrichmentSighting {
  Eigen::Vector3d start_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_world = Eigen::Vector3d::Zero();
  Eigen::Matrix3d start_covariance = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d end_covariance = Eigen::Matrix3d::Zero();
  // The model face's plane n . x = offset, site frame.
  Eigen::Vector3d plane_normal = Eigen::Vector3d::UnitX();
  double plane_offset = 0.0;
  // The database building whose face it lies on; none for a model from a file.
  std::optional<int64_t> building_id;
  std::string robot;
  int views = 0;
  int64_t first_seen_ns = 0;
  int64_t last_seen_ns = 0;
};

// A stored line a pass should have seen, and when.
struct EnrichmentExpectation {
  int64_t line_id = 0;
  int64_t expected_at_ns = 0;
};

struct EnrichmentMergeOptions {
  double max_angle_rad = 3.0 * M_PI / 180.0;
  double max_distance_m = 0.05;
  int min_passes = 2;
  int retire_after_passes = 3;
};

struct EnrichmentWriteReport {
  int added = 0;            // new candidates
  int joined = 0;           // sightings of stored lines
  int already_written = 0;  // this pass's sightings that were stored before
  int confirmed = 0;        // lines this pass confirmed
  int missed = 0;           // expected lines the pass did not see
  int retired = 0;          // lines this pass retired
};

// Throws std::invalid_argument naming the sighting that is malformed (no
// length, non-finite numbers, no robot, no views, times out of order), and
// DatabaseError when the database refuses; nothing is written then.
EnrichmentWriteReport writeEnrichmentPass(Connection& connection, const Site& site,
                                          const std::string& pass,
                                          const std::vector<EnrichmentSighting>& sightings,
                                          const std::vector<EnrichmentExpectation>& expected = {},
                                          const EnrichmentMergeOptions& options = {});

struct StoredEnrichmentLine {
  int64_t id = 0;
  std::optional<int64_t> building_id;
  Eigen::Vector3d start_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_world = Eigen::Vector3d::Zero();
  Eigen::Matrix3d start_covariance = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d end_covariance = Eigen::Matrix3d::Zero();
  Eigen::Vector3d plane_normal = Eigen::Vector3d::UnitX();
  double plane_offset = 0.0;
  EnrichmentStatus status = EnrichmentStatus::kCandidate;
  int passes = 0;
  int robots = 0;
  int views = 0;
  int64_t first_seen_ns = 0;
  int64_t last_seen_ns = 0;
};

// Which lines a read or a purge takes: all of the site's by default.
struct EnrichmentFilter {
  std::optional<EnrichmentStatus> status;
  // Lines that touch this box of the site frame's x, y.
  std::optional<Eigen::AlignedBox2d> area_world;
  // Lines last seen before, or first seen after, these times.
  std::optional<int64_t> seen_before_ns;
  std::optional<int64_t> seen_after_ns;
  // Lines a sighting of this pass, or of this robot, supports.
  std::optional<std::string> pass;
  std::optional<std::string> robot;
};

std::vector<StoredEnrichmentLine> readEnrichment(Connection& connection, const Site& site,
                                                 const EnrichmentFilter& filter = {});

// Deletes the lines the filter takes, with their sightings; returns how many.
int purgeEnrichment(Connection& connection, const Site& site, const EnrichmentFilter& filter);

}  // namespace lineloc::db
