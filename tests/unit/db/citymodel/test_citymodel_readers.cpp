// The city-model readers on small documents of known content and on
// malformed input, and the CRS transform against GeographicLib (the real files
// are read in test_shared_city_models.cpp).
#include <gtest/gtest.h>

#include <GeographicLib/UTMUPS.hpp>
#include <functional>

#include "db/citymodel/cityjson_reader.h"
#include "db/citymodel/crs_transform.h"
#include "db/citymodel/footprint_reader.h"
#include "db/citymodel/obj_reader.h"

namespace lineloc::citymodel {
namespace {

constexpr const char* kOneCube = R"({"type":"CityJSON","version":"2.0",
 "transform":{"scale":[1,1,1],"translate":[0,0,0]},
 "metadata":{"referenceSystem":"https://www.opengis.net/def/crs/EPSG/0/7415"},
 "CityObjects":{"cube":{"type":"Building","geometry":[{"type":"Solid","lod":"1","boundaries":
 [[[[0,3,2,1]],[[4,5,6,7]],[[0,1,5,4]],[[1,2,6,5]],[[2,3,7,6]],[[3,0,4,7]]]]}]}},
 "vertices":[[0,0,0],[1,0,0],[1,1,0],[0,1,0],[0,0,1],[1,0,1],[1,1,1],[0,1,1]]})";

std::string withReplaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

void expectModelError(const std::string& text, const std::string& reason,
                      const std::string& object_id) {
  try {
    readCityJson(text, "bad.json", {});
    FAIL() << "expected a ModelError: " << reason;
  } catch (const ModelError& error) {
    EXPECT_EQ(error.reason(), reason);
    EXPECT_NE(std::string(error.what()).find("bad.json"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find(object_id), std::string::npos) << error.what();
  }
}

TEST(CityJsonReader, MalformedInputNamesFileObjectAndReason) {
  ASSERT_EQ(readCityJson(kOneCube, "cube.json", {}).buildings.at(0).faces.size(), 6u);
  expectModelError(std::string(kOneCube).substr(0, 100), "malformed JSON", "");
  expectModelError(withReplaced(kOneCube, "[[0,3,2,1]]", "[[0,3,2,99]]"),
                   "vertex index out of range", "cube");
  expectModelError(withReplaced(kOneCube, "EPSG/0/7415", "OGC/1.3/CRS84"), "unknown CRS", "");
  expectModelError(withReplaced(kOneCube, "\"Solid\"", "\"Bogus\""), "unsupported geometry type",
                   "cube");
  // 1e308 * 10 overflows to infinity when the vertex is decoded.
  expectModelError(
      withReplaced(withReplaced(kOneCube, "\"scale\":[1,1,1]", "\"scale\":[1e308,1,1]"), "[0,1,1]]",
                   "[10,1,1]]"),
      "non-finite vertex coordinate", "");
  expectModelError(withReplaced(kOneCube, "\"scale\":[1,1,1]", "\"scale\":[1,1]"),
                   "malformed transform", "");
}

TEST(CityJsonReader, SkipInvalidCountsTheBadObjectAndKeepsTheRest) {
  const std::string two = withReplaced(
      kOneCube, "\"CityObjects\":{",
      R"("CityObjects":{"broken":{"type":"Building","geometry":[{"type":"Solid","lod":"1","boundaries":[[[[0,1,42]]]]}]},)");
  EXPECT_THROW(readCityJson(two, "two.json", {}), ModelError);
  const CityModel model =
      readCityJson(two, "two.json", {.lod = "", .invalid_objects = InvalidObjectPolicy::kSkip});
  ASSERT_EQ(model.buildings.size(), 1u);
  EXPECT_EQ(model.buildings[0].id, "cube");
  EXPECT_EQ(model.skipped.count_by_reason.at("vertex index out of range"), 1);
}

TEST(CityJsonReader, ATinReliefIsReadAsTrianglesFacingUp) {
  // Vertices 8-12 hold the terrain: a clockwise triangle (seen from above) and
  // a quad, which becomes two triangles.
  const std::string text = withReplaced(
      withReplaced(
          kOneCube, "\"CityObjects\":{",
          R"("CityObjects":{"ground":{"type":"TINRelief","geometry":[{"type":"CompositeSurface","lod":"1","boundaries":[[[8,10,9]],[[8,9,11,12]]]}]},)"),
      "[0,1,1]]", "[0,1,1],[0,0,0],[10,0,1],[0,10,2],[10,10,3],[0,-10,4]]");
  const CityModel model = readCityJson(text, "terrain.json", {});
  ASSERT_EQ(model.buildings.size(), 1u);
  ASSERT_EQ(model.terrain.size(), 3u);
  for (const TerrainTriangle& triangle : model.terrain) {
    const Eigen::Vector3d ab = triangle[1] - triangle[0];
    const Eigen::Vector3d ac = triangle[2] - triangle[0];
    EXPECT_GT(ab.x() * ac.y() - ab.y() * ac.x(), 0.0) << "counter-clockwise seen from above";
  }
  EXPECT_EQ(model.terrain[0][0], Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(model.skipped.total(), 0);
}

std::string nestedArrays(int depth) {
  return std::string(depth, '[') + std::string(depth, ']');
}

void expectTooDeep(const std::function<void()>& read, const std::string& source) {
  try {
    read();
    FAIL() << "expected a ModelError for " << source;
  } catch (const ModelError& error) {
    EXPECT_EQ(error.reason(), "JSON nested too deeply") << error.what();
    EXPECT_NE(std::string(error.what()).find(source), std::string::npos) << error.what();
  }
}

TEST(JsonReaders, EveryReaderRefusesADepthBomb) {
  const std::string bomb = nestedArrays(70000);
  expectTooDeep(
      [&] {
        readCityJson(withReplaced(kOneCube, "\"type\":\"Building\",",
                                  "\"type\":\"Building\",\"attributes\":{\"a\":" + bomb + "},"),
                     "bomb.json", {});
      },
      "bomb.json");
  const std::string header =
      R"({"type":"CityJSON","version":"2.0","transform":{"scale":[1,1,1],"translate":[0,0,0]}})";
  expectTooDeep([&] { readCityJsonLines(bomb + "\n", "header.jsonl", {}); }, "header.jsonl");
  expectTooDeep(
      [&] {
        readCityJsonLines(header + "\n{\"type\":\"CityJSONFeature\",\"a\":" + bomb + "}\n",
                          "feature.jsonl", {});
      },
      "feature.jsonl");
  expectTooDeep(
      [&] {
        readGeoJsonFootprints(R"({"type":"FeatureCollection","features":[],"a":)" + bomb + "}",
                              "bomb.geojson", {}, {});
      },
      "bomb.geojson");
}

TEST(JsonReaders, TheDeepestCityJsonGeometryLoadsWithinTheBound) {
  // A CompositeSolid nests its rings' indices 10 levels deep, the most any
  // CityJSON geometry does.
  const std::string composite =
      withReplaced(withReplaced(withReplaced(kOneCube, "\"Solid\"", "\"CompositeSolid\""),
                                "[[[[0,3,2,1]]", "[[[[[0,3,2,1]]"),
                   "[[3,0,4,7]]]]", "[[3,0,4,7]]]]]");
  EXPECT_EQ(readCityJson(composite, "composite.json", {}).buildings.at(0).faces.size(), 6u);
  ReadOptions tight;
  tight.max_json_nesting = 10;
  EXPECT_EQ(readCityJson(composite, "composite.json", tight).buildings.at(0).faces.size(), 6u);
  tight.max_json_nesting = 9;
  expectTooDeep([&] { readCityJson(composite, "composite.json", tight); }, "composite.json");
}

TEST(WavefrontObjReader, ReadsObjectsWithOffsetAndRejectsBadIndices) {
  const std::string obj =
      "# a unit square wall and a roof triangle\n"
      "o wall\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3 4\n"
      "o roof\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf -3/1/1 -2/2/2 -1/3/3\n";
  const CityModel model = readWavefrontObj(obj, "m.obj", {100, 200, 0}, {});
  ASSERT_EQ(model.buildings.size(), 2u);
  EXPECT_EQ(model.buildings[0].id, "wall");
  EXPECT_EQ(model.buildings[0].faces[0].kind, SurfaceKind::kWall);
  EXPECT_EQ(model.buildings[1].faces[0].kind, SurfaceKind::kRoof);
  EXPECT_EQ(model.buildings[0].faces[0].rings[0][1], Eigen::Vector3d(101, 200, 0));
  EXPECT_FALSE(model.epsg.has_value());
  try {
    readWavefrontObj("o a\nv 0 0 0\nf 1 2 3\n", "bad.obj", {0, 0, 0}, {});
    FAIL();
  } catch (const ModelError& error) {
    EXPECT_EQ(error.reason(), "vertex index out of range");
    EXPECT_NE(std::string(error.what()).find("line 3"), std::string::npos);
  }
  EXPECT_THROW(readWavefrontObj("v 0 nan 0\n", "bad.obj", {0, 0, 0}, {}), ModelError);
}

TEST(GeoJsonFootprints, ExtrudesAndReadsTheNamedCrs) {
  const std::string geojson = R"({"type":"FeatureCollection",
    "crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::28992"}},
    "features":[{"type":"Feature","id":"a","properties":{"height":9.5},
      "geometry":{"type":"Polygon","coordinates":[[[0,0],[0,10],[10,10],[10,0],[0,0]]]}},
     {"type":"Feature","id":"b","properties":{},
      "geometry":{"type":"Polygon","coordinates":[[[0,0],[0,10],[10,10],[0,0]]]}}]})";
  EXPECT_THROW(readGeoJsonFootprints(geojson, "f.geojson", {}, {}), ModelError);
  const CityModel model = readGeoJsonFootprints(
      geojson, "f.geojson", {}, {.lod = "", .invalid_objects = InvalidObjectPolicy::kSkip});
  EXPECT_EQ(model.epsg, 28992);
  ASSERT_EQ(model.buildings.size(), 1u);
  EXPECT_EQ(model.skipped.count_by_reason.at("missing height"), 1);
  // Ground, roof and 4 walls; the roof at the height, whatever the input orientation.
  ASSERT_EQ(model.buildings[0].faces.size(), 6u);
  EXPECT_EQ(model.buildings[0].faces[1].kind, SurfaceKind::kRoof);
  EXPECT_DOUBLE_EQ(model.buildings[0].faces[1].rings[0][0].z(), 9.5);
}

TEST(CrsTransform, Wgs84ToUtmAgreesWithGeographicLib) {
  const CrsTransform transform(4326, 32631);  // WGS 84 -> UTM zone 31N
  for (const auto& [latitude, longitude] : {std::pair{52.0116, 4.3571}, {51.5, 2.1}, {53.2, 5.9}}) {
    int zone;
    bool north;
    double easting, northing;
    GeographicLib::UTMUPS::Forward(latitude, longitude, zone, north, easting, northing, 31);
    const Eigen::Vector3d utm = transform.apply({longitude, latitude, 7.0});
    // Both implement Krüger's series to well below a millimetre.
    EXPECT_NEAR(utm.x(), easting, 1e-3);
    EXPECT_NEAR(utm.y(), northing, 1e-3);
    EXPECT_DOUBLE_EQ(utm.z(), 7.0);
  }
  EXPECT_THROW(CrsTransform(4326, 999999), std::invalid_argument);
}

TEST(UpAxis, AYUpFileIsTurnedZUpAndNothingElseIsAnAxis) {
  EXPECT_EQ(zUpPoint({1, 2, 3}, UpAxis::kZ), Eigen::Vector3d(1, 2, 3));
  // +90 degrees about x: the file's up (y) becomes z, its z (towards the
  // viewer) becomes -y, and the frame stays right-handed.
  EXPECT_EQ(zUpPoint({1, 2, 3}, UpAxis::kY), Eigen::Vector3d(1, -3, 2));
  EXPECT_EQ(zUpPoint({1, 0, 0}, UpAxis::kY).cross(zUpPoint({0, 1, 0}, UpAxis::kY)),
            zUpPoint({0, 0, 1}, UpAxis::kY));
  EXPECT_EQ(parseUpAxis("z"), UpAxis::kZ);
  EXPECT_EQ(parseUpAxis("y"), UpAxis::kY);
  for (const char* bad : {"Y", "x", "-z", "", "zy"}) {
    try {
      parseUpAxis(bad);
      FAIL() << bad;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(std::string("'") + bad + "'"), std::string::npos)
          << error.what();
    }
  }
}

TEST(UpAxis, AYUpObjAndCityJsonReadAsTheirZUpTwins) {
  // A wall and a roof, written y-up: the roof lies at y = 1, facing +y.
  const std::string y_up_obj =
      "o wall\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"
      "o roof\nv 0 1 0\nv 0 1 -1\nv 1 1 0\nf -3 -1 -2\n";
  ReadOptions y_up;
  y_up.up_axis = UpAxis::kY;
  const CityModel model = readWavefrontObj(y_up_obj, "y_up.obj", {10, 0, 0}, y_up);
  ASSERT_EQ(model.buildings.size(), 2u);
  EXPECT_EQ(model.buildings[0].faces[0].kind, SurfaceKind::kWall);
  EXPECT_EQ(model.buildings[1].faces[0].kind, SurfaceKind::kRoof);
  // Turned, then offset: the offset is in the z-up frame.
  EXPECT_EQ(model.buildings[0].faces[0].rings[0][2], Eigen::Vector3d(11, 0, 1));
  EXPECT_EQ(model.buildings[1].faces[0].rings[0][1], Eigen::Vector3d(11, 0, 1));

  const CityModel z_up = readCityJson(kOneCube, "z_up.json", {});
  const CityModel turned = readCityJson(kOneCube, "y_up.json", y_up);
  const auto& z_ring = z_up.buildings[0].faces[1].rings[0];
  const auto& y_ring = turned.buildings[0].faces[1].rings[0];
  ASSERT_EQ(z_ring.size(), y_ring.size());
  for (size_t i = 0; i < z_ring.size(); ++i) {
    EXPECT_EQ(y_ring[i], zUpPoint(z_ring[i], UpAxis::kY));
  }
}

TEST(CityModel, EpsgCodesFromEveryAcceptedFormAndNoOther) {
  EXPECT_EQ(parseEpsgCode("EPSG:7415"), 7415);
  EXPECT_EQ(parseEpsgCode("epsg:28992"), 28992);
  EXPECT_EQ(parseEpsgCode("urn:ogc:def:crs:EPSG::7415"), 7415);
  EXPECT_EQ(parseEpsgCode("urn:ogc:def:crs:EPSG:9.8.15:4326"), 4326);
  EXPECT_EQ(parseEpsgCode("https://www.opengis.net/def/crs/EPSG/0/7415"), 7415);
  EXPECT_EQ(parseEpsgCode("http://www.opengis.net/def/crs/EPSG/9.8/25832"), 25832);
  for (const char* bad :
       {"EPSG:abc", "EPSG:", "EPSG:0", "EPSG:-1", "EPSG:7415x", "EPSG:1234567890", "7415",
        "urn:ogc:def:crs:EPSG:7415", "urn:ogc:def:crs:OGC:1.3:CRS84",
        "https://www.opengis.net/def/crs/EPSG//7415", "https://www.opengis.net/def/crs/EPSG/0/",
        "https://www.opengis.net/def/crs/OGC/1.3/CRS84", "ftp://www.opengis.net/def/crs/EPSG/0/1",
        ""}) {
    EXPECT_THROW(parseEpsgCode(bad), std::invalid_argument) << bad;
  }
}

}  // namespace
}  // namespace lineloc::citymodel
