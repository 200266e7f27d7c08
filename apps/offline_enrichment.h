// What lineloc-enrich does: enrichment of a city model from a recorded drive
// (paper §3.1: the database "enriched with more lines, which are extracted
// from camera images ... before the database is used"). For each frame the
// robot's fix log answered OK, the robot's front end
// (robot/vision/features) extracts the image's segments, the model lines
// visible from the fix are found (backbone/visibility), and the segments they
// do not explain are placed on the model's faces and associated across frames
// into 3D lines (backbone/enrichment). Those that triangulate, are not part
// of a repeating pattern and are not model lines seen again are written, one
// per line (lineloc-eval --learnt-lines scores them against a simulated
// drive's façade edges), and stored as one pass of the site's enrichment when
// a database is given, with the stored lines the pass should have seen and
// did not (backbone/enrichment/expected_lines.h), which retire a line missed
// on enough passes.
//
// It composes the robot's and the backbone's libraries, so it belongs to
// neither: backbone/ never includes robot/.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "apps/recorded_drive.h"
#include "backbone/enrichment/line_learner.h"
#include "robot/vision/features/feature_extractor.h"

namespace lineloc {

struct OfflineEnrichmentConfig {
  // The drive's images, with stamps matching the fixes.
  RecordedDrive drive;
  // The robot's log of the backbone's answers (common/trajectory/fix_log.h).
  std::string fix_log;
  // Learnt lines written (apps/learnt_line_file.h).
  std::string out = "enrichment.txt";
  // The robot that drove (names its sightings).
  std::string robot = "robot";
  // With a database (the enricher role's connection string): the site the
  // model is, and the pass (a drive or a day) whose sightings the lines are,
  // stored in the site's enrichment (db/enrichment_store.h). Empty: not stored.
  std::string db;
  std::string site;
  std::string pass;
  FeatureExtractorOptions extractor = trackingFrontEndOptions();
  // With a database, its expected options say when the pass should have
  // seen a stored line.
  LineLearnerOptions learner;
};

struct OfflineEnrichmentSummary {
  int frames = 0;
  int fixed_frames = 0;
  LearningCounts learning;
  LearntPass pass;
};

// Throws std::runtime_error naming the option or file that is malformed or
// unreadable. Writes what it did, and the score, to `out`.
OfflineEnrichmentSummary runOfflineEnrichment(const OfflineEnrichmentConfig& config,
                                              std::ostream& out);

}  // namespace lineloc
