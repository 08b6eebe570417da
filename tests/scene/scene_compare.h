#pragma once
// Field-by-field Scene comparison for tests, written out by hand (not through the field
// description) so a field the description forgets shows up as a difference.
#include <gtest/gtest.h>

#include "engine/scene/scene.h"

namespace sky::test {

inline void expectSameScene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.output.width, b.output.width);
  EXPECT_EQ(a.output.height, b.output.height);
  EXPECT_EQ(a.output.name, b.output.name);
  EXPECT_EQ(a.output.exposureEv, b.output.exposureEv);
  EXPECT_EQ(a.output.display, b.output.display);
  EXPECT_EQ(a.output.view, b.output.view);
  EXPECT_EQ(a.camera.latitude, b.camera.latitude);
  EXPECT_EQ(a.camera.longitude, b.camera.longitude);
  EXPECT_EQ(a.camera.altitudeM, b.camera.altitudeM);
  EXPECT_EQ(a.camera.heading, b.camera.heading);
  EXPECT_EQ(a.camera.pitch, b.camera.pitch);
  EXPECT_EQ(a.camera.verticalFov, b.camera.verticalFov);
  EXPECT_EQ(a.time.instant, b.time.instant);
  EXPECT_EQ(a.sun.azimuth, b.sun.azimuth);
  EXPECT_EQ(a.sun.elevation, b.sun.elevation);
  EXPECT_EQ(a.sun.angularDiameter, b.sun.angularDiameter);
  EXPECT_EQ(a.sun.discIntensity, b.sun.discIntensity);
  EXPECT_EQ(a.sky.skyColor, b.sky.skyColor);
  EXPECT_EQ(a.sky.fogColor, b.sky.fogColor);
  EXPECT_EQ(a.sky.sunColor, b.sky.sunColor);
  EXPECT_EQ(a.sky.glowSize, b.sky.glowSize);
  EXPECT_EQ(a.sky.hazeHeight, b.sky.hazeHeight);
}

// A scene where every field differs from its default, with awkward values.
inline Scene unusualScene() {
  Scene s;
  s.output.width = 64;
  s.output.height = 36;
  s.output.name = "test-1.v2";
  s.output.exposureEv = -0.1;
  s.output.display = "Display \"P3\"";
  s.output.view = "64";
  s.camera.latitude = -33.8688;
  s.camera.longitude = 151.2093;
  s.camera.altitudeM = 0.1;
  s.camera.heading = 1.0 / 3.0;
  s.camera.pitch = -0.0;
  s.camera.verticalFov = 70.00000000000001;
  s.time.instant = IsoTime::parse("2024-12-21T05:30:00.125-03:30").value();
  s.sun.azimuth = 200.1;
  s.sun.elevation = 1e-7;
  s.sun.angularDiameter = 0.01;
  s.sun.discIntensity = 1e6;
  s.sky.skyColor = {0.1f, 0.2f, 0.3f};
  s.sky.fogColor = {1.0f / 3.0f, 0.0f, 1e-6f};
  s.sky.sunColor = {12.5f, 0.7f, 3e5f};
  s.sky.glowSize = 0.30000000000000004;
  s.sky.hazeHeight = 0.001;
  return s;
}

}  // namespace sky::test
