#include "engine/lighting/lighting_state.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

#include "engine/lighting/light_model.h"

namespace sky {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kMeanMoonDistanceKm = 384400.0;
// How far toward the zenith full overcast lifts the kozlov sky's horizon haze (applyOvercast).
constexpr double kOvercastHaze = 0.5;

glm::vec4 v4(const glm::dvec3& v, double w = 0.0) {
  return glm::vec4(static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z),
                   static_cast<float>(w));
}

PaletteKey scaled(PaletteKey k, glm::vec3 s) {
  for (glm::vec3* c : {&k.skyColor, &k.fogColor, &k.glowColor, &k.cloudLit, &k.cloudDark,
                       &k.ambientTop, &k.ambientBottom})
    *c *= s;
  return k;
}
PaletteKey scaled(const PaletteKey& k, float s) {
  return scaled(k, glm::vec3(s));
}

shared::Palette toGpu(const PaletteKey& k, const SkySettings& sky) {
  shared::Palette p{};
  p.sky = glm::vec4(k.skyColor, static_cast<float>(sky.glowSize));
  p.fog = glm::vec4(k.fogColor, static_cast<float>(sky.hazeHeight));
  p.glow = glm::vec4(k.glowColor, static_cast<float>(sky.glowExponent));
  p.cloudLit = glm::vec4(k.cloudLit, 0.0f);
  p.cloudDark = glm::vec4(k.cloudDark, 0.0f);
  p.ambientTop = glm::vec4(k.ambientTop, 0.0f);
  p.ambientBottom = glm::vec4(k.ambientBottom, 0.0f);
  return p;
}

double wrap360(double deg) {
  double a = std::fmod(deg, 360.0);
  return a < 0.0 ? a + 360.0 : a;
}

// Mean Lommel-Seeliger shading mu0 / (mu0 + mu) over the visible disc at phase angle i: the
// moon's surface has almost no limb darkening, which Lambert would wrongly add. Used to give
// the drawn disc exactly the Krisciunas-Schaefer flux.
double meanLommelSeeliger(double phaseRad) {
  const int n = 96;
  const glm::dvec3 s{std::sin(phaseRad), 0.0, std::cos(phaseRad)};
  double sum = 0.0;
  int count = 0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      double x = (i + 0.5) / n * 2.0 - 1.0, y = (j + 0.5) / n * 2.0 - 1.0;
      double r2 = x * x + y * y;
      if (r2 >= 1.0) continue;
      glm::dvec3 normal{x, y, std::sqrt(1.0 - r2)};
      double mu0 = glm::dot(normal, s), mu = normal.z;
      sum += mu0 > 0.0 ? mu0 / (mu0 + mu) : 0.0;
      ++count;
    }
  }
  return sum / count;
}

}  // namespace

glm::dvec3 enuDirection(double azimuthDeg, double elevationDeg) {
  double az = azimuthDeg * kDeg, el = elevationDeg * kDeg;
  return {std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
}

PaletteKey interpolatePalette(const std::vector<PaletteKey>& keys, double sunElevationDeg) {
  if (sunElevationDeg <= keys.front().sunElevation) return keys.front();
  for (size_t i = 1; i < keys.size(); ++i) {
    if (sunElevationDeg <= keys[i].sunElevation) {
      const PaletteKey& a = keys[i - 1];
      const PaletteKey& b = keys[i];
      auto t = static_cast<float>((sunElevationDeg - a.sunElevation) /
                                  (b.sunElevation - a.sunElevation));
      auto mix = [t](glm::vec3 x, glm::vec3 y) { return x + (y - x) * t; };
      return PaletteKey{sunElevationDeg,
                        mix(a.skyColor, b.skyColor),
                        mix(a.fogColor, b.fogColor),
                        mix(a.glowColor, b.glowColor),
                        mix(a.cloudLit, b.cloudLit),
                        mix(a.cloudDark, b.cloudDark),
                        mix(a.ambientTop, b.ambientTop),
                        mix(a.ambientBottom, b.ambientBottom)};
    }
  }
  return keys.back();
}

LightingState computeLighting(const Scene& scene, const IsoTime& time) {
  const CameraSettings& cam = scene.camera;
  const LightingSettings& ls = scene.lighting;
  LightingState st;
  st.time = time;
  st.ephemeris = computeEphemeris(
      time.julianDateUtc(),
      Observer{cam.latitude, cam.longitude, cam.altitudeM, ls.pressureHpa, ls.temperatureC});
  const Ephemeris& eph = st.ephemeris;

  // Placement: the ephemeris, or the scene's art-directed override.
  auto place = [](BodyLight& b, const SkyPosition& pos, const std::optional<double>& az,
                  const std::optional<double>& el) {
    b.overridden = az && el;
    b.azimuthDeg = b.overridden ? wrap360(*az) : pos.azimuthDeg;
    b.elevationDeg = b.overridden ? *el : pos.elevationDeg;
    b.direction = enuDirection(b.azimuthDeg, b.elevationDeg);
  };
  place(st.sun, eph.sun.position, scene.sun.azimuth, scene.sun.elevation);
  place(st.moon, eph.moon.position, scene.moon.azimuth, scene.moon.elevation);
  st.sun.angularRadiusDeg = 0.5 * scene.sun.angularDiameter;
  st.moon.angularRadiusDeg =
      std::asin(light::kMoonRadiusKm / eph.moon.topocentricDistanceKm) / kDeg;

  st.dayFactor = light::dayFactor(st.sun.elevationDeg);
  st.key = st.dayFactor >= 0.5 ? "sun" : "moon";

  // Sun: top-of-atmosphere illuminance at this distance, through the air mass.
  const double sunToaLux = light::kSolarIlluminanceLux / (eph.sun.distanceAu * eph.sun.distanceAu);
  const glm::dvec3 sunT =
      light::atmosphereTransmittance(st.sun.elevationDeg, cam.altitudeM, ls.turbidity);
  const double sunAbove = light::discAboveHorizon(st.sun.elevationDeg, st.sun.angularRadiusDeg);
  // The sun's own colour (light::solarColor): the renderer's white is D65, not the sun.
  const glm::dvec3 sunColor = light::solarColor();
  const glm::dvec3 sunUnhidden = sunToaLux / light::kLuxPerUnit * sunT * sunColor;
  st.sun.illuminanceLux = sunToaLux * light::luminance(sunT * sunColor) * sunAbove;

  // Moon: Krisciunas & Schaefer by phase and distance, reddened, through the air mass.
  const MoonEphemeris& m = eph.moon;
  const double moonToaLux = light::moonIlluminanceLux(m.phaseAngleDeg, m.topocentricDistanceKm);
  const glm::dvec3 moonT =
      light::atmosphereTransmittance(st.moon.elevationDeg, cam.altitudeM, ls.turbidity);
  const double moonAbove = light::discAboveHorizon(st.moon.elevationDeg, st.moon.angularRadiusDeg);
  // Moonlight is sunlight the moon reddens a little more (unit luminance: moonToaLux is the
  // moon's illuminance).
  const glm::dvec3 moonReflected = light::moonColor() * light::solarColor();
  const glm::dvec3 moonTint = moonReflected / light::luminance(moonReflected);
  const glm::dvec3 moonUnhidden = moonToaLux / light::kLuxPerUnit * moonT * moonTint;
  st.moon.illuminanceLux = moonToaLux * light::luminance(moonT * moonTint) * moonAbove;

  // Palettes: the sky at the sun's elevation, and the moonlit sky, a copy of the daylit sky
  // at the moon's elevation dimmed by the moon-to-sun illuminance ratio (moonlight is
  // sunlight, so the same atmosphere scatters it the same way). The palette is authored as
  // seen after the standard night lift; dividing that out makes both physical. Its colours
  // are light the air scatters from a white sun; the sun's own colour (as the physical sky's)
  // tints them, so the two skies stay one sun's (the zenith's r/g within 10 % of the
  // physical sky's, AtmosphereCompositeTest).
  auto physical = [&](double elevationDeg) {
    return scaled(interpolatePalette(ls.palette, elevationDeg),
                  glm::vec3(sunColor) *
                      static_cast<float>(std::exp2(-light::paletteExposureEv(elevationDeg))));
  };
  st.palette = physical(st.sun.elevationDeg);
  const double moonSky = moonToaLux / light::kSolarIlluminanceLux;
  st.moonPalette = scaled(physical(st.moon.elevationDeg), static_cast<float>(moonSky));

  // Night: how far the display's automatic exposure follows the light down (docs/lighting.md,
  // "Night lift"). Nothing here applies it: the state is physical, the display path exposes
  // it. It follows the sky's light, the twilight's and the moon's together. On the sun's
  // depression alone (full only at -18 degrees) a moonlit scene, whose light stops falling
  // near -12, was lifted 3 stops less there than at midnight: the time-lapse's twilight hole.
  // And a moonless night got the same lift as a moonlit one, which left it black. The sky is
  // taken at the horizon (the palettes' fog colour), which most frames show: it follows the
  // frame's histogram metering to within 0.75 stop from sunset to a moonlit midnight.
  const double sky = light::luminance(glm::dvec3(st.palette.fogColor)) +
                     light::luminance(glm::dvec3(st.moonPalette.fogColor));
  // The brightest moonlit sky: a full moon at the mean distance, overhead.
  const double moonlitSky = light::moonIlluminanceLux(0.0, kMeanMoonDistanceKm) /
                            light::kSolarIlluminanceLux *
                            light::luminance(glm::dvec3(physical(90.0).fogColor));
  st.nightLiftEv =
      light::sceneNightLiftEv(st.sun.elevationDeg, sky, moonlitSky, ls.nightAdaptation);
  st.autoExposureEv = light::autoExposureEv(st.sun.elevationDeg, st.nightLiftEv);

  shared::LightingState& g = st.gpu;
  g.sun.direction = v4(st.sun.direction, st.sun.angularRadiusDeg * kDeg);
  g.sun.illuminance = v4(sunUnhidden * sunAbove, sunAbove);
  g.moon.direction = v4(st.moon.direction, st.moon.angularRadiusDeg * kDeg);
  g.moon.illuminance = v4(moonUnhidden * moonAbove, moonAbove);
  g.palette = toGpu(st.palette, scene.sky);
  g.moonPalette = toGpu(st.moonPalette, scene.sky);

  // Discs: a uniform sun disc of the scene's size carrying the sun's illuminance.
  const double sunR = st.sun.angularRadiusDeg * kDeg;
  const double sunSolidAngle = 2.0 * kPi * (1.0 - std::cos(sunR));
  g.sunDisc = v4(sunUnhidden / sunSolidAngle * scene.sun.discScale);

  // The moon's bright limb: position angle chi from the north point of the disc toward
  // east (Meeus 48.5), turned into an east-north-up tangent at the moon's direction.
  const double lat = cam.latitude * kDeg;
  const glm::dvec3 pole{0.0, std::cos(lat), std::sin(lat)};  // north celestial pole
  const glm::dvec3 d = st.moon.direction;
  glm::dvec3 north = pole - glm::dot(pole, d) * d;
  if (glm::dot(north, north) < 1e-12) north = glm::dvec3(0.0, 1.0, 0.0);  // moon at the pole
  north = glm::normalize(north);
  const glm::dvec3 east = glm::cross(north, d);  // east on the sky, seen from inside
  const double chi = m.brightLimbAngleDeg * kDeg;
  const double phase = m.phaseAngleDeg * kDeg;
  g.moonLimb = v4(std::cos(chi) * north + std::sin(chi) * east, phase);

  const double moonR = st.moon.angularRadiusDeg * kDeg;
  const double moonSolidAngle = 2.0 * kPi * (1.0 - std::cos(moonR));
  // Radiance per unit shading such that the disc's total is the K&S illuminance. Near new
  // moon both shrink towards zero; the floor keeps the ratio finite.
  const double meanShade = std::max(meanLommelSeeliger(phase), 1e-6);
  g.moonDisc =
      v4(moonUnhidden / (moonSolidAngle * meanShade) * scene.moon.discScale, m.illuminatedFraction);
  // Earthshine: the earthlit side is seen at "full" phase from Earth, so its radiance is the
  // full moon's mean radiance times the earthshine ratio.
  const glm::dvec3 fullMoon = light::moonIlluminanceLux(0.0, m.topocentricDistanceKm) /
                              light::kLuxPerUnit * moonT * moonTint / moonSolidAngle;
  g.moonEarthshine = v4(fullMoon * light::earthshineRatio(m.illuminatedFraction) *
                            scene.moon.earthshine * scene.moon.discScale,
                        meanShade);

  g.night = glm::vec4(static_cast<float>(st.dayFactor), 0.0f,
                      static_cast<float>(light::kVegaIlluminanceLux / light::kLuxPerUnit *
                                         ls.starBrightness),
                      0.0f);
  for (int c = 0; c < 3; ++c) g.equatorialToEnu[c] = v4(eph.equatorialJ2000ToEnu[c]);
  // Above the atmosphere: the sun has its spectrum's colour in our Rec.709 units (D65 white),
  // which the air then reddens; the moon adds its reddened albedo.
  g.sunSpace = v4(sunToaLux / light::kLuxPerUnit * sunColor);
  g.moonSpace = v4(moonToaLux / light::kLuxPerUnit * moonTint);
  return st;
}

bool moonLightNegligible(const shared::LightingState& g) {
  const float sun = std::max({g.sunSpace.r, g.sunSpace.g, g.sunSpace.b});
  const float moon = std::max({g.moonSpace.r, g.moonSpace.g, g.moonSpace.b});
  return g.sun.direction.z > 0.0f && moon < 1e-4f * sun;
}

nlohmann::ordered_json lightingJson(const LightingState& st) {
  IsoTime utc = st.time;
  utc.offsetMinutes = 0;
  const MoonEphemeris& m = st.ephemeris.moon;
  auto source = [](const BodyLight& b) { return b.overridden ? "scene_override" : "ephemeris"; };
  return {
      {"time_utc", utc.format()},
      {"sun",
       {{"azimuth_deg", st.sun.azimuthDeg},
        {"elevation_deg", st.sun.elevationDeg},
        {"distance_au", st.ephemeris.sun.distanceAu},
        {"illuminance_lux", st.sun.illuminanceLux},
        {"source", source(st.sun)}}},
      {"moon",
       {{"azimuth_deg", st.moon.azimuthDeg},
        {"elevation_deg", st.moon.elevationDeg},
        {"distance_km", m.distanceKm},
        {"topocentric_distance_km", m.topocentricDistanceKm},
        {"illuminated_fraction", m.illuminatedFraction},
        {"phase_angle_deg", m.phaseAngleDeg},
        {"bright_limb_angle_deg", m.brightLimbAngleDeg},
        {"illuminance_lux", st.moon.illuminanceLux},
        {"source", source(st.moon)}}},
      {"light",
       {{"key", st.key},
        {"day_factor", st.dayFactor},
        {"night_lift_ev", st.nightLiftEv},
        {"auto_exposure_ev", st.autoExposureEv},
        {"overcast", st.overcast}}},
  };
}

void applyOvercast(LightingState& st, const SkySettings& sky, double overcast) {
  const double n = std::clamp(overcast, 0.0, 1.0);
  const auto ground = static_cast<float>(light::overcastGlobalShare(n));
  for (PaletteKey* k : {&st.palette, &st.moonPalette}) {
    k->ambientBottom *= ground;
    const auto grey = static_cast<float>(light::luminance(glm::dvec3(k->ambientTop)));
    k->ambientTop = glm::mix(k->ambientTop, glm::vec3(grey), static_cast<float>(n));
  }
  st.overcast = n;
  const auto haze = static_cast<float>(sky.hazeHeight + (1.0 - sky.hazeHeight) * kOvercastHaze * n);
  st.gpu.palette = toGpu(st.palette, sky);
  st.gpu.moonPalette = toGpu(st.moonPalette, sky);
  st.gpu.palette.fog.w = st.gpu.moonPalette.fog.w = haze;
}

}  // namespace sky
