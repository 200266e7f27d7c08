#include "db/citymodel/polygon_geometry.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cmath>

#include "common/geometry/polygon_triangulation.h"

namespace lineloc::citymodel {
namespace {

// sin(10°): normals closer than this to horizontal belong to walls.
const double kWallNormalZ = std::sin(10.0 * M_PI / 180.0);

// Why a face is unusable: a category and the numbers behind it.
struct FaceDefect {
  std::string reason;
  std::string detail;
};

int countDistinctVertices(const std::vector<Eigen::Vector3d>& ring) {
  int distinct = 0;
  for (size_t i = 0; i < ring.size(); ++i) {
    if ((ring[i] - ring[(i + 1) % ring.size()]).squaredNorm() > 0.0) {
      ++distinct;
    }
  }
  return distinct;
}

// The largest distance of a vertex of any ring from the plane through the
// exterior ring's centroid with its Newell normal.
double planarityDeviation_m(const Face& face) {
  const Eigen::Vector3d normal = newellNormal(face.rings.front()).normalized();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& vertex : face.rings.front()) {
    centroid += vertex;
  }
  centroid /= static_cast<double>(face.rings.front().size());
  double deviation_m = 0.0;
  for (const auto& ring : face.rings) {
    for (const Eigen::Vector3d& vertex : ring) {
      deviation_m = std::max(deviation_m, std::abs(normal.dot(vertex - centroid)));
    }
  }
  return deviation_m;
}

void validateFace(const Face& face, const FaceValidation& validation) {
  if (face.rings.empty()) {
    throw FaceDefect{"polygon without rings", ""};
  }
  for (const auto& ring : face.rings) {
    for (const Eigen::Vector3d& vertex : ring) {
      if (!vertex.allFinite()) {
        throw FaceDefect{"non-finite vertex coordinate", ""};
      }
    }
    if (countDistinctVertices(ring) < 3) {
      throw FaceDefect{"degenerate polygon", "fewer than 3 distinct vertices"};
    }
  }
  const Eigen::Vector3d area_vector = newellNormal(face.rings.front());
  const double area_m2 = 0.5 * area_vector.norm();
  if (!(area_m2 >= validation.min_area_m2)) {
    throw FaceDefect{"degenerate polygon", fmt::format("area {:.3g} m²", area_m2)};
  }
  const double distance_m = planarityDeviation_m(face);
  if (distance_m > validation.planarity_tolerance_m) {
    throw FaceDefect{"non-planar polygon",
                     fmt::format("a vertex is {:.3f} m off its plane, tolerance {} m", distance_m,
                                 validation.planarity_tolerance_m)};
  }
}

}  // namespace

Eigen::Vector3d faceNormal(const Face& face) {
  if (face.rings.empty()) {
    return Eigen::Vector3d::Zero();
  }
  const Eigen::Vector3d area_vector = newellNormal(face.rings.front());
  const double norm = area_vector.norm();
  return norm > 0.0 ? Eigen::Vector3d(area_vector / norm) : Eigen::Vector3d::Zero();
}

SurfaceKind surfaceKindFromNormal(const Eigen::Vector3d& unit_normal) {
  if (unit_normal.isZero()) {
    return SurfaceKind::kOther;
  }
  if (std::abs(unit_normal.z()) < kWallNormalZ) {
    return SurfaceKind::kWall;
  }
  return unit_normal.z() > 0.0 ? SurfaceKind::kRoof : SurfaceKind::kGround;
}

bool isDegenerate(const Face& face, const FaceValidation& validation) {
  if (face.rings.empty()) {
    return true;
  }
  for (const auto& ring : face.rings) {
    if (countDistinctVertices(ring) < 3) {
      return true;
    }
  }
  return !(0.5 * newellNormal(face.rings.front()).norm() >= validation.min_area_m2);
}

void dropDegenerateFaces(Building& building, const FaceValidation& validation,
                         const std::string& source, SkippedObjects& skipped) {
  if (building.faces.empty()) {
    return;
  }
  std::vector<Face> kept;
  kept.reserve(building.faces.size());
  for (size_t index = 0; index < building.faces.size(); ++index) {
    if (isDegenerate(building.faces[index], validation)) {
      skipped.add("degenerate face dropped",
                  fmt::format("{}: object '{}': face {} is degenerate, dropped", source,
                              building.id, index));
    } else {
      kept.push_back(std::move(building.faces[index]));
    }
  }
  if (kept.empty()) {
    throw ModelError(source, building.id, "degenerate polygon", "every face is degenerate");
  }
  building.faces = std::move(kept);
}

void triangulateNonPlanarFaces(Building& building, const FaceValidation& validation,
                               const std::string& source, SkippedObjects& skipped) {
  std::vector<Face> repaired;
  repaired.reserve(building.faces.size());
  for (size_t index = 0; index < building.faces.size(); ++index) {
    Face& face = building.faces[index];
    if (planarityDeviation_m(face) <= validation.planarity_tolerance_m) {
      repaired.push_back(std::move(face));
      continue;
    }
    if (face.rings.size() > 1) {
      skipped.add("non-planar face with holes dropped",
                  fmt::format("{}: object '{}': face {} is non-planar and has holes, dropped",
                              source, building.id, index));
      continue;
    }
    const std::vector<Eigen::Vector3d>& ring = face.rings.front();
    for (const std::array<int, 3>& corners : triangulatePolygon(ring)) {
      Face triangle{face.kind, {{ring[corners[0]], ring[corners[1]], ring[corners[2]]}}};
      if (!isDegenerate(triangle, validation)) {
        repaired.push_back(std::move(triangle));
      }
    }
    skipped.add("non-planar face triangulated",
                fmt::format("{}: object '{}': face {} is non-planar ({:.3f} m), triangulated",
                            source, building.id, index, planarityDeviation_m(face)));
  }
  building.faces = std::move(repaired);
}

void validateFaces(const std::vector<Face>& faces, const FaceValidation& validation,
                   const std::string& source, const std::string& object_id) {
  for (size_t index = 0; index < faces.size(); ++index) {
    try {
      validateFace(faces[index], validation);
    } catch (const FaceDefect& defect) {
      throw ModelError(
          source, object_id, defect.reason,
          fmt::format("face {}{}{}", index, defect.detail.empty() ? "" : ": ", defect.detail));
    }
  }
}

}  // namespace lineloc::citymodel
