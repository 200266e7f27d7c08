#include "robot/vision/lines/line_extractor.h"

#include <algorithm>
#include <span>
#include <stdexcept>

namespace lineloc {
LineExtractor::LineExtractor(const LineExtractorOptions& options)
    : options_(options),
      split_and_merge_(options.split_distance_px, options.min_points),
      merger_(options.merge),
      snapper_(options.snap) {
  if (!(options.min_length_px >= 0.0) || !(options.min_contrast >= 0.0) ||
      !(options.max_false_alarms > 0.0) || !(options.min_snap_length_px >= 0.0) ||
      options.max_segments < 0 || !(options.trim_distance_px >= 0.0) ||
      !(options.trim_sigmas >= 0.0) || !(options.trim_margin_px >= 0.0) ||
      !(options.fit.points_per_sample >= 1.0) || !(options.fit.min_sigma_px > 0.0)) {
    throw std::invalid_argument(
        "line extractor: min_length_px, min_snap_length_px, min_contrast, max_segments, "
        "trim_distance_px, trim_sigmas, trim_margin_px must be >= 0, points_per_sample >= 1, "
        "min_sigma_px, max_false_alarms > 0");
  }
}

void LineExtractor::extract(const std::vector<EdgePoint>& points, const EdgeLinker& chains,
                            const UndistortionTable& undistortion, cv::Size image_size,
                            const EdgeNoise& noise) {
  const SegmentValidation validation(image_size, noise, options_.max_false_alarms);
  const std::vector<int32_t>& chain_points = chains.chainPoints();
  undistorted_.resize(chain_points.size());
  if (undistortion.isIdentity()) {
    for (size_t i = 0; i < chain_points.size(); ++i) {
      undistorted_[i] = points[chain_points[i]].position;
    }
  } else {
    for (size_t i = 0; i < chain_points.size(); ++i) {
      undistorted_[i] = undistortion.undistort(points[chain_points[i]].position);
    }
  }
  segments_.clear();
  for (const PointRange& chain : chains.chains()) {
    // A fisheye's points outside the undistorted view split their chain.
    int run_begin = chain.begin;
    for (int i = chain.begin; i <= chain.end; ++i) {
      if (i == chain.end || !undistorted_[i].allFinite()) {
        if (i - run_begin >= 2) {
          fitPieces(points, chain_points, {run_begin, i});
        }
        run_begin = i + 1;
      }
    }
  }
  merger_.merge(segments_, options_.fit);
  rejected_segments_ = 0;
  keepSignificant(std::min(options_.min_snap_length_px, options_.min_length_px), validation);
  snapEndpoints();
  keepSignificant(options_.min_length_px, validation);
  std::sort(segments_.begin(), segments_.end(),
            [](const LineSegment& a, const LineSegment& b) { return a.length() > b.length(); });
  if (static_cast<int>(segments_.size()) > options_.max_segments) {
    segments_.resize(options_.max_segments);
  }
}

void LineExtractor::fitPieces(const std::vector<EdgePoint>& points,
                              const std::vector<int32_t>& chain_points, PointRange chain) {
  const std::span<const Eigen::Vector2f> polyline(undistorted_.data() + chain.begin,
                                                  static_cast<size_t>(chain.size()));
  pieces_.clear();
  cumulativeMoments(polyline, prefix_);
  split_and_merge_.approximate(polyline, prefix_, pieces_);
  for (PointRange piece : pieces_) {
    trimEnds(polyline, piece);
    LineSegment segment;
    segment.moments = momentsOf(piece);
    segment.fit = fitLine(segment.moments, options_.fit);
    if (segment.fit.status != LineFitStatus::kOk) {
      continue;
    }
    for (int i = piece.begin; i < piece.end; ++i) {
      const EdgePoint& point = points[chain_points[chain.begin + i]];
      segment.gradient_sum += point.gradient.cast<double>();
      segment.step_sum += std::abs(point.step);
    }
    segment.setExtent(polyline[piece.begin].cast<double>(), polyline[piece.end - 1].cast<double>());
    segments_.push_back(segment);
  }
}

void LineExtractor::trimEnds(std::span<const Eigen::Vector2f> polyline, PointRange& piece) const {
  const LineFit core = coreLine(polyline, piece);
  if (core.status != LineFitStatus::kOk) {
    return;
  }
  const double trim_distance =
      std::max(options_.trim_distance_px, options_.trim_sigmas * core.residual_sigma_px);
  const auto off_line = [&](int i) {
    return std::abs(core.distance(polyline[i].cast<double>())) > trim_distance;
  };
  while (piece.size() > 0 && off_line(piece.begin)) {
    ++piece.begin;
  }
  while (piece.size() > 0 && off_line(piece.end - 1)) {
    --piece.end;
  }
}

// The line through the points of the piece at least trim_margin from both
// ends along its chord (the run of them between the first and the last that
// are); through all of them when fewer than min_points are.
LineFit LineExtractor::coreLine(std::span<const Eigen::Vector2f> polyline, PointRange piece) const {
  const Eigen::Vector2d first = polyline[piece.begin].cast<double>();
  const Eigen::Vector2d chord = polyline[piece.end - 1].cast<double>() - first;
  const double length = chord.norm();
  const auto inside = [&](int i) {
    const double along = chord.dot(polyline[i].cast<double>() - first);
    return along >= options_.trim_margin_px * length &&
           along <= (length - options_.trim_margin_px) * length;
  };
  PointRange core = piece;
  while (core.size() > 0 && !inside(core.begin)) {
    ++core.begin;
  }
  while (core.size() > 0 && !inside(core.end - 1)) {
    --core.end;
  }
  return fitLine(momentsOf(core.size() >= options_.min_points ? core : piece), options_.fit);
}

void LineExtractor::snapEndpoints() {
  unsnapped_.assign(segments_.begin(), segments_.end());
  snapper_.snap(segments_);
  // Segments still too short when snapped take no part: a fragment near a
  // corner must not hold the endpoints of the lines that meet there.
  size_t kept = 0;
  for (size_t i = 0; i < segments_.size(); ++i) {
    if (segments_[i].length() >= options_.min_length_px) {
      unsnapped_[kept++] = unsnapped_[i];
    }
  }
  unsnapped_.resize(kept);
  segments_.assign(unsnapped_.begin(), unsnapped_.end());
  snapper_.snap(segments_);
}

PointMoments LineExtractor::momentsOf(PointRange run) const {
  return prefix_[run.end] - prefix_[run.begin];
}

void LineExtractor::keepSignificant(double min_length_px, const SegmentValidation& validation) {
  std::erase_if(segments_, [&](const LineSegment& segment) {
    if (segment.length() < min_length_px) {
      return true;
    }
    const bool weak = segment.contrast() < options_.min_contrast || !validation.meaningful(segment);
    rejected_segments_ += weak ? 1 : 0;
    return weak;
  });
}

}  // namespace lineloc
