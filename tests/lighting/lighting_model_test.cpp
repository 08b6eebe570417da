// engine/lighting's light model and LightingState: each formula against its source, and the
// whole state over a day and night for continuity (no pop at any time step).
#include <cmath>
#include <cstddef>
#include <vector>

#include <gtest/gtest.h>

#include "engine/lighting/light_model.h"
#include "engine/lighting/lighting_state.h"
#include "engine/scene/scene.h"

namespace sky {
namespace {

TEST(LightModel, KastenYoungAirMass) {
  EXPECT_NEAR(light::airMass(90.0), 1.0, 1e-3);
  EXPECT_NEAR(light::airMass(30.0), 1.995, 0.01);  // close to 1 / sin 30 this high
  // Kasten & Young's horizon value, 37.92 (their table 2).
  EXPECT_NEAR(light::airMass(0.0), 37.92, 0.2);
  EXPECT_EQ(light::airMass(-5.0), light::airMass(-1.0));  // clamped, not turning back
}

TEST(LightModel, TransmittanceReddensTowardTheHorizon) {
  glm::dvec3 zenith = light::atmosphereTransmittance(90.0, 0.0, 0.1);
  EXPECT_GT(zenith.r, zenith.g);
  EXPECT_GT(zenith.g, zenith.b);
  EXPECT_GT(zenith.b, 0.6);
  EXPECT_LT(zenith.r, 0.95);
  glm::dvec3 low = light::atmosphereTransmittance(3.0, 0.0, 0.1);
  EXPECT_GT(low.r / low.b, 5.0);
  // Thinner air above: more light at 3000 m than at sea level.
  EXPECT_GT(light::atmosphereTransmittance(10.0, 3000.0, 0.1).b,
            light::atmosphereTransmittance(10.0, 0.0, 0.1).b);
  // Aerosols dim it.
  EXPECT_LT(light::atmosphereTransmittance(30.0, 0.0, 0.5).g,
            light::atmosphereTransmittance(30.0, 0.0, 0.05).g);
}

TEST(LightModel, DiscAboveHorizonIsTheSegmentArea) {
  EXPECT_DOUBLE_EQ(light::discAboveHorizon(0.3, 0.25), 1.0);
  EXPECT_DOUBLE_EQ(light::discAboveHorizon(-0.3, 0.25), 0.0);
  EXPECT_NEAR(light::discAboveHorizon(0.0, 0.25), 0.5, 1e-12);
  // Height r/2 above the chord: segment area (acos(-1/2) + 1/2 sqrt(3/4)) / pi.
  EXPECT_NEAR(light::discAboveHorizon(0.125, 0.25),
              (std::acos(-0.5) + 0.5 * std::sqrt(0.75)) / M_PI, 1e-12);
  double previous = 0.0;
  for (double e = -0.3; e <= 0.3; e += 0.001) {
    double v = light::discAboveHorizon(e, 0.25);
    EXPECT_GE(v, previous);
    EXPECT_LT(v - previous, 0.01);  // continuous
    previous = v;
  }
}

TEST(LightModel, KrisciunasSchaeferMoonIlluminance) {
  // K&S (1991) eq. 8 at full moon and mean distance: 10^(-0.4 * 3.84) fc = 0.313 lux.
  EXPECT_NEAR(light::moonIlluminanceLux(0.0, 384400.0), 0.313, 0.002);
  // A quarter moon gives about a tenth of the full moon's light (0.091 by the formula).
  EXPECT_NEAR(light::moonIlluminanceLux(90.0, 384400.0) / light::moonIlluminanceLux(0.0, 384400.0),
              0.091, 0.002);
  // Inverse square in distance: perigee against apogee.
  EXPECT_NEAR(light::moonIlluminanceLux(0.0, 356500.0) / light::moonIlluminanceLux(0.0, 406700.0),
              std::pow(406700.0 / 356500.0, 2.0), 1e-9);
}

TEST(LightModel, DayFactorFallsFromDayToNight) {
  EXPECT_EQ(light::dayFactor(10.0), 1.0);
  EXPECT_EQ(light::dayFactor(0.0), 1.0);
  EXPECT_NEAR(light::dayFactor(-90.0), 0.0, 1e-12);
  double previous = 1.0, handover = 0.0;
  for (double h = 0.0; h >= -30.0; h -= 0.01) {
    double f = light::dayFactor(h);
    EXPECT_LE(f, previous + 1e-12);
    EXPECT_LT(previous - f, 0.01) << "jump at " << h;
    if (previous >= 0.5 && f < 0.5) handover = h;
    previous = f;
  }
  // The moon takes over where full moonlight (~0.3 lx) outshines the twilight sky: between
  // the end of civil twilight (3.4 lx) and nautical twilight (0.008 lx).
  EXPECT_LT(handover, -6.0);
  EXPECT_GT(handover, -12.0);
  EXPECT_DOUBLE_EQ(light::nightLiftEv(5.0, 0.8), 0.0);
  EXPECT_NEAR(light::nightLiftEv(-30.0, 0.8), 0.8 * light::nightLiftEv(-30.0, 1.0), 1e-12);
}

TEST(LightModel, HighCloudsStaySunlitAfterSunsetAndRedden) {
  const glm::vec3 space(4.0f);
  const glm::vec3 noon = light::illuminanceAtAltitude(space, 60.0, 0.265, 9000.0, 0.1);
  const glm::vec3 low = light::illuminanceAtAltitude(space, 2.0, 0.265, 9000.0, 0.1);
  const glm::vec3 after = light::illuminanceAtAltitude(space, -2.0, 0.265, 9000.0, 0.1);
  // At 9 km the horizon dips by acos(R / (R + h)) = 3.05 degrees.
  const glm::vec3 hidden = light::illuminanceAtAltitude(space, -3.5, 0.265, 9000.0, 0.1);
  EXPECT_GT(noon.g, 3.0f);
  EXPECT_GT(after.r, 0.0f) << "a 9 km layer still sees the sun 2 degrees below our horizon";
  EXPECT_EQ(hidden, glm::vec3(0.0f));
  EXPECT_GT(low.r / low.b, noon.r / noon.b) << "a low sun is redder";
  EXPECT_GT(after.r / after.b, low.r / low.b);
  // Continuous through elevation 0 (the two path models meet there).
  const glm::vec3 a = light::illuminanceAtAltitude(space, 1e-4, 0.265, 9000.0, 0.1);
  const glm::vec3 b = light::illuminanceAtAltitude(space, -1e-4, 0.265, 9000.0, 0.1);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-3 * a[c]);
  // At ground level there is no dip: the layer model is the observer's.
  EXPECT_EQ(light::illuminanceAtAltitude(space, -0.5, 0.0, 0.0, 0.1), glm::vec3(0.0f));
}

TEST(LightModel, MoonColourIsWarmAtUnitLuminance) {
  glm::dvec3 c = light::moonColor();
  EXPECT_NEAR(light::luminance(c), 1.0, 1e-12);
  EXPECT_GT(c.r, c.g);
  EXPECT_GT(c.g, c.b);
}

TEST(Palette, InterpolatesLinearlyAndClamps) {
  std::vector<PaletteKey> keys = {{-10, glm::vec3(0.0f)}, {10, glm::vec3(1.0f, 2.0f, 4.0f)}};
  EXPECT_EQ(interpolatePalette(keys, -50).skyColor, glm::vec3(0.0f));
  EXPECT_EQ(interpolatePalette(keys, 50).skyColor, glm::vec3(1.0f, 2.0f, 4.0f));
  PaletteKey mid = interpolatePalette(keys, 5);
  EXPECT_FLOAT_EQ(mid.skyColor.g, 1.5f);
  EXPECT_DOUBLE_EQ(mid.sunElevation, 5.0);
}

Scene zurich() {
  Scene s;
  s.camera.latitude = 47.37;
  s.camera.longitude = 8.54;
  return s;
}

TEST(LightingState, SunAndMoonFollowTheEphemerisUnlessOverridden) {
  Scene scene = zurich();
  IsoTime noon = IsoTime::parse("2024-06-21T13:30:00+02:00").value();
  LightingState st = computeLighting(scene, noon);
  EXPECT_EQ(st.key, "sun");
  EXPECT_EQ(st.dayFactor, 1.0);
  EXPECT_NEAR(st.sun.elevationDeg, st.ephemeris.sun.position.elevationDeg, 1e-12);
  EXPECT_FALSE(st.sun.overridden);
  EXPECT_GT(st.sun.illuminanceLux, 80000.0);
  EXPECT_LT(st.sun.illuminanceLux, 127500.0);
  EXPECT_NEAR(glm::length(st.sun.direction), 1.0, 1e-12);
  scene.sun.azimuth = 90.0;
  scene.sun.elevation = -30.0;
  st = computeLighting(scene, noon);
  EXPECT_TRUE(st.sun.overridden);
  EXPECT_EQ(st.key, "moon");  // the override decides day and night too
  EXPECT_EQ(st.sun.illuminanceLux, 0.0);
  EXPECT_NEAR(st.sun.direction.x, std::cos(30.0 * M_PI / 180), 1e-12);
}

TEST(LightingState, TheSameInstantInAnyZoneGivesTheSameSky) {
  const Scene scene = zurich();
  const LightingState utc = computeLighting(scene, IsoTime::parse("2024-02-29T10:00:00Z").value());
  for (const char* text : {"2024-02-29T11:00:00+01:00", "2024-02-29T19:00:00+09:00",
                           "2024-02-28T23:30:00-10:30", "2024-02-29T10:00:00.000Z"}) {
    const LightingState st = computeLighting(scene, IsoTime::parse(text).value());
    EXPECT_EQ(st.sun.azimuthDeg, utc.sun.azimuthDeg) << text;
    EXPECT_EQ(st.sun.elevationDeg, utc.sun.elevationDeg) << text;
    EXPECT_EQ(st.moon.elevationDeg, utc.moon.elevationDeg) << text;
    EXPECT_EQ(lightingJson(st)["time_utc"], "2024-02-29T10:00:00Z");
  }
}

TEST(LightingState, FullMoonMidnightIsLitByTheMoon) {
  // Full moon 2024-06-22 01:08 UTC; at local midnight in Zurich the sun is ~16.5 deg down.
  LightingState st = computeLighting(zurich(), IsoTime::parse("2024-06-22T00:30:00+02:00").value());
  EXPECT_EQ(st.key, "moon");
  EXPECT_GT(st.ephemeris.moon.illuminatedFraction, 0.99);
  EXPECT_GT(st.moon.elevationDeg, 5.0);
  // Full moonlight reaches the ground at a few tenths of a lux less the extinction.
  EXPECT_GT(st.moon.illuminanceLux, 0.05);
  EXPECT_LT(st.moon.illuminanceLux, 0.35);
  // Physical (the display lifts it), the moon is the stronger light by far.
  EXPECT_GT(st.gpu.moon.illuminance.g, 100.0f * st.gpu.sun.illuminance.g);
  // The bright limb tangent is perpendicular to the moon's direction.
  EXPECT_NEAR(glm::dot(glm::dvec3(st.gpu.moonLimb), st.moon.direction), 0.0, 1e-6);
}

// No pop at any time step: over a day and a night in 1-minute steps, no float of the GPU
// state moves by more than 5 % of its own largest magnitude that day, or 15 % of its own
// value, in one minute; a pop (a switch of key light, a lift applied in one step) moves a
// value by most of its range at once. The state is physical, and around sunrise the sky's
// light really grows by up to ~10 % a minute (the twilight illuminance rises 0.3 decades a
// degree). The exceptions are the shares of the sun's and moon's discs above the horizon,
// which honestly go from 1 to 0 in the 2-4 minutes a disc takes to set: at most 0.6 a minute
// (the segment area's steepest slope, 2/pi per radius, times 0.25 deg/min over 0.265 deg).
TEST(LightingState, ChangesContinuouslyMinuteByMinute) {
  for (const char* startText : {"2024-06-21T12:00:00+02:00", "2024-12-14T12:00:00+01:00"}) {
    Scene scene = zurich();
    IsoTime start = IsoTime::parse(startText).value();
    constexpr int kMinutes = 24 * 60;
    constexpr size_t kFloats = sizeof(shared::LightingState) / sizeof(float);
    std::vector<std::vector<float>> series(kFloats, std::vector<float>(kMinutes + 1));
    for (int m = 0; m <= kMinutes; ++m) {
      LightingState st = computeLighting(scene, start.plusSeconds(60.0 * m));
      const float* f = reinterpret_cast<const float*>(&st.gpu);
      for (size_t i = 0; i < kFloats; ++i) series[i][m] = f[i];
    }
    for (size_t i = 0; i < kFloats; ++i) {
      float largest = 0.0f, worstExcess = -1.0f;
      int worstAt = 0;
      for (int m = 0; m <= kMinutes; ++m) largest = std::max(largest, std::fabs(series[i][m]));
      const bool discShare =
          i == offsetof(shared::LightingState, sun.illuminance.w) / sizeof(float) ||
          i == offsetof(shared::LightingState, moon.illuminance.w) / sizeof(float);
      for (int m = 1; m <= kMinutes; ++m) {
        const float a = series[i][m - 1], b = series[i][m];
        const float allowed = std::max((discShare ? 0.6f : 0.05f) * largest,
                                       0.15f * std::max(std::fabs(a), std::fabs(b))) +
                              1e-9f;
        const float excess = std::fabs(b - a) - allowed;
        if (excess > worstExcess) worstExcess = excess, worstAt = m;
      }
      EXPECT_LE(worstExcess, 0.0f)
          << startText << ": float " << i << " of LightingState jumps at minute " << worstAt;
    }
  }
}

}  // namespace
}  // namespace sky
