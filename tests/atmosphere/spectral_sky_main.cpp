// spectral_sky: the physical sky's LUTs against the spectral brute-force reference over the
// dome, case by case, for docs/atmosphere.md ("A spectral reference"). Runs on whatever Vulkan
// device the engine picks (lavapipe here); the reference runs on the CPU.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "atmosphere_reference.h"
#include "engine/core/error.h"
#include "engine/gpu/context.h"
#include "engine/lighting/light_model.h"
#include "engine/render/renderer.h"
#include "engine/shader/shader_compiler.h"
#include "spectral_sky_compare.h"

namespace sky::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

constexpr const char* kUsage = R"(usage: spectral_sky [options]
The LUT sky (sky.model physical) against the spectral brute-force reference over the upper
half of a sky probe, for Preetham turbidity 2 and 3 and the default scene.
  --sun DEG[,DEG...]   sun elevations (default 5,10,30,60)
  --case NAME          only the cases named "T 2", "T 3" or "default" (repeatable)
  --turbidity T[,T...] instead, the default scene with these lighting.turbidity values
  --quality Q          reference resolution: test, default or fine (default: default)
  --step NM            wavelength step of the reference, a multiple of 5 (default 10)
  --size WxH           probe size (default 72x36: 5 degree cells)
  --white-sun          light the LUTs with the renderer's white sun (1, 1, 1) instead of the
                       sun's colour from the E-490 spectrum (both have luminance 1)
  --decompose          also the same integrator with the renderer's three channels
                       ("channels"), its second order made isotropic (Hillaire's Psi_ms) or
                       cut to its moments (the LUTs' model), and the direct reference of the
                       LUTs' model (atmosphere_reference.h)
  --attribute          the zenith with the channels' coefficients at 680, 550 and 440 nm
                       (before issue 30) one quantity at a time (Rayleigh, ozone, aerosols)
  --csv FILE           every direction of every case: elevation, azimuth from the sun, rgb of
                       the LUT, the reference and (with --decompose) the channels
  --against Q:NM       also the reference at quality Q every NM nm, against the main one
                       (how far a coarser reference is from a finer one)
  --threads N          CPU threads for the reference (default: all)
)";

std::vector<double> parseList(const std::string& s, const char* key) {
  std::vector<double> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      out.push_back(std::stod(item));
    } catch (const std::exception&) {
      inputError(std::string(key) + ": '" + item + "' is not a number");
    }
  }
  return out;
}

std::string percent(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f %%", 100.0 * v);
  return buf;
}

std::string fixed(double v, int digits = 3) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

void printStats(const char* what, const SkyStats& s) {
  std::cout << "  " << what << ": luminance median " << percent(s.luminanceMedian) << ", 90th "
            << percent(s.luminanceP90) << "; chromaticity median " << percent(s.chromaMedian)
            << ", 90th " << percent(s.chromaP90) << "; zenith R/G " << fixed(s.zenithRg()) << " vs "
            << fixed(s.zenithRgRef()) << " (" << fixed(s.zenithRg() / s.zenithRgRef()) << "x)\n";
}

// The zenith's R/G and luminance against the spectrum's with the channel integrator, its
// coefficients the channel averages (the defaults since issue 30) and then one quantity at a
// time at 680, 550 and 440 nm, the values before issue 30 (Hillaire's Table 1 for Rayleigh and
// ozone, Angstrom's law at those wavelengths for the aerosols).
void attributeZenith(const AtmosphereSettings& s, glm::dvec3 sun, glm::dvec3 L, int step,
                     const BruteForceQuality& q) {
  const glm::dvec3 zenith(0.0, 0.0, 1.0);
  const glm::dvec3 want = BruteForceSky(spectralSky(spectralAtmosphere(s), step), q)
                              .radiance(kCompareAltitudeKm, zenith, L)
                              .total();
  const glm::dvec3 rayleigh(5.802, 13.558, 33.1), ozone(0.650, 1.881, 0.085);
  glm::dvec3 aerosols;
  for (int c = 0; c < 3; ++c)
    aerosols[c] = std::pow(glm::dvec3(680.0, 550.0, 440.0)[c] / 550.0, -s.mieAngstrom) /
                  std::pow(light::kChannelAerosolWavelengthsNm[c] / 550.0, -s.mieAngstrom);
  const char* names[] = {"channel averages", "Rayleigh at 680/550/440 nm",
                         "ozone at 680/550/440 nm", "aerosols at 680/550/440 nm", "all three"};
  std::cout << "  zenith, channels against the spectrum:";
  for (int v = 0; v < 5; ++v) {
    SkyMedium m = channelSky(s, sun);
    for (int c = 0; c < 3; ++c) {
      SkyBand& b = m.bands[static_cast<size_t>(c)];
      if (v == 1 || v == 4) b.rayleigh = rayleigh[c] * 1e-3;
      if (v == 2 || v == 4) b.ozone = ozone[c] * 1e-3;
      if (v == 3 || v == 4) {
        b.mieScattering *= aerosols[c];
        b.mieExtinction *= aerosols[c];
      }
    }
    const glm::dvec3 got = BruteForceSky(m, q).radiance(kCompareAltitudeKm, zenith, L).total();
    std::cout << (v ? "; " : " ") << names[v] << " R/G "
              << fixed((got.r / got.g) / (want.r / want.g)) << "x, Y "
              << fixed(luminance709(got) / luminance709(want)) << "x";
  }
  std::cout << "\n";
}

int run(int argc, char** argv) {
  std::vector<double> suns = {5, 10, 30, 60};
  std::vector<std::string> only;
  std::vector<double> turbidities;
  std::string qualityName = "default", csvPath, againstQuality;
  int againstStep = 0;
  int step = 10, threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  HalfDome dome;
  bool whiteSun = false, decompose = false, attribute = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) inputError(a + " needs a value");
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      return 0;
    } else if (a == "--sun") {
      suns = parseList(value(), "--sun");
    } else if (a == "--turbidity") {
      turbidities = parseList(value(), "--turbidity");
    } else if (a == "--case") {
      only.push_back(value());
    } else if (a == "--quality") {
      qualityName = value();
    } else if (a == "--step") {
      step = static_cast<int>(parseList(value(), "--step").at(0));
      if (step < 5 || step % 5)
        inputError("--step: " + std::to_string(step) + " is not a multiple of 5");
    } else if (a == "--size") {
      const std::string v = value();
      if (std::sscanf(v.c_str(), "%dx%d", &dome.width, &dome.height) != 2 || dome.width < 4 ||
          dome.height < 4 || dome.width % 2 || dome.height % 2)
        inputError("--size: '" + v + "' (WxH, both even)");
    } else if (a == "--white-sun") {
      whiteSun = true;
    } else if (a == "--decompose") {
      decompose = true;
    } else if (a == "--attribute") {
      attribute = true;
    } else if (a == "--csv") {
      csvPath = value();
    } else if (a == "--against") {
      const std::string v = value();
      const size_t colon = v.find(':');
      if (colon == std::string::npos) inputError("--against: '" + v + "' (QUALITY:NM)");
      againstQuality = v.substr(0, colon);
      againstStep = static_cast<int>(parseList(v.substr(colon + 1), "--against").at(0));
      referenceQuality(againstQuality);
      if (againstStep < 5 || againstStep % 5)
        inputError("--against: " + std::to_string(againstStep) + " is not a multiple of 5");
    } else if (a == "--threads") {
      threads = static_cast<int>(parseList(value(), "--threads").at(0));
    } else {
      inputError("unknown option '" + a + "' (spectral_sky --help)");
    }
  }
  const BruteForceQuality q = referenceQuality(qualityName);

  Context ctx;
  ShaderCompiler compiler;
  GraphRuntime runtime(ctx);
  AtmosphereLuts luts(ctx, compiler);
  std::ofstream csv;
  if (!csvPath.empty()) {
    csv.open(csvPath);
    if (!csv) inputError("--csv: cannot write '" + csvPath + "'");
    csv << "case,sun_deg,elevation_deg,azimuth_from_sun_deg,lut_r,lut_g,lut_b,ref_r,ref_g,ref_b,"
           "channels_r,channels_g,channels_b,model_r,model_g,model_b,iso_r,iso_g,iso_b\n";
  }

  const glm::dvec3 sun = whiteSun ? glm::dvec3(1.0) : solarColor();
  std::cout << "sun above the atmosphere (linear Rec. 709, luminance 1): " << fixed(sun.r, 4) << " "
            << fixed(sun.g, 4) << " " << fixed(sun.b, 4) << "; reference quality " << qualityName
            << ", every " << step << " nm; probe " << dome.width << "x" << dome.height << "\n";
  const std::vector<glm::dvec3> directions = dome.directions();
  std::vector<SkyStats> all;
  std::vector<SkyCase> cases = standardCases(suns);
  if (!turbidities.empty()) {
    cases.clear();
    for (double t : turbidities)
      for (double e : suns) {
        SkyCase c;
        c.name = "turbidity " + fixed(t);
        c.scene.sky.model = SkyModel::Physical;
        c.scene.lighting.turbidity = t;
        c.sunElevationDeg = e;
        cases.push_back(c);
      }
  }
  for (const SkyCase& c : cases) {
    if (!only.empty() && std::find(only.begin(), only.end(), c.name) == only.end()) continue;
    const auto start = std::chrono::steady_clock::now();
    const AtmosphereLuts::Frame frame = caseFrame(c, sun);
    const std::vector<glm::dvec3> lut =
        halfDomeOf(renderProbe(runtime, luts, frame, dome.width, dome.height), dome);
    const glm::dvec3 L = caseSunDirection(c);
    const BruteForceSky reference(spectralSky(spectralAtmosphere(frame.atmosphere), step), q);
    std::vector<glm::dvec3> ref;
    std::vector<SkyRadiance> orders =
        reference.radiance(kCompareAltitudeKm, directions, L, threads);
    for (const SkyRadiance& s : orders) ref.push_back(s.total());
    const SkyStats stats = compareSky(lut, ref, dome);
    all.push_back(stats);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const SkyRadiance& zenith = orders.front();
    std::cout << c.name << ", sun " << c.sunElevationDeg << " deg (" << fixed(seconds, 1)
              << " s; reference orders at the zenith: single "
              << percent(luminance709(zenith.single) / luminance709(zenith.total())) << ", second "
              << percent(luminance709(zenith.second) / luminance709(zenith.total())) << ", higher "
              << percent(luminance709(zenith.higher) / luminance709(zenith.total())) << ")\n";
    printStats("LUT vs spectral", stats);
    if (!againstQuality.empty()) {
      const BruteForceSky other(spectralSky(spectralAtmosphere(frame.atmosphere), againstStep),
                                referenceQuality(againstQuality));
      std::vector<glm::dvec3> otherRef;
      for (const SkyRadiance& s : other.radiance(kCompareAltitudeKm, directions, L, threads))
        otherRef.push_back(s.total());
      const SkyStats o = compareSky(otherRef, ref, dome);
      printStats(("reference " + againstQuality + " every " + std::to_string(againstStep) +
                  " nm vs reference")
                     .c_str(),
                 o);
      std::cout << "    largest luminance difference " << percent(o.luminanceMax) << "\n";
    }
    if (!whiteSun) {
      // The LUTs are linear in the light's illuminance per channel: the renderer's white sun
      // (1, 1, 1) gives the same sky divided by the sun's colour.
      std::vector<glm::dvec3> white;
      for (const glm::dvec3& v : lut) white.push_back(v / sun);
      printStats("LUT with the white sun vs spectral", compareSky(white, ref, dome));
    }
    if (attribute) attributeZenith(frame.atmosphere, sun, L, step, q);
    std::vector<glm::dvec3> channels, direct, isotropic, moments;
    if (decompose) {
      const BruteForceSky channelRef(channelSky(frame.atmosphere, sun), q);
      for (const SkyRadiance& s : channelRef.radiance(kCompareAltitudeKm, directions, L, threads)) {
        channels.push_back(s.total());
        isotropic.push_back(s.single + s.isotropic);
        moments.push_back(s.single + s.moments);
      }
      printStats("channels vs spectral (three channels)", compareSky(channels, ref, dome));
      printStats("LUT vs channels (the LUTs' model and resolution)",
                 compareSky(lut, channels, dome));
      printStats("isotropic second order vs channels (Hillaire + true first phase)",
                 compareSky(isotropic, channels, dome));
      printStats("second order by its moments vs channels (the LUTs' model)",
                 compareSky(moments, channels, dome));
      const AtmosphereReference model(frame.atmosphere);
      for (const glm::dvec3& V : directions)
        direct.push_back(
            kPi * sun *
            model.skyRadiance(model.atmosphere().groundRadius + kCompareAltitudeKm, V, L));
      printStats("direct LUT-model reference vs channels", compareSky(direct, channels, dome));
      printStats("LUT vs direct LUT-model reference (the LUTs' resolution)",
                 compareSky(lut, direct, dome));
    }
    if (csv)
      for (int row = 0; row < dome.rows(); ++row)
        for (int k = 0; k < dome.columns(); ++k) {
          const size_t i = static_cast<size_t>(row * dome.columns() + k);
          csv << c.name << "," << c.sunElevationDeg << "," << dome.elevationDeg(row) << ","
              << 360.0 * (k + 0.5) / dome.width << "," << lut[i].r << "," << lut[i].g << ","
              << lut[i].b << "," << ref[i].r << "," << ref[i].g << "," << ref[i].b;
          if (decompose)
            csv << "," << channels[i].r << "," << channels[i].g << "," << channels[i].b << ","
                << direct[i].r << "," << direct[i].g << "," << direct[i].b << "," << isotropic[i].r
                << "," << isotropic[i].g << "," << isotropic[i].b;
          else
            csv << ",,,,,,,,,";
          csv << "\n";
        }
  }
  return 0;
}

}  // namespace
}  // namespace sky::test

int main(int argc, char** argv) {
  try {
    return sky::test::run(argc, argv);
  } catch (const sky::Error& e) {
    std::cerr << "spectral_sky: " << e.what() << "\n";
    return e.exitCode();
  } catch (const std::exception& e) {
    std::cerr << "spectral_sky: " << e.what() << "\n";
    return 1;
  }
}
