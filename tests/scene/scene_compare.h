#pragma once
// Field-by-field Scene comparison for tests, written out by hand (not through the field
// description) so a field the description forgets shows up as a difference.
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/scene.h"

namespace sky {

// Readable failures: "2024-06-21T12:00:00+02:00" rather than a byte dump.
inline void PrintTo(const IsoTime& t, std::ostream* os) {
  *os << t.format();
}

namespace test {

inline void expectSameColor(const glm::vec3& a, const glm::vec3& b, const char* name) {
  SCOPED_TRACE(name);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.z, b.z);
}

inline void expectSamePalette(const std::vector<PaletteKey>& a, const std::vector<PaletteKey>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE("palette[" + std::to_string(i) + "]");
    EXPECT_EQ(a[i].sunElevation, b[i].sunElevation);
    expectSameColor(a[i].skyColor, b[i].skyColor, "sky_color");
    expectSameColor(a[i].fogColor, b[i].fogColor, "fog_color");
    expectSameColor(a[i].glowColor, b[i].glowColor, "glow_color");
    expectSameColor(a[i].cloudLit, b[i].cloudLit, "cloud_lit");
    expectSameColor(a[i].cloudDark, b[i].cloudDark, "cloud_dark");
    expectSameColor(a[i].ambientTop, b[i].ambientTop, "ambient_top");
    expectSameColor(a[i].ambientBottom, b[i].ambientBottom, "ambient_bottom");
  }
}

inline void expectSameLighting(const LightingSettings& a, const LightingSettings& b) {
  EXPECT_EQ(a.pressureHpa, b.pressureHpa);
  EXPECT_EQ(a.temperatureC, b.temperatureC);
  EXPECT_EQ(a.turbidity, b.turbidity);
  EXPECT_EQ(a.nightAdaptation, b.nightAdaptation);
  EXPECT_EQ(a.starBrightness, b.starBrightness);
  EXPECT_EQ(a.starExtinction, b.starExtinction);
  expectSamePalette(a.palette, b.palette);
}

inline void expectSameScene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.output.width, b.output.width);
  EXPECT_EQ(a.output.height, b.output.height);
  EXPECT_EQ(a.output.name, b.output.name);
  EXPECT_EQ(a.output.exposure, b.output.exposure);
  EXPECT_EQ(a.output.exposureEv, b.output.exposureEv);
  EXPECT_EQ(a.output.exposureAdaptationS, b.output.exposureAdaptationS);
  EXPECT_EQ(a.output.nightLook, b.output.nightLook);
  EXPECT_EQ(a.output.display, b.output.display);
  EXPECT_EQ(a.output.view, b.output.view);
  EXPECT_EQ(a.camera.latitude, b.camera.latitude);
  EXPECT_EQ(a.camera.longitude, b.camera.longitude);
  EXPECT_EQ(a.camera.altitudeM, b.camera.altitudeM);
  EXPECT_EQ(a.camera.heading, b.camera.heading);
  EXPECT_EQ(a.camera.pitch, b.camera.pitch);
  EXPECT_EQ(a.camera.verticalFov, b.camera.verticalFov);
  EXPECT_EQ(a.camera.projection, b.camera.projection);
  EXPECT_EQ(a.camera.mode, b.camera.mode);
  // IsoTime's == compares the zone and the fraction too: a time that prints back in
  // another zone is a difference.
  EXPECT_EQ(a.time.start, b.time.start);
  EXPECT_EQ(a.time.end, b.time.end);
  EXPECT_EQ(a.time.stepSeconds, b.time.stepSeconds);
  EXPECT_EQ(a.sun.azimuth, b.sun.azimuth);
  EXPECT_EQ(a.sun.elevation, b.sun.elevation);
  EXPECT_EQ(a.sun.angularDiameter, b.sun.angularDiameter);
  EXPECT_EQ(a.sun.discScale, b.sun.discScale);
  EXPECT_EQ(a.moon.azimuth, b.moon.azimuth);
  EXPECT_EQ(a.moon.elevation, b.moon.elevation);
  EXPECT_EQ(a.moon.discScale, b.moon.discScale);
  EXPECT_EQ(a.moon.earthshine, b.moon.earthshine);
  EXPECT_EQ(a.sky.glowSize, b.sky.glowSize);
  EXPECT_EQ(a.sky.hazeHeight, b.sky.hazeHeight);
  EXPECT_EQ(a.sky.model, b.sky.model);
  const AtmosphereSettings &aa = a.atmosphere, &ba = b.atmosphere;
  EXPECT_EQ(aa.groundRadiusKm, ba.groundRadiusKm);
  EXPECT_EQ(aa.thicknessKm, ba.thicknessKm);
  expectSameColor(aa.rayleighScattering, ba.rayleighScattering, "rayleigh_scattering");
  EXPECT_EQ(aa.rayleighScaleHeightKm, ba.rayleighScaleHeightKm);
  EXPECT_EQ(aa.mieScattering, ba.mieScattering);
  EXPECT_EQ(aa.mieExtinction, ba.mieExtinction);
  EXPECT_EQ(aa.mieScaleHeightKm, ba.mieScaleHeightKm);
  EXPECT_EQ(aa.mieAnisotropy, ba.mieAnisotropy);
  expectSameColor(aa.ozoneAbsorption, ba.ozoneAbsorption, "ozone_absorption");
  EXPECT_EQ(aa.ozoneCenterKm, ba.ozoneCenterKm);
  EXPECT_EQ(aa.ozoneHalfWidthKm, ba.ozoneHalfWidthKm);
  EXPECT_EQ(aa.aerosols, ba.aerosols);
  expectSameColor(a.ground.albedo, b.ground.albedo, "ground.albedo");
  const HighCloudSettings &ah = a.highClouds, &bh = b.highClouds;
  EXPECT_EQ(ah.source, bh.source);
  EXPECT_EQ(ah.style, bh.style);
  EXPECT_EQ(ah.cover, bh.cover);
  EXPECT_EQ(ah.coverMap, bh.coverMap);
  EXPECT_EQ(ah.coefficients, bh.coefficients);
  EXPECT_EQ(ah.normals, bh.normals);
  EXPECT_EQ(ah.resolution, bh.resolution);
  EXPECT_EQ(ah.seed, bh.seed);
  EXPECT_EQ(ah.altitudeM, bh.altitudeM);
  EXPECT_EQ(ah.tileSizeKm, bh.tileSizeKm);
  EXPECT_EQ(ah.windSpeedMs, bh.windSpeedMs);
  EXPECT_EQ(ah.windFrom, bh.windFrom);
  EXPECT_EQ(ah.edgeGlowDeg, bh.edgeGlowDeg);
  EXPECT_EQ(ah.brightness, bh.brightness);
  EXPECT_EQ(ah.coverSource, bh.coverSource);
  const CloudSettings &ac = a.clouds, &bc = b.clouds;
  EXPECT_EQ(ac.quality, bc.quality);
  EXPECT_EQ(ac.temporal.mode, bc.temporal.mode);
  EXPECT_EQ(ac.temporal.block, bc.temporal.block);
  EXPECT_EQ(ac.temporal.resolution, bc.temporal.resolution);
  EXPECT_EQ(ac.light, bc.light);
  EXPECT_EQ(ac.model, bc.model);
  EXPECT_EQ(ac.coverage, bc.coverage);
  EXPECT_EQ(ac.extinction, bc.extinction);
  EXPECT_EQ(ac.g, bc.g);
  EXPECT_EQ(ac.phase, bc.phase);
  EXPECT_EQ(ac.gBack, bc.gBack);
  EXPECT_EQ(ac.backWeight, bc.backWeight);
  EXPECT_EQ(ac.attenuationClamp, bc.attenuationClamp);
  EXPECT_EQ(ac.stepM, bc.stepM);
  EXPECT_EQ(ac.stepGrowth, bc.stepGrowth);
  EXPECT_EQ(ac.maxSteps, bc.maxSteps);
  EXPECT_EQ(ac.samples, bc.samples);
  EXPECT_EQ(ac.lightSteps, bc.lightSteps);
  EXPECT_EQ(ac.lightSplit, bc.lightSplit);
  EXPECT_EQ(ac.lightDistanceM, bc.lightDistanceM);
  EXPECT_EQ(ac.transmittanceCutoff, bc.transmittanceCutoff);
  EXPECT_EQ(ac.energyConserving, bc.energyConserving);
  EXPECT_EQ(ac.scatteringOctaves, bc.scatteringOctaves);
  EXPECT_EQ(ac.shapeScaleKm, bc.shapeScaleKm);
  EXPECT_EQ(ac.detailScaleKm, bc.detailScaleKm);
  EXPECT_EQ(ac.windSpeedMs, bc.windSpeedMs);
  EXPECT_EQ(ac.windFrom, bc.windFrom);
  EXPECT_EQ(ac.low.baseM, bc.low.baseM);
  EXPECT_EQ(ac.low.topM, bc.low.topM);
  EXPECT_EQ(ac.mid.baseM, bc.mid.baseM);
  EXPECT_EQ(ac.mid.topM, bc.mid.topM);
  const WeatherSettings &aw = a.weather, &bw = b.weather;
  EXPECT_EQ(aw.source, bw.source);
  EXPECT_EQ(aw.region.has_value(), bw.region.has_value());
  if (aw.region && bw.region) {
    EXPECT_EQ(aw.region->lat[0], bw.region->lat[0]);
    EXPECT_EQ(aw.region->lat[1], bw.region->lat[1]);
    EXPECT_EQ(aw.region->lon[0], bw.region->lon[0]);
    EXPECT_EQ(aw.region->lon[1], bw.region->lon[1]);
  }
  EXPECT_EQ(aw.cameraRegionKm, bw.cameraRegionKm);
  EXPECT_EQ(aw.coverLow, bw.coverLow);
  EXPECT_EQ(aw.coverMid, bw.coverMid);
  EXPECT_EQ(aw.spread, bw.spread);
  EXPECT_EQ(aw.scaleKm, bw.scaleKm);
  EXPECT_EQ(aw.seed, bw.seed);
  EXPECT_EQ(aw.resolution, bw.resolution);
  EXPECT_EQ(aw.cloudType, bw.cloudType);
  EXPECT_EQ(aw.image, bw.image);
  EXPECT_EQ(aw.file, bw.file);
  EXPECT_EQ(aw.cover, bw.cover);
  EXPECT_EQ(aw.advection, bw.advection);
  EXPECT_EQ(aw.steeringHpa, bw.steeringHpa);
  EXPECT_EQ(aw.time, bw.time);
  EXPECT_EQ(aw.localRadiusKm, bw.localRadiusKm);
  EXPECT_EQ(aw.evolution, bw.evolution);
  EXPECT_EQ(aw.automaton, bw.automaton);
  for (auto [x, y] : {std::pair{&aw.low, &bw.low}, {&aw.mid, &bw.mid}, {&aw.high, &bw.high}}) {
    EXPECT_EQ(x->bottomHpa, y->bottomHpa);
    EXPECT_EQ(x->topHpa, y->topHpa);
    EXPECT_EQ(x->rhCritical, y->rhCritical);
  }
  expectSameLighting(a.lighting, b.lighting);
}

// A scene where every field differs from its default, with awkward values: a time-lapse
// with a fractional-second step and fractional start/end, numbers whose shortest text is
// long, range ends, a subnormal float and a three-key palette of odd floats.
inline Scene unusualScene() {
  Scene s;
  s.output.width = 64;
  s.output.height = 36;
  s.output.name = "test-1.v2";
  s.output.exposure = ExposureMode::Histogram;
  s.output.exposureEv = -0.1;
  s.output.exposureAdaptationS = 0.25;
  s.output.nightLook = false;
  s.output.display = "Display \"P3\"";
  s.output.view = "64";
  s.camera.latitude = -33.8688;
  s.camera.longitude = 151.2093;
  s.camera.altitudeM = 0.1;
  s.camera.heading = 1.0 / 3.0;
  s.camera.pitch = -0.0;
  s.camera.verticalFov = 70.00000000000001;
  s.camera.projection = CameraProjection::Equirectangular;
  s.camera.mode = CameraMode::GeographicTopdown;
  s.time.start = IsoTime::parse("2024-12-21T05:30:00.125-03:30").value();
  s.time.end = IsoTime::parse("2024-12-21T10:30:00.375+01:00").value();  // another zone
  s.time.stepSeconds = 61.3;
  s.sun.azimuth = 200.1;
  s.sun.elevation = 1e-7;
  s.sun.angularDiameter = 0.01;
  s.sun.discScale = 999.9999999999999;
  s.moon.azimuth = -359.99;
  s.moon.elevation = -0.30000000000000004;
  s.moon.discScale = 0.0;
  s.moon.earthshine = 100.0;
  s.sky.glowSize = 0.30000000000000004;
  s.sky.hazeHeight = 0.001;
  s.sky.model = SkyModel::Physical;
  s.atmosphere.groundRadiusKm = 100.0;
  s.atmosphere.thicknessKm = 1000.0;
  s.atmosphere.rayleighScattering = {0.0f, 1e4f, 1.0f / 3.0f};
  s.atmosphere.rayleighScaleHeightKm = 0.01;
  s.atmosphere.mieScattering = 0.1 + 0.2;
  s.atmosphere.mieExtinction = 1e4;
  s.atmosphere.mieScaleHeightKm = 100.0;
  s.atmosphere.mieAnisotropy = -0.99;
  s.atmosphere.ozoneAbsorption = {1e-30f, 2.0f / 3.0f, 9999.999f};
  s.atmosphere.ozoneCenterKm = 999.9999999999999;
  s.atmosphere.ozoneHalfWidthKm = 0.01;
  s.atmosphere.aerosols = AerosolSource::Settings;
  s.ground.albedo = {0.0f, 1.0f, 0.1f};
  s.highClouds.source = HighCloudSource::Image;
  s.highClouds.style = HighCloudStyle::Cirrocumulus;
  s.highClouds.cover = 1.0 / 3.0;
  s.highClouds.coverMap = "maps/cover \"high\".png";
  s.highClouds.coefficients = "C:/textures/cirrus coefficients.exr";
  s.highClouds.normals = "../n\u00e9rmals.png";
  s.highClouds.resolution = 4096;
  s.highClouds.seed = 2147483647;
  s.highClouds.altitudeM = 1000.0;
  s.highClouds.tileSizeKm = 0.1;
  s.highClouds.windSpeedMs = 200.0;
  s.highClouds.windFrom = -359.5;
  s.highClouds.edgeGlowDeg = 0.5;
  s.highClouds.brightness = 1e-3;
  s.highClouds.coverSource = HighCloudCoverSource::Weather;
  s.clouds.quality = CloudQuality::Reference;
  s.clouds.temporal.mode = CloudTemporalMode::On;
  s.clouds.temporal.block = 3;
  s.clouds.temporal.resolution = CloudTemporalResolution::Half;
  s.clouds.light = CloudLight::Volume;
  s.clouds.model = CloudModel::Tang2019;
  s.clouds.coverage = CloudCoverageMode::Paper;
  s.clouds.extinction = 1e-5;
  s.clouds.g = -0.99;
  s.clouds.phase = CloudPhase::Hg;
  s.clouds.gBack = -0.0001;
  s.clouds.backWeight = 1.0;
  s.clouds.attenuationClamp = 1.0 / 3.0;
  s.clouds.stepM = 10000.0;
  s.clouds.stepGrowth = 0.1 + 0.2;
  s.clouds.maxSteps = 4096;
  s.clouds.samples = 9;
  s.clouds.lightSteps = 16;
  s.clouds.lightDistanceM = 1.5;
  s.clouds.transmittanceCutoff = 0.0;
  s.clouds.energyConserving = false;
  s.clouds.scatteringOctaves = 8;
  s.clouds.shapeScaleKm = 999.9999999999999;
  s.clouds.detailScaleKm = 0.01;
  s.clouds.windSpeedMs = 0.0;
  s.clouds.windFrom = -0.5;
  s.clouds.low = {0.0, 1e-3};
  s.clouds.mid = {1e-3, 30000.0};
  s.weather.source = WeatherMapSource::Image;
  s.weather.region = WeatherRegion{{-90.0, -89.99999999999999}, {-180.0, 1.0 / 3.0}};
  s.weather.cameraRegionKm = 10000.0 / 3.0;
  s.weather.coverLow = 1.0;
  s.weather.coverMid = 0.30000000000000004;
  s.weather.spread = 0.0;
  s.weather.scaleKm = 1.0;
  s.weather.seed = 0;
  s.weather.resolution = 8192;
  s.weather.cloudType = CloudType::Altocumulus;
  s.weather.image = "maps/weather \u00e9.exr";
  s.weather.file = "../gfs/gfs.t12z.grib2";
  s.weather.cover = WeatherCover::Tcc;
  s.weather.advection = WeatherAdvection::Wind;  // "data" needs source file
  s.weather.steeringHpa = 700.0 + 1.0 / 3.0;
  s.weather.time = IsoTime::parse("2011-01-15T12:00:00.25-03:30");
  s.weather.localRadiusKm = 0.1;
  s.weather.evolution = WeatherEvolution::Ca;
  s.weather.automaton = {3600.0, 1.0 / 3.0 + 0.1, 1440.0, 0.0};
  s.weather.low = {1100.0, 1099.5, 0.0};
  s.weather.mid = {700.0, 1.0, 0.99};
  s.weather.high = {2.0 / 3.0 + 1.0, 1.0, 1.0 / 3.0};
  s.lighting.pressureHpa = 0.0;
  s.lighting.temperatureC = -40.05;
  s.lighting.turbidity = 4.999999999999999;
  s.lighting.nightAdaptation = 1.0 / 3.0;
  s.lighting.starBrightness = 1e6;
  s.lighting.starExtinction = 1e-300;
  PaletteKey night;
  night.sunElevation = -89.99999999999999;
  night.skyColor = {1e-40f, 1.0f / 3.0f, 0.1f};
  night.fogColor = {1e-6f, 0.0f, 524288.03f};
  night.glowColor = {0.0f, 0.0f, 2e-3f};
  night.cloudLit = {3.4028235e-10f, 0.7f, 0.2f};
  night.cloudDark = {0.1f + 0.2f, 1.1754944e-38f, 2.0f / 3.0f};
  night.ambientTop = {999999.94f, 1e6f, 0.5f};
  night.ambientBottom = {0.0001f, 0.00012345678f, 7.0f};
  PaletteKey dusk = night;
  dusk.sunElevation = -1e-9;
  dusk.skyColor = {0.30000001f, 0.2f, 0.1f};
  dusk.glowColor = {12.5f, 0.7f, 3e5f};
  PaletteKey day = dusk;
  day.sunElevation = 90.0;
  day.fogColor = {1.0f / 7.0f, 6.0f / 7.0f, 1.0f};
  day.ambientBottom = {0.0f, 0.0f, 1e-45f};
  s.lighting.palette = {night, dusk, day};
  return s;
}

}  // namespace test
}  // namespace sky
