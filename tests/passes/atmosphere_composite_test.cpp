// passes/atmosphere_composite on the device: the shader against a C++ reference of Kozlov
// 3.1 lit by sun and moon (every pixel), the sun and moon discs' energy and phase, stars by
// night only, and golden images from day to night.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <glm/geometric.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine/core/paths.h"
#include "engine/io/exr.h"
#include "engine/io/image_metrics.h"
#include "engine/lighting/lighting_state.h"
#include "engine/render/camera.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene_io.h"
#include "engine/shader/shader_compiler.h"
#include "passes/atmosphere_composite/atmosphere_composite.h"
#include "gpu_test.h"
#include "kozlov_reference.h"

namespace sky {
namespace {
namespace fs = std::filesystem;

using test::referenceClearSky;
using test::referenceDirection;

// Solid angle of pixel (x, y) of a pinhole image: p^2 cos^3 t at angle t off axis.
double pixelSolidAngle(const CameraSettings& cam, int w, int h, int x, int y) {
  const shared::ViewState view = makeViewState(cam, w, h);
  const double cosT = glm::dot(referenceDirection(cam, w, h, x, y), glm::vec3(view.forward));
  return double(view.forward.w) * view.forward.w * cosT * cosT * cosT;
}

// Sum over the image of (beauty - sky) times solid angle, per channel: the illuminance the
// discs and stars add.
glm::dvec3 addedIlluminance(const RenderedFrame& frame, const CameraSettings& cam) {
  const ImageLayer* beauty = frame.image.find("");
  const ImageLayer* sky = frame.image.find("sky");
  const int w = frame.image.width, h = frame.image.height;
  glm::dvec3 sum(0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      for (int c = 0; c < 3; ++c)
        sum[c] +=
            (beauty->pixels[i * 4 + c] - sky->pixels[i * 3 + c]) * pixelSolidAngle(cam, w, h, x, y);
    }
  return sum;
}

class AtmosphereCompositeTest : public test::GpuTest {
protected:
  RenderedFrame render(const Scene& scene) {
    static ShaderCompiler compiler;
    if (!mRenderer) mRenderer = std::make_unique<Renderer>(ctx(), compiler);
    return mRenderer->render(scene);
  }
  RenderedFrame render(const Scene& scene, const char* time) {
    static ShaderCompiler compiler;
    if (!mRenderer) mRenderer = std::make_unique<Renderer>(ctx(), compiler);
    return mRenderer->render(scene, IsoTime::parse(time).value());
  }
  std::unique_ptr<Renderer> mRenderer;
};

TEST_F(AtmosphereCompositeTest, SkyLayerMatchesKozlov31Everywhere) {
  Scene scene = loadSceneFile(configDir() / "tests" / "clear_sky_low.yaml");
  scene.camera.pitch = 0;  // horizon across the middle: haze, fog below, glow and sky above
  scene.camera.verticalFov = 120;
  RenderedFrame frame = render(scene);
  const ImageLayer* sky = frame.image.find("sky");
  ASSERT_NE(sky, nullptr);
  const int w = scene.output.width, h = scene.output.height;
  double worst = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::vec3 ref = referenceClearSky(referenceDirection(scene.camera, w, h, x, y),
                                        frame.lighting, scene.sky);
      for (int c = 0; c < 3; ++c) {
        double got = sky->pixels[(static_cast<size_t>(y) * w + x) * 3 + c];
        // Half-float storage: 11 significant bits.
        worst = std::max(worst, std::abs(got - ref[c]) / std::max(1e-3, std::abs(double(ref[c]))));
      }
    }
  EXPECT_LT(worst, 2e-3) << "largest relative error against the C++ Kozlov 3.1 reference";
}

TEST_F(AtmosphereCompositeTest, SunDiscKeepsItsEnergyAndHidesBelowTheHorizon) {
  Scene scene = loadSceneFile(configDir() / "tests" / "clear_sky_high.yaml");
  RenderedFrame frame = render(scene);
  // The disc must carry pi r^2 L: box filtering adds at most ~8 %, the pixel grid a little more.
  const double r = 0.5 * scene.sun.angularDiameter * 3.14159265358979 / 180;
  const double expected = 3.14159265358979 * r * r * frame.lighting.gpu.sunDisc.g;
  EXPECT_NEAR(addedIlluminance(frame, scene.camera).g, expected, 0.15 * expected);
  // ...which is the sun's illuminance through the atmosphere (the uniform disc's solid
  // angle is pi r^2 to 1e-5 at this size).
  EXPECT_NEAR(expected, frame.lighting.gpu.sun.illuminance.g, 1e-3 * expected);

  // Set, it leaves the sky above the horizon as it is: the camera's 80-degree view 30 degrees
  // up meets the horizon at row 30, and rows 0-25 lie above it across the whole width. Only
  // the stars add to it, physically a millionth of the twilight sky.
  scene.sun.elevation = -2.0;
  frame = render(scene);
  const ImageLayer* beauty = frame.image.find("");
  const ImageLayer* sky = frame.image.find("sky");
  for (size_t i = 0; i < 64 * 26; ++i)
    ASSERT_NEAR(beauty->pixels[i * 4], sky->pixels[i * 3], 1e-5 * sky->pixels[i * 3]);
}

TEST_F(AtmosphereCompositeTest, ResolvedSunDiscIsDarkerAndRedderAtTheLimbWithItsEnergy) {
  // The sun placed at 180/45 degrees and looked at with a 1.5-degree field of view: the disc
  // (0.53 degrees) spans about 13 of the 36 rows. Its centre against a pixel at 85 % of the
  // radius: the linear limb-darkening law (Neckel & Labs' coefficients) gives 0.79 in green
  // and a redder limb. The disc's flux stays pi r^2 times its mean radiance.
  Scene scene = loadSceneFile(configDir() / "tests" / "clear_sky_high.yaml");
  scene.sun.azimuth = 180.0;
  scene.sun.elevation = 45.0;
  scene.camera.heading = 180.0;
  scene.camera.pitch = 45.0;
  scene.camera.verticalFov = 1.5;
  const RenderedFrame frame = render(scene);
  const ImageLayer* beauty = frame.image.find("");
  const ImageLayer* sky = frame.image.find("sky");
  const int w = frame.image.width;
  auto disc = [&](int x, int y) {
    const size_t i = static_cast<size_t>(y) * w + x;
    return glm::dvec3(beauty->pixels[i * 4] - sky->pixels[i * 3],
                      beauty->pixels[i * 4 + 1] - sky->pixels[i * 3 + 1],
                      beauty->pixels[i * 4 + 2] - sky->pixels[i * 3 + 2]);
  };
  // Pixel centres: the sun lies on the image centre (32, 18), between pixels 31/32 and 17/18.
  const double pixelDeg = scene.camera.verticalFov / 36.0;
  const double radiusPx = 0.5 * scene.sun.angularDiameter / pixelDeg;
  const int limbX = 32 + static_cast<int>(std::lround(0.85 * radiusPx - 0.5));
  const glm::dvec3 centre = disc(32, 18), limb = disc(limbX, 18);
  std::cout << "sun disc: centre " << centre.g << ", limb (x " << limbX << ") " << limb.g
            << ", R/B " << centre.r / centre.b << " -> " << limb.r / limb.b << "\n";
  EXPECT_LT(limb.g, 0.9 * centre.g);
  EXPECT_GT(limb.g, 0.6 * centre.g);
  EXPECT_GT(limb.r / limb.b, 1.05 * centre.r / centre.b);
  const double r = 0.5 * scene.sun.angularDiameter * 3.14159265358979 / 180;
  const double expected = 3.14159265358979 * r * r * frame.lighting.gpu.sunDisc.g;
  EXPECT_NEAR(addedIlluminance(frame, scene.camera).g, expected, 0.05 * expected);
}

// The composite compiles a disc out when no pixel can get a share of it
// (discReachesView): a disc whose centre lies just past the frame's edge must still be
// drawn where it reaches in, and one a few pixels further out may be left out.
TEST_F(AtmosphereCompositeTest, SunDiscJustPastTheEdgeIsStillDrawn) {
  Scene scene = loadSceneFile(configDir() / "tests" / "clear_sky_high.yaml");
  scene.sun.azimuth = 180.0;
  scene.sun.elevation = 45.0;
  scene.camera.pitch = 45.0;
  scene.camera.verticalFov = 1.5;
  const int w = scene.output.width, h = scene.output.height;
  const double pixelDeg = scene.camera.verticalFov / h;
  const double radiusPx = 0.5 * scene.sun.angularDiameter / pixelDeg;  // ~6 pixels
  const double halfWidthDeg =
      std::atan(std::tan(0.75 * 3.14159265358979 / 180) * w / h) * 180 / 3.14159265358979;
  // Facing south the sun lies to the right by the heading's offset (times cos 45 degrees in
  // angle, at 45 degrees up): its centre `beyondPx` pixels past the right edge.
  auto edgeExcess = [&](double beyondPx) {
    scene.camera.heading =
        180.0 - (halfWidthDeg + beyondPx * pixelDeg) / std::cos(3.14159265358979 / 4);
    const RenderedFrame frame = render(scene);
    const ImageLayer* beauty = frame.image.find("");
    const ImageLayer* sky = frame.image.find("sky");
    double most = 0;
    for (int y = 0; y < h; ++y) {
      const size_t i = static_cast<size_t>(y) * w + (w - 1);
      most = std::max(most, double(beauty->pixels[i * 4 + 1] - sky->pixels[i * 3 + 1]) /
                                sky->pixels[i * 3 + 1]);
    }
    return most;
  };
  EXPECT_GT(edgeExcess(0.5 * radiusPx), 10.0) << "the disc's left part lies in the last column";
  EXPECT_LT(edgeExcess(radiusPx + 4.0), 1e-5) << "the disc lies wholly outside";

  const shared::ViewState view = makeViewState(scene.camera, w, h);
  const glm::vec3 forward(view.forward), right(view.right);
  const float r = static_cast<float>(0.5 * scene.sun.angularDiameter * 3.14159265358979 / 180);
  auto along = [&](double angle) {
    return glm::normalize(float(std::cos(angle)) * forward + float(std::sin(angle)) * right);
  };
  EXPECT_TRUE(discReachesView(view, forward, r));
  EXPECT_FALSE(discReachesView(view, -forward, r));
  // The corner pixel's centre, and a disc just reaching it from outward along the diagonal.
  const glm::vec3 corner = referenceDirection(scene.camera, w, h, w - 1, 0);
  const double cornerAngle = std::acos(glm::dot(corner, forward));
  const glm::vec3 outward = glm::normalize(corner - forward * glm::dot(corner, forward));
  const double reach = cornerAngle + r + 0.4 * view.forward.w;
  EXPECT_TRUE(discReachesView(
      view, glm::normalize(float(std::cos(reach)) * forward + float(std::sin(reach)) * outward),
      r));
  EXPECT_FALSE(discReachesView(view, along(cornerAngle + r + 4.0 * view.forward.w + 2e-3), r));
}

// The moon seen from Zurich with a 1-degree field of view, so the disc spans about 19 pixels.
Scene moonCloseUp(double moonAzimuth, double moonElevation) {
  Scene scene = loadSceneFile(configDir() / "tests" / "night_full_moon.yaml");
  scene.camera.heading = moonAzimuth;
  scene.camera.pitch = moonElevation;
  scene.camera.verticalFov = 1.0;
  return scene;
}

TEST_F(AtmosphereCompositeTest, MoonDiscCarriesTheKrisciunasSchaeferFlux) {
  // The full moon of 2024-06-22 01:08 UTC.
  const char* time = "2024-06-22T00:30:00+02:00";
  const LightingState st = computeLighting(moonCloseUp(0, 0), IsoTime::parse(time).value());
  Scene scene = moonCloseUp(st.moon.azimuthDeg, st.moon.elevationDeg);
  RenderedFrame frame = render(scene, time);
  // Everything the disc adds (earthshine included, 1e-4 of it) is the moon's illuminance.
  const glm::dvec3 added = addedIlluminance(frame, scene.camera);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(added[c], frame.lighting.gpu.moon.illuminance[c],
                0.03 * frame.lighting.gpu.moon.illuminance[c]);
}

TEST_F(AtmosphereCompositeTest, MoonIsLitOnTheBrightLimbSide) {
  // First quarter, 2024-06-14 05:18 UTC; the moon is up in Zurich that evening.
  const char* time = "2024-06-14T22:00:00+02:00";
  const LightingState st = computeLighting(moonCloseUp(0, 0), IsoTime::parse(time).value());
  ASSERT_GT(st.moon.elevationDeg, 10.0);
  ASSERT_NEAR(st.ephemeris.moon.illuminatedFraction, 0.5, 0.1);
  Scene scene = moonCloseUp(st.moon.azimuthDeg, st.moon.elevationDeg);
  RenderedFrame frame = render(scene, time);
  const ImageLayer* beauty = frame.image.find("");
  const ImageLayer* sky = frame.image.find("sky");
  // The light-weighted centre of the disc must lie toward the bright limb, and the far side
  // must show earthshine only.
  const int w = scene.output.width, h = scene.output.height;
  const glm::dvec3 limb = glm::dvec3(frame.lighting.gpu.moonLimb);
  const double sinR = std::sin(frame.lighting.gpu.moon.direction.w);
  double weighted = 0.0, total = 0.0, darkSide = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      const double added = beauty->pixels[i * 4 + 1] - sky->pixels[i * 3 + 1];
      const double along = glm::dot(glm::dvec3(referenceDirection(scene.camera, w, h, x, y)), limb);
      weighted += added * along;
      total += added;
      if (along < -0.5 * sinR && along > -0.8 * sinR) darkSide = std::max(darkSide, added);
    }
  ASSERT_GT(total, 0.0);
  EXPECT_GT(weighted / total, 0.25 * sinR);
  EXPECT_LE(darkSide, 1.05 * frame.lighting.gpu.moonEarthshine.g);
  EXPECT_GT(darkSide, 0.5 * frame.lighting.gpu.moonEarthshine.g) << "earthshine on the dark side";
}

TEST_F(AtmosphereCompositeTest, StarsShineOnlyInTheDark) {
  // New moon 2024-06-06 12:38 UTC: a moonless night in Zurich, and the same view at noon.
  Scene scene = loadSceneFile(configDir() / "tests" / "night_full_moon.yaml");
  scene.camera.heading = 0;
  scene.camera.pitch = 45;
  RenderedFrame night = render(scene, "2024-06-06T01:00:00+02:00");
  ASSERT_EQ(night.lighting.key, "moon");
  ASSERT_LT(night.lighting.moon.elevationDeg, -5.0);
  const ImageLayer* beauty = night.image.find("");
  const ImageLayer* sky = night.image.find("sky");
  int starPixels = 0;
  for (size_t i = 0; i < 64 * 36; ++i)
    if (beauty->pixels[i * 4 + 1] > 1.1f * sky->pixels[i * 3 + 1]) ++starPixels;
  EXPECT_GE(starPixels, 10) << "pixels where stars outshine the night sky by 10 %";

  const auto hasStarPasses = [](const RenderedFrame& f) {
    return std::any_of(f.frame.passes.begin(), f.frame.passes.end(),
                       [](const PassTiming& t) { return t.name == "star_field"; });
  };
  EXPECT_TRUE(hasStarPasses(night));

  RenderedFrame noon = render(scene, "2024-06-06T13:00:00+02:00");
  const glm::dvec3 added = addedIlluminance(noon, scene.camera);
  EXPECT_LT(added.g, 1e-6 * noon.lighting.gpu.sun.illuminance.g) << "no stars by day";
  EXPECT_FALSE(hasStarPasses(noon)) << "no star passes by day";
  // Through a long lens (a 0.05 degree field, pixels of 1.4 arcseconds) Sirius outshines a
  // pixel's worth of the noon sky, as it does in a telescope: the passes stay.
  scene.camera.verticalFov = 0.05;
  EXPECT_TRUE(hasStarPasses(render(scene, "2024-06-06T13:00:00+02:00")));
  // Vega's 2.5e-6 lux is 8e-11 renderer units; a 1280 x 720 pixel of a 60 degree view spans
  // 2e-6 sr; the noon sky is about 0.3 units.
  EXPECT_FALSE(starsVisible(-1.46, 8e-11, 2e-6, 0.3)) << "Sirius in a 720p pixel at noon";
  EXPECT_TRUE(starsVisible(-1.46, 8e-11, 1e-11, 0.3)) << "in a telescope's pixel";
  EXPECT_TRUE(starsVisible(-1.46, 8e-11, 2e-6, 1e-4)) << "in a dark sky";
}

TEST_F(AtmosphereCompositeTest, KozlovSkyTakesThePhysicalSkysHueAndPalesTowardTheHorizon) {
  // The default palette against sky.model physical at the same sun elevations (10, 30 and 60
  // degrees), 64x32 equirectangular: the zenith's chromaticity (r/g and b/g) within 15 % of
  // the physical sky's; and 90 degrees from the sun, below its most saturated row the kozlov
  // sky pales steadily to the horizon, which keeps at most 0.6 of that saturation. (That row
  // lies just above the haze top, 15-20 degrees up, where Kozlov's glow has faded and the
  // haze not begun: 0.85 against the physical sky's even 0.76 there; a known limit.) The old
  // palette's peach glow over a deep blue mixed to lavender around the sun.
  auto sky = [&](const char* model, double elevation) {
    Scene scene = loadSceneFile(configDir() / "examples" / "clear_noon.json");
    scene.output.width = 64;
    scene.output.height = 32;
    scene.camera.projection = CameraProjection::Equirectangular;
    scene.camera.heading = 180.0;
    scene.sun.azimuth = 180.0;
    scene.sun.elevation = elevation;
    scene.sky.model = std::string(model) == "physical" ? SkyModel::Physical : SkyModel::Kozlov;
    scene.highClouds.cover = 0.0;
    return render(scene);
  };
  auto rgb = [](const RenderedFrame& f, int x, int y) {
    const ImageLayer* l = f.image.find("sky");
    const float* p = &l->pixels[(static_cast<size_t>(y) * f.image.width + x) * 3];
    return glm::dvec3(p[0], p[1], p[2]);
  };
  auto saturation = [](glm::dvec3 c) {
    const double hi = std::max({c.r, c.g, c.b}), lo = std::min({c.r, c.g, c.b});
    return (hi - lo) / hi;
  };
  for (double elevation : {10.0, 30.0, 60.0}) {
    SCOPED_TRACE("sun at " + std::to_string(elevation));
    const RenderedFrame kozlov = sky("kozlov", elevation), physical = sky("physical", elevation);
    glm::dvec3 zk(0.0), zp(0.0);
    for (int x = 0; x < 64; ++x) zk += rgb(kozlov, x, 0), zp += rgb(physical, x, 0);
    std::cout << "sun " << elevation << ": zenith r/g, b/g kozlov " << zk.r / zk.g << ", "
              << zk.b / zk.g << "; physical " << zp.r / zp.g << ", " << zp.b / zp.g << "\n";
    EXPECT_NEAR(zk.r / zk.g, zp.r / zp.g, 0.15 * zp.r / zp.g);
    EXPECT_NEAR(zk.b / zk.g, zp.b / zp.g, 0.15 * zp.b / zp.g);
    // Column 16 looks 90 degrees from the sun; rows 0 (zenith) to 15 (the horizon).
    int peak = 0;
    for (int y = 1; y < 16; ++y)
      if (saturation(rgb(kozlov, 16, y)) > saturation(rgb(kozlov, 16, peak))) peak = y;
    double last = saturation(rgb(kozlov, 16, peak));
    const double most = last;
    for (int y = peak + 1; y < 16; ++y) {
      const double s = saturation(rgb(kozlov, 16, y));
      // Below 0.1 the haze is white to the eye, and the sun's warm tint may turn its hue
      // from blue to cream there (0.04 to 0.06 in the last row with the sun 10 degrees up).
      EXPECT_LE(s, std::max(last + 1e-3, 0.1)) << "row " << y;
      last = s;
    }
    std::cout << "  saturation 90 degrees from the sun: most " << most << " (row " << peak
              << "), horizon " << last << "\n";
    EXPECT_LT(last, 0.6 * most);
  }
}

// Golden images: 64x36 renders of configs/tests/clear_sky_*.yaml against tests/golden/*.exr.
// Tolerance: PSNR >= 50 dB on RGB (peak = the reference's largest value) and max error
// <= 2 % of the peak, room for GPU-to-GPU float differences but not for a changed sky.
// SKY_UPDATE_GOLDEN=1 rewrites the references instead (scripts/update-goldens.sh).
class ClearSkyGolden : public AtmosphereCompositeTest,
                       public ::testing::WithParamInterface<const char*> {};

std::vector<float> rgbOf(const LayeredImage& image) {
  const ImageLayer* l = image.find("");
  std::vector<float> rgb;
  for (size_t i = 0; i < l->pixels.size() / 4; ++i)
    for (int c = 0; c < 3; ++c) rgb.push_back(l->pixels[i * 4 + c]);
  return rgb;
}

TEST_P(ClearSkyGolden, MatchesReference) {
  const std::string name = GetParam();
  Scene scene = loadSceneFile(configDir() / "tests" / (name + ".yaml"));
  ASSERT_EQ(scene.output.width, 64);
  ASSERT_EQ(scene.output.height, 36);
  RenderedFrame frame = render(scene);
  const fs::path golden =
      fs::path(std::getenv("SKY_TEST_DATA")).parent_path() / "golden" / (name + ".exr");
  if (const char* u = std::getenv("SKY_UPDATE_GOLDEN"); u && std::string(u) == "1") {
    writeExr(golden, frame.image);
    GTEST_SKIP() << "wrote " << golden;
  }
  LayeredImage reference = readExr(golden);
  std::vector<float> got = rgbOf(frame.image), want = rgbOf(reference);
  ASSERT_EQ(got.size(), want.size());
  const double peak = *std::max_element(want.begin(), want.end());
  EXPECT_GE(psnr(got, want, peak), 50.0);
  EXPECT_LE(maxAbsError(got, want), 0.02 * peak);
}

INSTANTIATE_TEST_SUITE_P(DayToNight, ClearSkyGolden,
                         ::testing::Values("clear_sky_high", "clear_sky_low", "clear_sky_sunset",
                                           "civil_twilight", "night_full_moon"));

TEST(ClearSkyGoldenSet, ReferencesDifferFromEachOther) {
  // Guards against references that could not catch a moved sun.
  const fs::path dir = fs::path(std::getenv("SKY_TEST_DATA")).parent_path() / "golden";
  std::vector<float> high = rgbOf(readExr(dir / "clear_sky_high.exr"));
  std::vector<float> low = rgbOf(readExr(dir / "clear_sky_low.exr"));
  std::vector<float> sunset = rgbOf(readExr(dir / "clear_sky_sunset.exr"));
  const double peak = *std::max_element(high.begin(), high.end());
  EXPECT_LT(psnr(high, low, peak), 40.0);
  EXPECT_LT(psnr(low, sunset, peak), 40.0);
}

// The composite's bands (lavapipe runs every side of a branch for every pixel, so a band
// compiles out what its rows cannot see): checked against every pixel's own direction.
shared::AtmosphereCompositeParams bandParams(const CameraSettings& cam, int w, int h,
                                             double altitudeM) {
  shared::AtmosphereCompositeParams p{};
  p.view = makeViewState(cam, w, h);
  p.observer = 1u;
  p.planetRadiusM = 6371e3f;
  p.cameraRadiusM = static_cast<float>(6371e3 + altitudeM);
  return p;
}

// A pixel centre's direction, pinhole or equirectangular (written from view_shared.h's
// description, apart from the shader).
glm::vec3 pixelDirection(const CameraSettings& cam, int w, int h, int x, int y) {
  if (cam.projection == CameraProjection::Perspective) return referenceDirection(cam, w, h, x, y);
  const double azimuth = cam.heading + 360.0 * ((x + 0.5) / w - 0.5);
  const double elevation = 90.0 - 180.0 * (y + 0.5) / h;
  return directionFromAzEl(azimuth, elevation);
}

// Each row's band must hold the ground if a pixel of the row looks at or below the horizon
// (within the half pixel the shader blends over), and the clouds' air if one looks above it.
void expectBandsCoverEveryRow(const CameraSettings& cam, int w, int h, double altitudeM,
                              const std::vector<CompositeBand>& bands) {
  const shared::AtmosphereCompositeParams p = bandParams(cam, w, h, altitudeM);
  const double hc = p.cameraRadiusM - p.planetRadiusM;
  const double horizonZ = -std::sqrt(hc * (2.0 * p.planetRadiusM + hc)) / double(p.cameraRadiusM);
  uint32_t next = 0;
  for (const CompositeBand& b : bands) {
    ASSERT_EQ(b.firstRow, next) << "bands must tile the image";
    next += b.rows;
    for (uint32_t y = b.firstRow; y < b.firstRow + b.rows; ++y)
      for (int x = 0; x < w; ++x) {
        const glm::vec3 d = pixelDirection(cam, w, h, x, static_cast<int>(y));
        const double pixel = p.view.forward.w;
        if (d.z < horizonZ + pixel) {
          ASSERT_TRUE(b.ground) << "row " << y << " sees the ground";
        }
        if (d.z > horizonZ - pixel) {
          ASSERT_TRUE(b.cloudAir) << "row " << y << " sees the sky";
        }
      }
  }
  EXPECT_EQ(next, static_cast<uint32_t>(h));
}

TEST(AtmosphereCompositeBands, TheGroundOnlyBelowTheHorizonAndTheCloudsAirOnlyAboveIt) {
  CameraSettings cam;  // the peer's view: 20 degrees up, 60 degrees vertical field of view
  cam.pitch = 20.0;
  cam.verticalFov = 60.0;
  cam.heading = 30.0;
  const int w = 320, h = 180;
  const std::vector<CompositeBand> bands =
      compositeBands(bandParams(cam, w, h, 10.0), true, true, 8);
  expectBandsCoverEveryRow(cam, w, h, 10.0, bands);
  ASSERT_GE(bands.size(), 3u);
  // The sky at the top needs no ground, the ground at the bottom no clouds' air; the ground
  // (the lowest 18 % of the image) and the band around the horizon are all that pays for it.
  EXPECT_EQ(bands.front(), (CompositeBand{0, bands.front().rows, false, true}));
  EXPECT_FALSE(bands.back().cloudAir);
  EXPECT_TRUE(bands.back().ground);
  uint32_t groundRows = 0;
  for (const CompositeBand& b : bands) groundRows += b.ground ? b.rows : 0;
  EXPECT_LT(groundRows, 0.3 * h);

  // From above the clouds' base every row may see clouds; looking down from 3 km, the
  // horizon dips and every row sees the ground.
  for (const CompositeBand& b : compositeBands(bandParams(cam, w, h, 10.0), true, false, 8))
    EXPECT_TRUE(b.cloudAir);
  cam.pitch = -40.0;
  const std::vector<CompositeBand> down =
      compositeBands(bandParams(cam, w, h, 3000.0), true, true, 8);
  expectBandsCoverEveryRow(cam, w, h, 3000.0, down);
  for (const CompositeBand& b : down) EXPECT_TRUE(b.ground);
  // Without volumetric clouds there is no clouds' air to compute.
  for (const CompositeBand& b : compositeBands(bandParams(cam, w, h, 10.0), false, true, 8))
    EXPECT_FALSE(b.cloudAir);
}

TEST(AtmosphereCompositeBands, AnEquirectangularImageAndATopDownOne) {
  CameraSettings cam;
  cam.projection = CameraProjection::Equirectangular;
  const int w = 256, h = 128;
  const std::vector<CompositeBand> bands =
      compositeBands(bandParams(cam, w, h, 10.0), true, true, 8);
  expectBandsCoverEveryRow(cam, w, h, 10.0, bands);
  EXPECT_FALSE(bands.front().ground);
  EXPECT_FALSE(bands.back().cloudAir);
  // A top-down render has no observer: no ground and no air anywhere, in one dispatch.
  shared::AtmosphereCompositeParams top = bandParams(cam, w, h, 10.0);
  top.observer = 0u;
  EXPECT_EQ(compositeBands(top, true, false, 8),
            (std::vector<CompositeBand>{{0, static_cast<uint32_t>(h), false, false}}));
}

}  // namespace
}  // namespace sky

namespace sky {
namespace {

// Every choice of the composite's variant reaches the shader as its own define, once: a
// field left out of compositeVariantDefines would compile every variant the same.
TEST(CompositeVariant, EachFieldIsOneDefineOfTheShader) {
  const CompositeVariant base;
  const std::vector<ShaderDefine> defines = compositeVariantDefines(base);
  std::vector<std::string> names;
  for (const ShaderDefine& d : defines) names.push_back(d.name);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end()) << "a define twice";
  auto changed = [&](CompositeVariant v) {
    const std::vector<ShaderDefine> other = compositeVariantDefines(v);
    int n = 0;
    for (size_t i = 0; i < defines.size(); ++i) n += defines[i].value != other[i].value;
    return n;
  };
  CompositeVariant v = base;
  v.sky = CompositeSky::Physical;
  EXPECT_EQ(changed(v), 1);
  for (bool CompositeVariant::*field :
       {&CompositeVariant::clouds, &CompositeVariant::stars, &CompositeVariant::sunDisc,
        &CompositeVariant::moonDisc, &CompositeVariant::ground, &CompositeVariant::cloudAir,
        &CompositeVariant::host, &CompositeVariant::hostDepth, &CompositeVariant::perception}) {
    v = base;
    v.*field = !(v.*field);
    EXPECT_EQ(changed(v), 1);
  }
  v = base;
  v.hostFormat = HostColourFormat::Rgba32f;
  EXPECT_EQ(changed(v), 1);
}

}  // namespace
}  // namespace sky
