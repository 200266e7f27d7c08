// Hand-labelled line segments of a real image, read from a text file:
//   # comment
//   region x0 y0 x1 y1      the rectangle the labels cover completely
//   x1 y1 x2 y2             one segment per line, pixel coordinates
// (pixel centres at integers). Any other line is an error naming the file
// and line.
#pragma once

#include <Eigen/Geometry>
#include <istream>
#include <string>
#include <vector>

#include "segment_precision_recall.h"

namespace lineloc::testing {

struct LabelledSegments {
  Eigen::AlignedBox2d region;
  std::vector<Segment2d> segments;
};

// `name` names the source in errors. Throws std::invalid_argument for a
// malformed line, a missing, repeated or empty region, or a segment of zero
// length.
LabelledSegments readLabelledSegments(std::istream& in, const std::string& name);

// Reads the file at `path`; throws std::invalid_argument when it cannot be opened.
LabelledSegments readLabelledSegments(const std::string& path);

}  // namespace lineloc::testing
