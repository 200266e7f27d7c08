#include "backbone/enrichment/enrichment_pass_store.h"

namespace lineloc {
namespace {

db::EnrichmentSighting sightingOf(const LineCandidate& candidate, const std::string& robot) {
  db::EnrichmentSighting sighting;
  sighting.start_world = candidate.line.start_world;
  sighting.end_world = candidate.line.end_world;
  sighting.start_covariance = candidate.line.start_covariance;
  sighting.end_covariance = candidate.line.end_covariance;
  sighting.plane_normal = candidate.plane.normal;
  sighting.plane_offset = candidate.plane.offset;
  sighting.robot = robot;
  sighting.views = candidate.views;
  sighting.first_seen_ns = candidate.first_stamp_ns;
  sighting.last_seen_ns = candidate.last_stamp_ns;
  return sighting;
}

}  // namespace

EnrichmentPassStore::EnrichmentPassStore(const std::string& conninfo, const std::string& site,
                                         bool database_buildings)
    : connection_(conninfo),
      site_(db::requireSite(connection_, site)),
      database_buildings_(database_buildings) {}

std::vector<KnownLearntLine> EnrichmentPassStore::knownLines(
    const Eigen::AlignedBox2d& area_world) {
  db::EnrichmentFilter near;
  near.area_world = area_world;
  std::vector<KnownLearntLine> known;
  for (const db::StoredEnrichmentLine& line : db::readEnrichment(connection_, site_, near)) {
    if (line.status != db::EnrichmentStatus::kRetired) {
      known.push_back(
          {line.id, line.start_world, line.end_world, {line.plane_normal, line.plane_offset}});
    }
  }
  return known;
}

db::EnrichmentWriteReport EnrichmentPassStore::write(const std::string& pass,
                                                     const std::string& robot,
                                                     const LearntPass& learnt) {
  std::vector<db::EnrichmentSighting> sightings;
  for (const LineCandidate& line : learnt.lines) {
    sightings.push_back(sightingOf(line, robot));
    if (database_buildings_) {
      sightings.back().building_id = line.building_id;
    }
  }
  std::vector<db::EnrichmentExpectation> expectations;
  for (const ExpectedLine& line : learnt.expected) {
    expectations.push_back({line.id, line.expected_at_ns});
  }
  return db::writeEnrichmentPass(connection_, site_, pass, sightings, expectations);
}

}  // namespace lineloc
