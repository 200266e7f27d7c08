#include "labelled_segments.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace lineloc::testing {
namespace {

// Reads exactly `count` finite numbers and nothing else from `fields`.
bool readNumbers(std::istringstream& fields, double* values, int count) {
  for (int i = 0; i < count; ++i) {
    if (!(fields >> values[i]) || !std::isfinite(values[i])) {
      return false;
    }
  }
  std::string rest;
  return !(fields >> rest);
}

}  // namespace

LabelledSegments readLabelledSegments(std::istream& in, const std::string& name) {
  LabelledSegments labels;
  bool has_region = false;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto fail = [&](const std::string& what) {
      throw std::invalid_argument(name + ":" + std::to_string(number) + ": " + what);
    };
    std::istringstream fields(line);
    std::string first;
    if (!(fields >> first) || first[0] == '#') {
      continue;
    }
    double v[4];
    if (first == "region") {
      if (has_region) {
        fail("a second region");
      }
      if (!readNumbers(fields, v, 4) || !(v[2] > v[0]) || !(v[3] > v[1])) {
        fail("region needs x0 y0 x1 y1 with x1 > x0 and y1 > y0");
      }
      labels.region = Eigen::AlignedBox2d(Eigen::Vector2d(v[0], v[1]), Eigen::Vector2d(v[2], v[3]));
      has_region = true;
      continue;
    }
    std::istringstream segment(line);
    if (!readNumbers(segment, v, 4)) {
      fail("expected a segment 'x1 y1 x2 y2' or 'region x0 y0 x1 y1', got '" + line + "'");
    }
    const Segment2d s{{v[0], v[1]}, {v[2], v[3]}};
    if (s.start == s.end) {
      fail("a segment of zero length");
    }
    labels.segments.push_back(s);
  }
  if (!has_region) {
    throw std::invalid_argument(name + ": no region line");
  }
  return labels;
}

LabelledSegments readLabelledSegments(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw std::invalid_argument("cannot open labelled segments '" + path + "'");
  }
  return readLabelledSegments(in, path);
}

}  // namespace lineloc::testing
