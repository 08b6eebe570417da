// The path-traced field's committed Cycles numbers (issue 46; tests/data/pathtrace/field_cycles.json,
// written by `FIELD_REFERENCE=... scripts/pathtrace/compare.sh field_...`, docs/cloud-model.md
// "A path-traced field"): the cloud-to-sky luminance ratio and the lit clouds' hue Cycles
// gives each field scene, lit by our sun and sky, with the clouds toward the sun outside the
// view in it too (256 samples since 2026-12-07). FieldLook holds ours to them: the ratio within
// 20 % and the hue within 8 degrees, the goals (field_compare.py on the full-size
// renders: -12.7 to +17.1 % and 0.0 to 1.2 degrees). It measures ours as
// scripts/pathtrace/field_compare.py does, so the two agree on our renders.
// These numbers were made with Cycles' sun at one illuminance, the layer middle's, at every
// altitude (the JSON's sun_profile: flat). Ours lights each altitude with the sun's light
// through the air down to it, and scripts/pathtrace now gives Cycles the same
// (sun_profile.py); on the single clouds that moved Cycles by -24 to +15 % at a low sun. The
// field's reference is still to be made again that way (docs/cloud-model.md, "The
// reference's sun at each altitude"), so these goals hold against the old reference only.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/volumetric_clouds/cloud_test_util.h"

namespace sky::test {
namespace {

namespace fs = std::filesystem;

nlohmann::json fieldReference() {
  // Reference numbers, not a scene: configs/ holds only scenes (SceneFiles loads them all).
  std::ifstream in(dataRoot() / "tests" / "data" / "pathtrace" / "field_cycles.json");
  EXPECT_TRUE(in) << "tests/data/pathtrace/field_cycles.json";
  return nlohmann::json::parse(in);
}

// The field scenes, configs/pathtrace/field_*.yaml.
std::set<std::string> fieldScenes() {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(configDir() / "pathtrace")) {
    const std::string stem = e.path().stem().string();
    if (e.path().extension() == ".yaml" && stem.rfind("field_", 0) == 0) names.insert(stem);
  }
  return names;
}

TEST(FieldReference, CoversEveryFieldSceneWithTheNumbersATestNeeds) {
  const nlohmann::json ref = fieldReference();
  const std::set<std::string> scenes = fieldScenes();
  EXPECT_EQ(scenes.size(), 5u);
  ASSERT_TRUE(ref.contains("scenes"));
  for (const std::string& name : scenes) {
    ASSERT_TRUE(ref["scenes"].contains(name)) << name;
    const nlohmann::json& s = ref["scenes"][name];
    const Scene scene = loadSceneFile(configDir() / "pathtrace" / (name + ".yaml"));
    EXPECT_EQ(s["size"][0].get<int>(), scene.output.width) << name;
    EXPECT_EQ(s["size"][1].get<int>(), scene.output.height) << name;
    EXPECT_EQ(s["range_box_m"]["min"].size(), 3u) << name;
    for (const char* world : {"cycles_sky", "cycles_nishita"}) {
      ASSERT_TRUE(s.contains(world)) << name << " " << world;
      const double ratio = s[world]["ratio"].get<double>();
      const double hue = s[world]["lit_hue_deg"].get<double>();
      EXPECT_TRUE(std::isfinite(ratio) && ratio > 0.05 && ratio < 20.0) << name << " " << world;
      EXPECT_TRUE(hue >= 0.0 && hue < 360.0) << name << " " << world;
    }
  }
}

// Our cloud-to-sky ratio and lit hue on the final image, as field_compare.py measures them.
struct FieldMeasure {
  double ratio = 0.0, litHueDeg = 0.0;
  size_t opaque = 0, clear = 0;
};

double hueDeg(const glm::dvec3& c) {
  const double mx = std::max({c.r, c.g, c.b}), mn = std::min({c.r, c.g, c.b});
  if (mx <= mn) return 0.0;
  const double d = mx - mn;
  double h = mx == c.r   ? std::fmod((c.g - c.b) / d, 6.0)
             : mx == c.g ? (c.b - c.r) / d + 2.0
                         : (c.r - c.g) / d + 4.0;
  h *= 60.0;
  return h < 0.0 ? h + 360.0 : h;
}

FieldMeasure measureField(const Scene& scene, const RenderedFrame& f, const nlohmann::json& box) {
  constexpr double kEarth = 6371000.0, kGround = 6360000.0;  // the export's frame; the sky's ground
  const double cam = scene.camera.altitudeM;
  const double horizonZ = -std::sqrt(std::max(1.0 - std::pow(kGround / (kGround + cam), 2.0), 0.0));
  // The top of the highest layer the boxes reach into.
  const double top = cam + box["max"][2].get<double>() > scene.clouds.mid.baseM
                         ? scene.clouds.mid.topM
                         : scene.clouds.low.topM;
  const ImageLayer& beauty = f.image.layers.at(0);
  const size_t stride = beauty.channels.size();
  const CloudLayerView clouds(f);
  std::vector<std::pair<double, glm::dvec3>> opaque;
  double skySum = 0.0;
  FieldMeasure m;
  for (int y = 0; y < f.image.height; ++y)
    for (int x = 0; x < f.image.width; ++x) {
      const glm::dvec3 d(pixelDirection(scene.camera, f.image.width, f.image.height, x, y));
      if (d.z <= horizonZ) continue;
      const double r0 = kEarth + cam, r1 = kEarth + top, b = r0 * d.z;
      const double t = -b + std::sqrt(std::max(b * b - r0 * r0 + r1 * r1, 0.0));
      const double ex = t * d.x, ny = t * d.y;
      if (ex < box["min"][0].get<double>() || ex > box["max"][0].get<double>() ||
          ny < box["min"][1].get<double>() || ny > box["max"][1].get<double>())
        continue;
      const float* p = &beauty.pixels[(size_t(y) * f.image.width + x) * stride];
      const glm::dvec3 rgb(p[0], p[1], p[2]);
      const double lum = 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b;
      const float a = clouds.at(x, y).alpha;
      if (a > 0.95f) opaque.push_back({lum, rgb});
      if (a < 0.02f) skySum += lum, ++m.clear;
    }
  m.opaque = opaque.size();
  if (opaque.empty() || m.clear == 0) return m;
  double cloudSum = 0.0;
  for (const auto& o : opaque) cloudSum += o.first;
  m.ratio = (cloudSum / double(opaque.size())) / (skySum / double(m.clear));
  // The brightest quarter (at or above the 75th percentile, as numpy's quantile puts it).
  std::vector<double> lums;
  for (const auto& o : opaque) lums.push_back(o.first);
  std::sort(lums.begin(), lums.end());
  const double pos = 0.75 * double(lums.size() - 1);
  const size_t i = size_t(pos);
  const double q = lums[i] + (pos - double(i)) * (lums[std::min(i + 1, lums.size() - 1)] - lums[i]);
  glm::dvec3 lit(0.0);
  for (const auto& o : opaque)
    if (o.first >= q) lit += o.second;
  m.litHueDeg = hueDeg(lit);
  return m;
}

class FieldLook : public CloudRenderTest {};

TEST_F(FieldLook, OurCloudToSkyRatiosAndHuesAreWithinTheGoalsOfCycles) {
  const nlohmann::json ref = fieldReference();
  for (const std::string& name : fieldScenes()) {
    const nlohmann::json& s = ref["scenes"][name];
    const Scene scene = loadSceneFile(configDir() / "pathtrace" / (name + ".yaml"));
    const FieldMeasure ours = measureField(scene, render(scene), s["range_box_m"]);
    const double cycles = s["cycles_sky"]["ratio"].get<double>();
    const double hue = s["cycles_sky"]["lit_hue_deg"].get<double>();
    std::printf(
        "%s: ratio ours %.3f Cycles %.3f (%+.1f %%), lit hue ours %.1f Cycles %.1f "
        "(%zu opaque, %zu clear pixels)\n",
        name.c_str(), ours.ratio, cycles, 100.0 * (ours.ratio / cycles - 1.0), ours.litHueDeg, hue,
        ours.opaque, ours.clear);
    EXPECT_NEAR(ours.ratio / cycles, 1.0, ref["goals"]["ratio_within"].get<double>()) << name;
    EXPECT_NEAR(std::remainder(ours.litHueDeg - hue, 360.0), 0.0,
                ref["goals"]["hue_within_deg"].get<double>())
        << name;
    // A 3 degree sun's path crosses kilometres of small clouds before it leaves the layer: the
    // light march's long step must read them, not step over them (cloud_light_march_shared.h,
    // CLOUD_LIGHT_LONG_PART_M). In 400 m parts these two views were +15.1 % and +17.1 %; in
    // 125 m parts to 3 km they are +8.3 % and +9.8 %. Tolerance: 12 %.
    if (name == "field_sun3_away" || name == "field_deck_sunset") {
      EXPECT_NEAR(ours.ratio / cycles, 1.0, 0.12) << name << ": the long step's parts";
    }
  }
}

}  // namespace
}  // namespace sky::test
