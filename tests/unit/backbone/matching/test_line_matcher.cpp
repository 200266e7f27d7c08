// The gate of line_matcher.h against its definition, pair by pair: an image
// segment matches a projected model segment when it overlaps it along the line
// by min_overlap_fraction of its own length and the chi-square of its two
// endpoints' normal distances, each over n^T (Sigma_image + Sigma_model(t)) n
// plus the floor, is within the gate. The gate's shortcuts (a bound on the
// start's distance that turns most pairs away early) must change nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>

#include "backbone/matching/line_matcher.h"

namespace lineloc {
namespace {

const PinholeCamera kCamera{500, 500, 320, 240, 0, 640, 480};

// chi^2 of one pair straight from the definition; nullopt when the overlap
// is too short.
std::optional<double> definitionChi2(const ImageSegment& image, const ProjectedSegment& model,
                                     const MatchingOptions& options) {
  const Eigen::Vector2d along = model.end_px - model.start_px;
  const double length = along.norm();
  const Eigen::Vector2d direction = along / length;
  const Eigen::Vector2d normal(-direction.y(), direction.x());
  const Eigen::Vector2d q0 = image.start.cast<double>();
  const Eigen::Vector2d q1 = image.end.cast<double>();
  const double t0 = direction.dot(q0 - model.start_px);
  const double t1 = direction.dot(q1 - model.start_px);
  const double overlap = std::min(std::max(t0, t1), length) - std::max(std::min(t0, t1), 0.0);
  if (overlap < options.min_overlap_fraction * (q1 - q0).norm()) {
    return std::nullopt;
  }
  double chi2 = 0.0;
  for (const auto& [q, image_covariance] :
       {std::pair{q0, image.start_covariance.cast<double>().eval()},
        std::pair{q1, image.end_covariance.cast<double>().eval()}}) {
    const double t = std::clamp(direction.dot(q - model.start_px) / length, 0.0, 1.0);
    const Eigen::Matrix2d covariance =
        image_covariance + (1.0 - t) * model.start_covariance + t * model.end_covariance;
    const double distance = normal.dot(q - model.start_px);
    chi2 += distance * distance /
            (normal.dot(covariance * normal) +
             options.model_sigma_floor_px * options.model_sigma_floor_px);
  }
  return chi2;
}

TEST(LineMatcher, GatesExactlyThePairsItsDefinitionAdmits) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> lateral(-8.0, 8.0);
  std::uniform_real_distribution<double> depth(5.0, 40.0);
  std::uniform_real_distribution<double> height(-1.5, 8.0);
  std::normal_distribution<double> pixel_noise(0.0, 2.0);
  std::uniform_real_distribution<double> variance(0.01, 4.0);
  PoseWithCovariance T_world_camera;
  T_world_camera.covariance = diagonalPoseCovariance(0.1, 0.3 * M_PI / 180.0);
  std::vector<VisibleSegment> model;
  for (int i = 0; i < 60; ++i) {
    VisibleSegment segment;
    segment.start_world = {lateral(random), height(random), depth(random)};
    segment.end_world =
        segment.start_world + Eigen::Vector3d(pixel_noise(random), pixel_noise(random), 0.0);
    model.push_back(segment);
  }
  // Image segments near projected model segments, and anywhere.
  std::vector<ImageSegment> image;
  for (const VisibleSegment& segment : model) {
    const ProjectedSegment p =
        projectSegment(segment.start_world, segment.end_world, T_world_camera, kCamera);
    for (int copy = 0; copy < 3; ++copy) {
      ImageSegment seen;
      seen.start =
          (p.start_px + Eigen::Vector2d(pixel_noise(random), pixel_noise(random))).cast<float>();
      seen.end =
          (p.end_px + Eigen::Vector2d(pixel_noise(random), pixel_noise(random))).cast<float>();
      seen.start_covariance = Eigen::Vector2f(variance(random), variance(random)).asDiagonal();
      seen.end_covariance = Eigen::Vector2f(variance(random), variance(random)).asDiagonal();
      image.push_back(seen);
    }
  }
  const MatchingOptions options;
  const std::vector<std::vector<LineMatch>> gated =
      gateCandidates(image, model, T_world_camera, kCamera, options);
  ASSERT_EQ(gated.size(), image.size());
  int admitted = 0;
  int turned_away = 0;
  for (size_t i = 0; i < image.size(); ++i) {
    std::set<int> expected;
    for (size_t m = 0; m < model.size(); ++m) {
      const ProjectedSegment p =
          projectSegment(model[m].start_world, model[m].end_world, T_world_camera, kCamera);
      const std::optional<double> chi2 = definitionChi2(image[i], p, options);
      if (chi2 && *chi2 <= options.gate_chi2) {
        expected.insert(static_cast<int>(m));
      } else {
        ++turned_away;
      }
    }
    std::set<int> got;
    for (size_t k = 0; k < gated[i].size(); ++k) {
      got.insert(gated[i][k].model_index);
      EXPECT_EQ(gated[i][k].image_index, static_cast<int>(i));
      if (k > 0) {
        EXPECT_LE(gated[i][k - 1].chi2, gated[i][k].chi2) << "best first";
      }
    }
    EXPECT_EQ(got, expected) << "image segment " << i;
    admitted += static_cast<int>(expected.size());
  }
  // Both outcomes are exercised.
  EXPECT_GT(admitted, 100);
  EXPECT_GT(turned_away, 1000);
}

// A model line across the image predicted brighter on its left (+1), and an
// image segment lying on it: a candidate unless both have a polarity and they
// differ read along the same direction.
TEST(LineMatcher, KeepsImageSegmentsOfTheOtherPolarityOffAModelLine) {
  PoseWithCovariance T_world_camera;
  T_world_camera.covariance = diagonalPoseCovariance(0.05, 0.1 * M_PI / 180.0);
  VisibleSegment model_line;
  model_line.start_world = {-3.0, -1.0, 10.0};
  model_line.end_world = {3.0, -1.0, 10.0};
  model_line.polarity = 1;
  const ProjectedSegment p =
      projectSegment(model_line.start_world, model_line.end_world, T_world_camera, kCamera);
  const auto candidatesFor = [&](bool same_direction, int polarity, bool use_polarity) {
    ImageSegment seen;
    seen.start = (same_direction ? p.start_px : p.end_px).cast<float>();
    seen.end = (same_direction ? p.end_px : p.start_px).cast<float>();
    seen.polarity = polarity;
    MatchingOptions options;
    options.use_polarity = use_polarity;
    return gateCandidates({seen}, {model_line}, T_world_camera, kCamera, options).front().size();
  };
  EXPECT_EQ(candidatesFor(true, 1, true), 1u);
  EXPECT_EQ(candidatesFor(true, -1, true), 0u);
  EXPECT_EQ(candidatesFor(false, -1, true), 1u) << "reversed, the same polarity";
  EXPECT_EQ(candidatesFor(false, 1, true), 0u);
  EXPECT_EQ(candidatesFor(true, 0, true), 1u) << "the image segment has none";
  EXPECT_EQ(candidatesFor(true, -1, false), 1u) << "polarity not used";
  model_line.polarity = 0;
  EXPECT_EQ(candidatesFor(true, -1, true), 1u) << "the model cannot tell";
}

}  // namespace
}  // namespace lineloc
