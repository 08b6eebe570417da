// engine/weather/geo.h: the ENU/ECEF frames, lat/lon/altitude of camera-frame points and back,
// region coordinates (row 0 north, column 0 west, regions across 180E), and
// shaders/common/geo.glsl against it through a kernel (tests/weather/geo_kernel.comp).
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include "engine/core/paths.h"
#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/graph/pass_context.h"
#include "engine/scene/scene.h"
#include "engine/shader/shader_compiler.h"
#include "engine/weather/geo.h"
#include "gpu_test.h"

namespace sky {
namespace {
using test::GpuTest;

// Metres of ground per degree of latitude on the sphere.
const double kMPerDegree = kEarthRadiusM * glm::radians(1.0);

WeatherRegion region(double south, double north, double west, double east) {
  WeatherRegion r;
  r.lat = {south, north};
  r.lon = {west, east};
  return r;
}

// Ground distance (m) between two lat/lon points close together (flat-Earth approximation,
// longitude differences taken modulo 360).
double groundError(glm::dvec2 a, glm::dvec2 b) {
  const double dLon = std::remainder(a.y - b.y, 360.0);
  return std::hypot((a.x - b.x) * kMPerDegree,
                    dLon * kMPerDegree * std::cos(glm::radians(0.5 * (a.x + b.x))));
}

TEST(Geo, EnuAxesAreOrthonormalAndPointEastNorthUp) {
  const glm::dmat3 m0 = enuToEcefRotation(0.0, 0.0);
  EXPECT_NEAR(glm::distance(m0[0], glm::dvec3(0, 1, 0)), 0.0, 1e-15);  // east at 0N 0E: +y
  EXPECT_NEAR(glm::distance(m0[1], glm::dvec3(0, 0, 1)), 0.0, 1e-15);  // north: +z
  EXPECT_NEAR(glm::distance(m0[2], glm::dvec3(1, 0, 0)), 0.0, 1e-15);  // up: +x
  for (double lat : {-89.0, -30.0, 0.0, 47.37, 90.0})
    for (double lon : {-179.0, 0.0, 8.54, 120.0}) {
      const glm::dmat3 m = enuToEcefRotation(lat, lon);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          EXPECT_NEAR(glm::dot(m[i], m[j]), i == j ? 1.0 : 0.0, 1e-12) << lat << " " << lon;
      EXPECT_NEAR(glm::distance(glm::cross(m[0], m[1]), m[2]), 0.0, 1e-12);  // right-handed
      // Up is the direction of the place itself; north points toward the pole.
      EXPECT_NEAR(glm::distance(m[2], glm::normalize(ecefFromLatLonAltitude(lat, lon, 0))), 0.0,
                  1e-12);
      if (lat < 90.0) {
        EXPECT_GT(m[1].z, 0.0);
      }
    }
}

TEST(Geo, LatLonFromEcefInvertsThePlacement) {
  for (double lat : {-90.0, -45.5, 0.0, 12.25, 89.999})
    for (double lon : {-179.5, -90.0, 0.0, 33.3, 180.0}) {
      const glm::dvec2 back = latLonFromEcef(ecefFromLatLonAltitude(lat, lon, 1234.0));
      EXPECT_NEAR(back.x, lat, 1e-9);
      if (std::abs(lat) < 90.0) {
        EXPECT_NEAR(std::remainder(back.y - lon, 360.0), 0.0, 1e-9);
      }
    }
  EXPECT_NEAR(glm::length(ecefFromLatLonAltitude(10, 20, 500)), kEarthRadiusM + 500, 1e-6);
}

TEST(Geo, CameraFramePointsMapToLatLonAltitudeAndBack) {
  const GeoPosition cam{47.37, 8.54, 500.0};
  const glm::dvec3 here = latLonAltitude(cam, {0, 0, 0});
  EXPECT_NEAR(here.x, cam.latDeg, 1e-12);
  EXPECT_NEAR(here.y, cam.lonDeg, 1e-12);
  EXPECT_NEAR(here.z, cam.altitudeM, 1e-9);
  // Straight up: the same place, higher.
  const glm::dvec3 above = latLonAltitude(cam, {0, 0, 1000});
  EXPECT_NEAR(above.x, cam.latDeg, 1e-12);
  EXPECT_NEAR(above.z, 1500.0, 1e-9);
  // One degree of arc north along the ground: one degree of latitude, the ground curving
  // away below the camera's horizon plane.
  const glm::dvec3 north = geoPosition(cam, cam.latDeg + 1.0, cam.lonDeg, cam.altitudeM);
  EXPECT_NEAR(north.x, 0.0, 1e-6);
  EXPECT_NEAR(north.y, (kEarthRadiusM + 500) * std::sin(glm::radians(1.0)), 1e-6);
  EXPECT_NEAR(north.z, -(kEarthRadiusM + 500) * (1 - std::cos(glm::radians(1.0))), 1e-6);
  // East is +x: a point east of the camera has a larger longitude.
  EXPECT_GT(latLonAltitude(cam, {10000, 0, 0}).y, cam.lonDeg);

  std::mt19937 rng(3);
  std::uniform_real_distribution<double> h(-400e3, 400e3), v(-10e3, 20e3);
  for (const GeoPosition& c : {cam, GeoPosition{-89.5, 10, 0}, GeoPosition{0, 179.9, 12000}}) {
    for (int i = 0; i < 200; ++i) {
      const glm::dvec3 p(h(rng), h(rng), v(rng));
      const glm::dvec3 g = latLonAltitude(c, p);
      const glm::dvec3 back = geoPosition(c, g.x, g.y, g.z);
      ASSERT_NEAR(glm::distance(back, p), 0.0, 1e-6) << "camera lat " << c.latDeg;
      // The altitude is the distance from the centre less the radius.
      const double r = glm::length(p + glm::dvec3(0, 0, kEarthRadiusM + c.altitudeM));
      ASSERT_NEAR(g.z, r - kEarthRadiusM, 1e-6);
    }
  }
}

TEST(Geo, RegionUvRunsWestToEastAndNorthToSouth) {
  const WeatherRegion r = region(45, 50, 5, 12);
  glm::dvec2 uv;
  EXPECT_TRUE(regionUv(r, 50, 5, uv));  // north-west corner
  EXPECT_EQ(uv, glm::dvec2(0, 0));
  EXPECT_TRUE(regionUv(r, 45, 12, uv));  // south-east corner
  EXPECT_EQ(uv, glm::dvec2(1, 1));
  EXPECT_TRUE(regionUv(r, 47.5, 8.5, uv));
  EXPECT_NEAR(uv.x, 0.5, 1e-12);
  EXPECT_NEAR(uv.y, 0.5, 1e-12);
  // Texel (0, 0) of a 7 x 5 map is centred at uv (0.5 / 7, 0.5 / 5): the north-west texel.
  EXPECT_TRUE(regionUv(r, 50 - 0.5, 5 + 0.5, uv));
  EXPECT_NEAR(uv.x, 0.5 / 7, 1e-12);
  EXPECT_NEAR(uv.y, 0.5 / 5, 1e-12);
  EXPECT_FALSE(regionUv(r, 50.01, 8, uv));
  EXPECT_LT(uv.y, 0.0);
  EXPECT_FALSE(regionUv(r, 47, 4.9, uv));
  EXPECT_LT(uv.x, 0.0);
  EXPECT_FALSE(regionUv(r, 47, 12.1, uv));
  EXPECT_GT(uv.x, 1.0);

  // A region across the antimeridian, written with east past 180.
  const WeatherRegion pacific = region(-10, 10, 170, 200);
  EXPECT_TRUE(regionUv(pacific, 0, -175, uv));  // 185E
  EXPECT_NEAR(uv.x, 0.5, 1e-12);
  EXPECT_TRUE(regionUv(pacific, 0, 175, uv));
  EXPECT_NEAR(uv.x, 5.0 / 30, 1e-12);
  EXPECT_FALSE(regionUv(pacific, 0, -150, uv));  // 210E
  EXPECT_NEAR(uv.x, 40.0 / 30, 1e-12);
  EXPECT_FALSE(regionUv(pacific, 0, 160, uv));
  EXPECT_NEAR(uv.x, -10.0 / 30, 1e-12);
}

TEST(Geo, RegionSizeUsesRealKilometres) {
  const glm::dvec2 equator = regionSizeKm(region(-1, 1, 0, 2));
  EXPECT_NEAR(equator.x, 2 * kMPerDegree * 1e-3 * std::cos(0.0), 1e-9);
  EXPECT_NEAR(equator.y, 2 * kMPerDegree * 1e-3, 1e-9);
  const glm::dvec2 north = regionSizeKm(region(59, 61, 0, 2));
  EXPECT_NEAR(north.x, 0.5 * equator.x, 1e-9);  // cos 60 = 0.5
  EXPECT_NEAR(north.y, equator.y, 1e-9);
}

TEST(Geo, GpuStructsCarryTheFrame) {
  const GeoPosition cam{-33.9, 151.2, 250.0};
  const shared::GeoFrame f = geoFrame(cam);
  const glm::dmat3 m = enuToEcefRotation(cam.latDeg, cam.lonDeg);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(f.east[c], m[0][c], 1e-7);
    EXPECT_NEAR(f.north[c], m[1][c], 1e-7);
    EXPECT_NEAR(f.up[c], m[2][c], 1e-7);
  }
  EXPECT_EQ(f.origin, glm::vec4(-33.9f, 151.2f, 250.0f, float(kEarthRadiusM)));
  EXPECT_EQ(geoRegion(region(1, 2, 3, 4)).bounds, glm::vec4(1, 2, 3, 4));
}

// --- geo.glsl against the reference ---

constexpr int kQueries = 64;  // GEO_KERNEL_QUERIES in geo_kernel.comp
constexpr int kFrames = 4;    // GEO_KERNEL_FRAMES

struct Case {
  GeoPosition camera;
  WeatherRegion region;
};

TEST_F(GpuTest, GeoGlslMatchesTheReference) {
  const std::array<Case, kFrames> cases = {{
      {{47.37, 8.54, 500.0}, region(45, 50, 5, 12)},
      {{-33.9, 151.2, 10000.0}, region(-36, -31, 149, 154)},
      {{0.5, 179.5, 0.0}, region(-3, 3, 177, 183)},  // across the antimeridian
      {{88.0, -40.0, 3000.0}, region(85, 90, -180, 180)},
  }};
  // Points within 300 km and from the ground's drop to 15 km up; places within 3 degrees of
  // the camera, some outside the region.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<glm::vec4> queries(2 * kQueries * kFrames);
  struct Query {
    glm::dvec3 p;    // as the GPU gets it (float), in double
    glm::dvec3 geo;  // lat, lon, altitude as the GPU gets them
  };
  std::vector<Query> q(size_t(kQueries) * kFrames);
  for (int f = 0; f < kFrames; ++f)
    for (int i = 0; i < kQueries; ++i) {
      const GeoPosition& c = cases[size_t(f)].camera;
      const glm::vec3 p(float(600e3 * (unit(rng) - 0.5)), float(600e3 * (unit(rng) - 0.5)),
                        float(-7000.0 + 22000.0 * unit(rng)));
      const glm::vec3 g(float(std::min(c.latDeg + 6.0 * (unit(rng) - 0.5), 89.9)),
                        float(c.lonDeg + 6.0 * (unit(rng) - 0.5)), float(12000.0 * unit(rng)));
      queries[size_t(2 * kQueries * f + i)] = glm::vec4(p, 0.0f);
      queries[size_t(2 * kQueries * f + kQueries + i)] = glm::vec4(g, 0.0f);
      q[size_t(kQueries * f + i)] = {glm::dvec3(p), glm::dvec3(g)};
    }
  struct FramesBlock {
    shared::GeoFrame frames[kFrames];
    shared::GeoRegion regions[kFrames];
  } block;
  for (int f = 0; f < kFrames; ++f) {
    block.frames[f] = geoFrame(cases[size_t(f)].camera);
    block.regions[f] = geoRegion(cases[size_t(f)].region);
  }

  ShaderCompiler compiler(shaderDir(), std::nullopt);
  const CompiledShader shader =
      compiler.compile(std::filesystem::path(SKY_WEATHER_TEST_DIR) / "geo_kernel.comp");
  ComputePipeline pipeline(ctx(), "geo_kernel", shader.spirv, shader.reflection);
  GraphRuntime runtime(ctx());
  FrameGraph graph(runtime);
  ImageId results;
  GraphBuilder b = graph.addPass("geo_kernel", [&](PassContext& pc) {
    pc.dispatch(pipeline,
                {Binding::of(0, pc.uniform(block)),
                 Binding::of(1, pc.uniform(queries.data(), queries.size() * sizeof(glm::vec4))),
                 Binding::of(2, results)},
                1, kFrames);
  });
  ImageDesc desc;
  desc.name = "results";
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.width = kQueries;
  desc.height = 3 * kFrames;
  results = b.write(b.create(desc), Access::StorageWriteCompute);
  graph.requestOutput(results, "results");
  const std::vector<float> out = graph.execute().output("results").pixels;
  auto texel = [&](int x, int y) {
    const size_t i = (size_t(y) * kQueries + size_t(x)) * 4;
    return glm::dvec4(out[i], out[i + 1], out[i + 2], out[i + 3]);
  };

  // Float on the GPU: positions good to a metre (a float ulp at the Earth's radius is 0.5 m),
  // altitudes to a centimetre (the cancellation-free form), uv to float rounding.
  double worst[4] = {0, 0, 0, 0};
  for (int f = 0; f < kFrames; ++f) {
    const Case& c = cases[size_t(f)];
    // The reference sees the frame's camera as the GPU does (float lat/lon/altitude).
    const GeoPosition cam{double(float(c.camera.latDeg)), double(float(c.camera.lonDeg)),
                          double(float(c.camera.altitudeM))};
    for (int i = 0; i < kQueries; ++i) {
      SCOPED_TRACE("frame " + std::to_string(f) + " query " + std::to_string(i));
      const Query& x = q[size_t(kQueries * f + i)];
      const glm::dvec3 ref = latLonAltitude(cam, x.p);
      const glm::dvec4 got = texel(i, 3 * f);
      const double ground = groundError({got.x, got.y}, {ref.x, ref.y});
      // GPU atan is good to a relative error (lavapipe's to about 2e-5), and the angles are
      // offsets from the camera: the error grows with the distance from the camera, not with
      // the Earth's radius.
      const double distance = glm::length(glm::dvec2(x.p));
      EXPECT_LT(ground, 1.0 + 5e-5 * distance) << "distance " << distance;
      EXPECT_NEAR(got.z, ref.z, 0.01);
      EXPECT_GT(got.y, -180.0);  // the longitude range of latLonFromEcef
      EXPECT_LE(got.y, 180.0);

      const glm::dvec3 pos = geoPosition(cam, x.geo.x, x.geo.y, x.geo.z);
      const glm::dvec4 gotPos = texel(i, 3 * f + 1);
      const double posError = glm::distance(glm::dvec3(gotPos), pos);
      EXPECT_LT(posError, 1.0);
      EXPECT_NEAR(gotPos.w, x.geo.z, 0.01);  // geoAltitude of geoPosition: the altitude asked

      glm::dvec2 uv;
      const bool inside = regionUv(c.region, x.geo.x, x.geo.y, uv);
      const glm::dvec4 gotUv = texel(i, 3 * f + 2);
      EXPECT_NEAR(gotUv.x, uv.x, 1e-5);
      EXPECT_NEAR(gotUv.y, uv.y, 1e-5);
      // Inside/outside agree except within float rounding of an edge.
      const double edge =
          std::min({std::abs(uv.x), std::abs(uv.x - 1), std::abs(uv.y), std::abs(uv.y - 1)});
      if (edge > 1e-5) {
        EXPECT_EQ(gotUv.z, inside ? 1.0 : 0.0);
      }
      worst[0] = std::max(worst[0], ground / (1.0 + distance));
      worst[1] = std::max(worst[1], std::abs(got.z - ref.z));
      worst[2] = std::max(worst[2], posError);
      worst[3] = std::max({worst[3], std::abs(gotUv.x - uv.x), std::abs(gotUv.y - uv.y)});
    }
  }
  RecordProperty("worst_ground_per_m", std::to_string(worst[0]));
  RecordProperty("worst_altitude_m", std::to_string(worst[1]));
  RecordProperty("worst_position_m", std::to_string(worst[2]));
  RecordProperty("worst_uv", std::to_string(worst[3]));
  std::printf(
      "geo.glsl worst: ground %.3g m per m from the camera, altitude %.3g m, position %.3g m, uv "
      "%.3g\n",
      worst[0], worst[1], worst[2], worst[3]);
  // The queries cover both sides of the regions' edges.
  int inside = 0;
  for (int f = 0; f < kFrames; ++f)
    for (int i = 0; i < kQueries; ++i) inside += texel(i, 3 * f + 2).z > 0.5;
  EXPECT_GT(inside, kFrames * kQueries / 8);
  EXPECT_LT(inside, kFrames * kQueries * 7 / 8);
}

}  // namespace
}  // namespace sky
