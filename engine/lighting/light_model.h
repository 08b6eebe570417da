#pragma once
// How much light the sun and the moon give at the ground, and how the exposure follows
// the day into night. Plain functions of elevation, phase and distance so tests can check
// each against its source. Units are in shaders/common/lighting_shared.h.
#include <glm/vec3.hpp>

namespace sky::light {

// Photometric units of the renderer: radiance 1 = 10^4 cd/m^2, illuminance 1 = pi 10^4 lux.
constexpr double kLuxPerUnit = 3.14159265358979323846 * 1.0e4;
// Solar illuminance at the top of the atmosphere at 1 AU (photometric solar constant).
constexpr double kSolarIlluminanceLux = 127500.0;
// Illuminance of a V = 0 star outside the atmosphere (Allen's Astrophysical Quantities).
constexpr double kVegaIlluminanceLux = 2.54e-6;
constexpr double kMoonRadiusKm = 1737.4;

// Angstrom exponent of the aerosols: their optical depth goes as (lambda / 550 nm)^-1.3.
constexpr double kAerosolAngstrom = 1.3;

// What the R, G, B channels stand for in the extinction model (and in the physical sky). A
// channel is a linear Rec. 709 component, so a spectral coefficient enters it averaged over
// the channel's colour-matching function (CIE 1931 to Rec. 709) times the sun's spectrum (ASTM
// E-490): the averages under which an optically thin atmosphere rendered in three channels is
// its spectrum converted to Rec. 709. Single wavelengths (680, 550 and 440 nm until issue 30)
// made the zenith a quarter too red with the sun 5 degrees up and the setting sun far too
// bright (docs/atmosphere.md, "A spectral reference", which also says how to recompute these).
//
// Aerosols, (l / 550 nm)^-a: at these wavelengths the law gives the channel averages exactly
// for a = 1.3 and within 0.5 % for a from 0.5 to 2.
constexpr glm::dvec3 kChannelAerosolWavelengthsNm{642.1, 544.8, 441.8};
// Rayleigh optical depth of the whole atmosphere at sea level, the channel averages of
// Hansen & Travis (1974) eq. 2.29.
constexpr glm::dvec3 kChannelRayleighDepth{0.05003, 0.09911, 0.23582};
// Ozone's absorption cross-section at 293 K (Bogumil et al. 2003), channel averages in cm^2.
// Blue's average is negative (its matching function dips below 0 where ozone absorbs most)
// and is taken as 0: no medium adds light.
constexpr glm::dvec3 kChannelOzoneCrossSectionCm2{5.029e-21, 3.218e-21, 0.0};

// Kasten & Young (1989) relative air mass for an apparent elevation in degrees. Clamped at
// -1 degree, below which the formula turns back; a body that low is hidden anyway.
double airMass(double apparentElevationDeg);

// The lower atmosphere of the lighting model as a medium: per-channel extinction at sea level
// (1/m) of the air molecules (Rayleigh) and the aerosols, each falling off exponentially with
// its scale height. Its vertical optical depths are those of atmosphereTransmittance, so the
// haze a view ray crosses (the composite's aerial perspective for sky.model kozlov) is the
// same air that reddens the sun and the moon.
struct HazeMedium {
  glm::dvec3 rayleighPerM{0.0};  // Rayleigh extinction at sea level, 1/m
  glm::dvec3 aerosolPerM{0.0};   // aerosol extinction at sea level, 1/m
  double rayleighHeightM = 8434.0;
  double aerosolHeightM = 1200.0;
};
HazeMedium hazeMedium(double turbidity);

// Direct-beam transmittance of the atmosphere per channel: Rayleigh (Hansen & Travis 1974
// optical depth, scaled by the standard-atmosphere pressure at the observer's altitude),
// ozone (Chappuis band, 300 DU) and aerosol (Angstrom exponent 1.3, optical depth
// `turbidity` at 550 nm, scale height 1.2 km), along `airMass(elevation)`. Integrated over
// the spectrum: each channel's share of the sunlight (spectral_tables.h) that the air lets
// through, every 5 nm. One optical depth a channel (the channel averages above) is right for
// thin air but misses the colour through many air masses, where only the long-wavelength end
// of each channel gets through: red/green 1.63 instead of 1.80 with the sun 3 degrees up.
glm::dvec3 atmosphereTransmittance(double apparentElevationDeg, double altitudeM, double turbidity);

// Rayleigh optical depth of the whole atmosphere at sea level at `lambdaNm`, Hansen & Travis
// (1974) eq. 2.29.
double rayleighDepth(double lambdaNm);
glm::dvec3 atmosphereTransmittance(double apparentElevationDeg, double altitudeM, double turbidity);

// Share of a disc of angular radius `radiusDeg` centred at `elevationDeg` that lies above the
// horizon (the exact circular-segment area), so a setting body dims smoothly.
double discAboveHorizon(double elevationDeg, double radiusDeg);

// Moon illuminance outside the atmosphere, lux: Krisciunas & Schaefer (1991) eq. 8,
// I = 10^(-0.4 (3.84 + 0.026 |a| + 4e-9 a^4)) foot-candles at the mean distance, a the
// phase angle in degrees, scaled by the inverse square of the distance.
double moonIlluminanceLux(double phaseAngleDeg, double distanceKm);

// Earthshine on the moon relative to sunlight on it. Full Earth seen from the moon is about
// 5 magnitudes brighter than the full moon seen from Earth, i.e. about 2.4e-4 of sunlight
// (Danjon's measurements); scaled by Earth's illuminated fraction as seen from the moon,
// which is 1 - k for a moon illuminated fraction k.
double earthshineRatio(double moonIlluminatedFraction);

// Clear-sky horizontal illuminance from the sun and sky, lux, by apparent sun elevation:
// log-interpolated from commonly tabulated values (noon ~1e5, sunset ~750, end of civil
// twilight 3.4, nautical 0.008, astronomical ~6e-4 lux, then the natural night floor).
double twilightIlluminanceLux(double sunElevationDeg);

// How far the exposure has followed the twilight down after sunset, in stops: `adaptation`
// times the stops lost since sunset (0 while the sun is up). The lower bound of the night
// lift (sceneNightLiftEv) and the lift the palette is authored for (paletteExposureEv).
double nightLiftEv(double sunElevationDeg, double adaptation);

// The night lift of a scene whose sky (at the horizon) has luminance `skyLuminance`, with the
// sun at `sunElevationDeg`: an eye follows the twilight's fall all the way (every stop of
// nightLiftEv(h, 1)) down to the light of the brightest moonlit night, `moonlitSkyLuminance`
// (a full moon overhead), where the lift is the full night lift nightLiftEv(-90, adaptation);
// a darker sky is lifted by `adaptation` of the stops it is darker. Never less than the sun's
// lift nightLiftEv(sunElevationDeg, adaptation) nor more than all the twilight's stops, so 0
// by day. Luminances in any one unit. docs/lighting.md, "Night lift".
double sceneNightLiftEv(double sunElevationDeg, double skyLuminance, double moonlitSkyLuminance,
                        double adaptation);

// The lift of a low sun, in stops: a camera's or an eye's exposure follows the light a
// setting sun loses only in part, kLowSunAdaptation of the stops the clear-sky illuminance
// (twilightIlluminanceLux) has fallen from 10 degrees (full daylight) down to `sunElevationDeg`,
// held at its sunset value below the horizon: 0.11 EV at 6 degrees, 0.27 at 3, 0.47 at 0,
// which the night lift passes within a degree below the horizon.
double lowSunLiftEv(double sunElevationDeg);
constexpr double kLowSunAdaptation = 0.1;

// output.exposure auto: the larger of the low sun's lift and the night lift, so the exposure
// rises gently through sunset and then follows the twilight and the night without a step.
double autoExposureEv(double sunElevationDeg, double nightLiftEv);

// The night adaptation the palette is authored for: lighting.palette holds the sky as it
// should look after paletteExposureEv stops of night lift, the standard night_adaptation's.
constexpr double kPaletteNightAdaptation = 0.8;

// The stops the palette at this sun elevation is authored above the physical sky:
// nightLiftEv(sunElevationDeg, kPaletteNightAdaptation). The lighting divides them out, so
// the scene-linear image is physical whatever output.exposure does with it.
double paletteExposureEv(double sunElevationDeg);

// 1 by day, 0 at full night, continuous: the share of the sunset-to-night darkening (in
// stops) still ahead. 0.5 is where the key light hands over from sun to moon.
double dayFactor(double sunElevationDeg);

// The moon's colour relative to the sun's: its reflectance reddens sunlight (B-V 0.92
// against the sun's 0.65), normalised to unit Rec.709 luminance.
glm::dvec3 moonColor();

// The sun's colour above the atmosphere in linear Rec.709 with its D65 white, normalised to
// unit luminance: the solar spectrum (ASTM E-490, spectral_tables.h) through the CIE 1931
// colour-matching functions, about (1.09, 0.97, 0.93): a 5900 K sun is a little warmer than
// D65's average daylight. Through the air it is what atmosphereTransmittance leaves of each
// channel's share (both integrate over the same spectrum), so the noon sun at the ground is
// about the 5500 K of a photographer's daylight, as Cycles' Nishita sky and Bruneton's
// precomputed atmosphere have it.
glm::dvec3 solarColor();

// Kasten & Czeplak (1980): the share of the clear sky's global irradiance that reaches the
// ground under an overcast share n of the sky, 1 - 0.75 n^3.4 (n clamped to 0..1).
double overcastGlobalShare(double n);

// Rec.709 luminance of a linear colour.
double luminance(const glm::dvec3& rgb);

// Illuminance (renderer units, rgb) from a body at apparent elevation `elevationDeg` with
// angular radius `radiusDeg` and illuminance `aboveAtmosphere` outside the air, arriving at a
// point `altitudeM` above the ground: the point sees below the sea-level horizon by the dip
// acos(R / (R + h)), so high clouds stay sunlit after sunset, through a redder, longer path.
glm::vec3 illuminanceAtAltitude(const glm::vec3& aboveAtmosphere, double elevationDeg,
                                double radiusDeg, double altitudeM, double turbidity);

// The same at a cloud layer's base, middle and top: the raymarch lights a sample with the
// light at its own altitude, log-quadratic through these three (volumetric_clouds.comp
// keyLightAt), and export-volume hands them to the path tracer.
struct LayerIlluminance {
  glm::vec3 base, middle, top;
};
LayerIlluminance illuminanceAcrossLayer(const glm::vec3& aboveAtmosphere, double elevationDeg,
                                        double radiusDeg, double baseM, double topM,
                                        double turbidity);

}  // namespace sky::light
