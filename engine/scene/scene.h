#pragma once
// The scene: plain settings structs, filled from YAML or JSON (engine/scene/scene_io.h).
// Defaults here are the defaults of the file format; `skyrender validate` prints them back.
// File keys are snake_case versions of the member names (exposureEv -> exposure_ev).
// Keys, ranges and descriptions are written once, in engine/scene/scene_fields.h: a new
// member here needs one line there to be read, printed and put in the JSON Schema. A choice
// (a model, a mode) is an enum class with its table of file names, enumNames(), beside it
// (engine/scene/field_rules.h): the scene layer reads and prints the names, the rest of the
// code switches on the enum.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/scene/field_rules.h"
#include "engine/scene/iso_time.h"

namespace sky {

// output.exposure: how the display path exposes the physical scene-linear image (never the
// EXR). auto: the lighting model's lift (LightingState::autoExposureEv: a low sun's gentle
// lift, then the night lift following the sky's light, twilight and moon); histogram: metered from the frame's own luminance, adapting
// over a sequence's frames (exposure_adaptation_s); fixed: exposure_ev alone.
enum class ExposureMode { Auto, Histogram, Fixed };
constexpr auto enumNames(ExposureMode) {
  return std::to_array<EnumName<ExposureMode>>({{ExposureMode::Auto, "auto"},
                                                {ExposureMode::Histogram, "histogram"},
                                                {ExposureMode::Fixed, "fixed"}});
}

struct OutputSettings {
  int width = 1280;              // pixels, 1..16384
  int height = 720;              // pixels, 1..16384
  std::string name = "sky";      // file stem: [A-Za-z0-9._-], not starting with '.'
  ExposureMode exposure = ExposureMode::Auto;
  double exposureEv = 0.0;       // stops added to the exposure, -20..20 (not applied to EXR)
  double exposureAdaptationS = 0.0;  // histogram: time constant of the adaptation, s, 0..3600
  bool nightLook = true;         // the display's mesopic/scotopic look for dim scenes
  std::string display = "sRGB";  // OCIO display
  std::string view = "AgX";  // OCIO view (docs/outputs.md, "Views": why AgX)
  bool dither = true;  // dither the 8-bit PNG (not the EXR) so smooth gradients do not band
  // The perception layers in the EXR (clouds.optical_depth, clouds.distance, label,
  // cloud_type, air.transmittance, ground.cloud_shadow; docs/outputs.md): one more march of
  // the clouds' density per pixel (passes/cloud_perception).
  bool perception = false;

  bool operator==(const OutputSettings&) const = default;
};

// camera.projection: a pinhole, or the whole sphere (360 x 180 degrees centred on `heading`;
// pitch, roll and vertical_fov are ignored).
enum class CameraProjection { Perspective, Equirectangular };
constexpr auto enumNames(CameraProjection) {
  return std::to_array<EnumName<CameraProjection>>(
      {{CameraProjection::Perspective, "perspective"},
       {CameraProjection::Equirectangular, "equirectangular"}});
}

// camera.mode: a camera at latitude/longitude/altitude_m looking along heading/pitch, or the
// weather region seen from straight above (CameraSettings::mode).
enum class CameraMode { Observer, GeographicTopdown };
constexpr auto enumNames(CameraMode) {
  return std::to_array<EnumName<CameraMode>>(
      {{CameraMode::Observer, "observer"}, {CameraMode::GeographicTopdown, "geographic_topdown"}});
}

struct CameraSettings {
  double latitude = 47.37;    // degrees, -90..90
  double longitude = 8.54;    // degrees, -180..180
  double altitudeM = 500.0;   // metres above sea level, -500..100000
  double heading = 180.0;     // degrees clockwise from north, -360..360
  double pitch = 15.0;        // degrees above the horizon, -90..90
  double roll = 0.0;          // degrees about the view direction, -180..180, + banks right
  double verticalFov = 60.0;  // degrees, 1..179 (perspective)
  CameraProjection projection = CameraProjection::Perspective;
  // Observer: a camera at latitude/longitude/altitude_m looking along heading/pitch.
  // GeographicTopdown: the weather region mapped exactly onto the image (row 0 = north
  // edge, column 0 = west edge, equal lat/lon spacing), rays straight down from above the
  // top cloud layer; the other camera keys are ignored.
  CameraMode mode = CameraMode::Observer;

  bool operator==(const CameraSettings&) const = default;
};

// `time` is one instant or a time-lapse range. In a file: a single ISO 8601 string, the
// interval text "START/END/STEP", or a map {start, end, step}.
struct TimeSettings {
  IsoTime start =
      IsoTime::parse("2024-06-21T12:00:00+02:00").value();  // the instant or first frame
  std::optional<IsoTime> end;  // a range when set: frames start, start+step, ... up to end
  double stepSeconds = 0.0;    // > 0 for a range

  static constexpr int64_t kMaxFrames = 100000;
  bool isRange() const { return end.has_value(); }
  int64_t frameCount() const;          // 1 for an instant
  IsoTime frame(int64_t index) const;  // written in the zone of `start`

  bool operator==(const TimeSettings&) const = default;
};

// An explicit sun placement (art direction, tests). When azimuth/elevation are absent the
// sun follows `time` and the camera position.
struct SunSettings {
  std::optional<double> azimuth;    // degrees from north through east, -360..360
  std::optional<double> elevation;  // degrees above the horizon, -90..90
  double angularDiameter = 0.53;    // degrees, 0.01..20
  double discScale = 1.0;           // multiplies the physical disc radiance, 0..1e3

  bool operator==(const SunSettings&) const = default;
};

// The moon follows `time` and place; azimuth/elevation override its placement only (phase,
// distance and brightness still come from the ephemeris).
struct MoonSettings {
  std::optional<double> azimuth;
  std::optional<double> elevation;
  double discScale = 1.0;   // multiplies the physical disc radiance, 0..1e3
  double earthshine = 1.0;  // multiplies the modelled earthshine on the dark limb, 0..100

  bool operator==(const MoonSettings&) const = default;
};

// sky.model: Kozlov 3.1 (colours from the lighting palette) or Hillaire 2020's physically
// based atmosphere (AtmosphereSettings).
enum class SkyModel { Kozlov, Physical };
constexpr auto enumNames(SkyModel) {
  return std::to_array<EnumName<SkyModel>>(
      {{SkyModel::Kozlov, "kozlov"}, {SkyModel::Physical, "physical"}});
}

// The clear sky: Kozlov 3.1 (colours from the lighting palette, geometry here) or the
// physically based Hillaire 2020 atmosphere (AtmosphereSettings).
struct SkySettings {
  SkyModel model = SkyModel::Kozlov;
  double glowSize = 0.50;      // s, 0..1 (kozlov)
  double glowExponent = 8.0;   // n in l = s max(V.S, 0)^n, 1..64 (kozlov; Kozlov 3.1: 2)
  double hazeHeight = 0.70;    // hmax as a fraction of the dome height, 0.001..1 (kozlov)

  bool operator==(const SkySettings&) const = default;
};

// atmosphere.aerosols: the Mie coefficients from lighting.turbidity (one atmosphere for the
// sky and for the light the sun, the moon, the clouds and the ground receive), or the
// atmosphere's own mie_scattering and mie_extinction.
enum class AerosolSource { Turbidity, Settings };
constexpr auto enumNames(AerosolSource) {
  return std::to_array<EnumName<AerosolSource>>(
      {{AerosolSource::Turbidity, "turbidity"}, {AerosolSource::Settings, "settings"}});
}

// The planet's atmosphere for sky.model "physical" (Hillaire 2020, Earth defaults from his
// Table 1). Coefficients are in 1/Mm (10^-6 per metre), heights in km. A channel's
// coefficient is the average of the spectrum over that channel (light_model.h,
// kChannelAerosolWavelengthsNm): Rayleigh and ozone are Hillaire's Earth (Bruneton & Neyret's
// l^-4, 300 DU of ozone with the 293 K cross-section) averaged so; his Table 1 gives their
// values at 680, 550 and 440 nm, which made the sky at a low sun too red (docs/atmosphere.md).
struct AtmosphereSettings {
  double groundRadiusKm = 6360.0;                         // 100..100000
  double thicknessKm = 100.0;                             // top radius = ground + this, 1..1000
  glm::vec3 rayleighScattering{7.051f, 13.827f, 32.19f};  // 1/Mm per channel
  double rayleighScaleHeightKm = 8.0;                    // 0.01..100
  double mieScattering = 3.996;                          // 1/Mm
  double mieExtinction = 4.40;                           // 1/Mm, >= mie_scattering
  double mieScaleHeightKm = 1.2;                         // 0.01..100
  double mieAnisotropy = 0.8;                            // g of Cornette-Shanks, -0.99..0.99
  AerosolSource aerosols = AerosolSource::Turbidity;
  glm::vec3 ozoneAbsorption{2.703f, 1.730f, 0.0f};       // 1/Mm at the tent's peak
  double ozoneCenterKm = 25.0;                           // tent centre altitude
  double ozoneHalfWidthKm = 15.0;                        // tent half width, 0.01..100
  // Not a scene key: the renderer copies ground.albedo here, so the ground the composite
  // draws and the ground bounce in the multiple-scattering LUT are one surface.
  glm::vec3 groundAlbedo{0.3f};  // 0..1
  // Not a scene key either: the Angstrom exponent of the Mie coefficients, which stand for
  // 550 nm (0: grey, Hillaire's). aerosols: turbidity sets the lighting model's.
  double mieAngstrom = 0.0;

  bool operator==(const AtmosphereSettings&) const = default;
};

// The ground below the horizon (passes/atmosphere_composite): a Lambertian sphere at sea
// level lit by the sun and the moon through the clouds' shadows and by the sky, seen through
// the aerial perspective. Its albedo is also the physical atmosphere's ground bounce.
struct GroundSettings {
  // Linear Rec.709 reflectance: summer farmland and forest seen from afar (green vegetation
  // reflects 5-15 % in the visible, soil and fields 10-25 %).
  glm::vec3 albedo{0.10f, 0.12f, 0.07f};  // 0..1

  bool operator==(const GroundSettings&) const = default;
};

// high_clouds.source: the coefficient texture baked from noise and cover (cached on disk), or
// read from the files high_clouds.coefficients and normals.
enum class HighCloudSource { Procedural, Image };
constexpr auto enumNames(HighCloudSource) {
  return std::to_array<EnumName<HighCloudSource>>(
      {{HighCloudSource::Procedural, "procedural"}, {HighCloudSource::Image, "image"}});
}

// high_clouds.style: what the procedural bake draws.
enum class HighCloudStyle { Cirrus, Cirrostratus, Cirrocumulus };
constexpr auto enumNames(HighCloudStyle) {
  return std::to_array<EnumName<HighCloudStyle>>({{HighCloudStyle::Cirrus, "cirrus"},
                                                  {HighCloudStyle::Cirrostratus, "cirrostratus"},
                                                  {HighCloudStyle::Cirrocumulus, "cirrocumulus"}});
}

// high_clouds.cover_source: where the procedural layer's cover comes from (HighCloudSettings).
enum class HighCloudCoverSource { Auto, Scene, Weather };
constexpr auto enumNames(HighCloudCoverSource) {
  return std::to_array<EnumName<HighCloudCoverSource>>(
      {{HighCloudCoverSource::Auto, "auto"},
       {HighCloudCoverSource::Scene, "scene"},
       {HighCloudCoverSource::Weather, "weather"}});
}

// The high-cloud layer (cirrus, cirrostratus, cirrocumulus): a Kozlov coefficient texture and
// normal map on a sphere at `altitudeM`, scrolled by the wind. See docs/high-clouds.md.
struct HighCloudSettings {
  HighCloudSource source = HighCloudSource::Procedural;
  HighCloudStyle style = HighCloudStyle::Cirrus;  // procedural
  double cover = 0.0;                             // 0..1 (procedural); 0: no high clouds
  std::string coverMap;                           // optional greyscale image multiplying `cover`
  std::string coefficients;   // "image": RGBA PNG/EXR (thin lit, dense, clear, edges)
  std::string normals;        // "image": tangent-space normal map; "": derived
  int resolution = 1024;      // baked texture size (square, power of two), 64..4096
  int seed = 1;               // procedural noise seed, 0..2^31-1
  double altitudeM = 9000.0;  // layer altitude above sea level, 1000..20000
  double tileSizeKm = 30.0;   // ground size of one texture repeat, 0.1..10000
  double windSpeedMs = 15.0;  // 0..200
  double windFrom = 270.0;    // direction the wind blows from, degrees from north; a
                              // procedural texture's +u (its streaks) is laid downwind
  double edgeGlowDeg = 10.0;  // l: angular width of the edge glow (Kozlov 3.4), 0.5..90
  double brightness = 1.0;    // multiplies the cloud terms, 0..100
  // Where the procedural layer's cover comes from: Scene (`cover`, uniform), Weather (the
  // weather map's high-layer cover per pixel, from a forecast file) or Auto (Weather when
  // the weather map has a high layer, else Scene).
  HighCloudCoverSource coverSource = HighCloudCoverSource::Auto;

  bool operator==(const HighCloudSettings&) const = default;
};

// A volumetric cloud layer: a spherical shell between two altitudes above sea level.
struct CloudLayerSettings {
  double baseM = 0.0;  // 0..30000
  double topM = 0.0;   // > baseM

  bool operator==(const CloudLayerSettings&) const = default;
};

// clouds.model: the density and noise model, Lu et al. 2023 or Tang et al. 2019.
enum class CloudModel { Lu2023, Tang2019 };
constexpr auto enumNames(CloudModel) {
  return std::to_array<EnumName<CloudModel>>(
      {{CloudModel::Lu2023, "lu2023"}, {CloudModel::Tang2019, "tang2019"}});
}

// clouds.coverage: how cover sets the noise threshold, calibrated (the covered area equals the
// cover, engine/clouds/coverage_calibration.h) or as the paper writes it (Lu's 1 - CMc).
enum class CloudCoverageMode { Calibrated, Paper };
constexpr auto enumNames(CloudCoverageMode) {
  return std::to_array<EnumName<CloudCoverageMode>>(
      {{CloudCoverageMode::Calibrated, "calibrated"}, {CloudCoverageMode::Paper, "paper"}});
}

// clouds.phase: Henyey-Greenstein, Lu (23), or a dual lobe that adds a back-scattering lobe.
enum class CloudPhase { Hg, DualLobe };
constexpr auto enumNames(CloudPhase) {
  return std::to_array<EnumName<CloudPhase>>(
      {{CloudPhase::Hg, "hg"}, {CloudPhase::DualLobe, "dual_lobe"}});
}

// clouds.quality: the raymarch as tuned for speed, or the reference every optimisation is
// measured against (docs/clouds.md, "Reference"): small fixed steps, no early exit, no
// empty-space skipping, a long uniform light march, full resolution, no temporal reuse.
enum class CloudQuality { Standard, Reference };
constexpr auto enumNames(CloudQuality) {
  return std::to_array<EnumName<CloudQuality>>(
      {{CloudQuality::Standard, "standard"}, {CloudQuality::Reference, "reference"}});
}

// clouds.light: how a view sample finds the light reaching it through the cloud (Lu (24)):
// a march toward each light at every sample, or the cloud light volume made once per frame
// (or less often) with a finer march, the sample marching only the nearest steps itself.
enum class CloudLight { March, Volume };
constexpr auto enumNames(CloudLight) {
  return std::to_array<EnumName<CloudLight>>(
      {{CloudLight::March, "march"}, {CloudLight::Volume, "volume"}});
}

// clouds.temporal.mode: whether frames of a sequence reuse the clouds of the frames before
// (passes/cloud_temporal).
enum class CloudTemporalMode { Off, On };
constexpr auto enumNames(CloudTemporalMode) {
  return std::to_array<EnumName<CloudTemporalMode>>(
      {{CloudTemporalMode::Off, "off"}, {CloudTemporalMode::On, "on"}});
}

// clouds.temporal.resolution: the clouds of a sequence marched and kept at the view's size,
// or at half its width and height and upsampled (passes/cloud_upsample).
enum class CloudTemporalResolution { Full, Half };
constexpr auto enumNames(CloudTemporalResolution) {
  return std::to_array<EnumName<CloudTemporalResolution>>(
      {{CloudTemporalResolution::Full, "full"}, {CloudTemporalResolution::Half, "half"}});
}

// Temporal reuse of the volumetric clouds (Nubis-style): each frame marches one pixel of every
// block x block square and reprojects the rest from the frames before, with the camera's
// motion and the wind. A single frame (a still) is unchanged whatever these say: it marches
// every pixel. docs/clouds.md, "Temporal reuse".
struct CloudTemporalSettings {
  CloudTemporalMode mode = CloudTemporalMode::Off;
  int block = 4;  // 1..4: a frame marches 1 / block^2 of the pixels
  CloudTemporalResolution resolution = CloudTemporalResolution::Full;

  bool operator==(const CloudTemporalSettings&) const = default;
};

// The volumetric low and mid clouds (Lu et al. 2023, Tang et al. 2019), raymarched through
// the shells of `low` and `mid`, with cover and type from the weather map. See docs/clouds.md.
struct CloudSettings {
  CloudQuality quality = CloudQuality::Standard;  // the tuned march, or the reference
  CloudTemporalSettings temporal;
  CloudLight light = CloudLight::March;  // marched per sample, or from a light volume
  CloudModel model = CloudModel::Lu2023;                       // density and noise model
  CloudCoverageMode coverage = CloudCoverageMode::Calibrated;  // how cover sets the remap
  double extinction = 0.1;                  // sigma_t per metre at density 1, 1e-5..1
  double g = 0.6;                           // Henyey-Greenstein asymmetry, Lu (23), -0.99..0.99
  CloudPhase phase = CloudPhase::DualLobe;  // DualLobe adds a back-scattering lobe
  double gBack = -0.3;                      // the back lobe's asymmetry, -0.99..0
  double backWeight = 0.2;                  // the back lobe's share, 0..1
  double attenuationClamp = 0.02;           // Lu's ac, 0..1, Lu (22)
  double stepM = 20.0;                      // view-ray step near the camera, metres
  double stepGrowth = 0.002;                // extra step length per metre of distance
  int maxSteps = 512;                       // per view ray
  int samples = 1;                          // marches per pixel, averaged: 1..64
  bool denoise = true;  // a still's one march per pixel filtered of its grain (cloud_denoise)
  int lightSteps = 5;                 // short steps toward the light (plus one long one), 1..16
  int lightSplit = 2;                 // samples per short light step (the long one 2x), 1..4
  double lightDistanceM = 1200.0;     // length covered by the short light steps, metres
  double transmittanceCutoff = 0.05;  // stop marching below this transmittance
  bool energyConserving = true;       // Hillaire 2016's integration of each step
  int scatteringOctaves = 3;          // multiple-scattering octaves (Wrenninge); 1 = single
  double multipleScattering = 2.2;    // strength of the diffusion term, 0..4 (0: octaves only)
  double edgeSharpness = 4.0;         // density gain at cloud boundaries, 1..32 (1: the noise's)
  double shapeScaleKm = 5.0;          // ground size of one repeat of the shape noise
  double detailScaleKm = 0.4;         // ground size of one repeat of the detail noise
  double windSpeedMs = 10.0;          // moves the noise with time, 0..200
  double windFrom = 270.0;            // degrees clockwise from north
  CloudLayerSettings low{500.0, 2500.0};
  CloudLayerSettings mid{3000.0, 6500.0};

  bool operator==(const CloudSettings&) const = default;
};

// The weather region: latitudes [south, north] and longitudes [west, east] in degrees. It has
// no meaningful default: a scene gives both bounds or none (WeatherSettings::region).
struct WeatherRegion {
  glm::dvec2 lat{0.0, 1.0};
  glm::dvec2 lon{0.0, 1.0};

  bool operator==(const WeatherRegion&) const = default;
};

// The pressure levels of one cloud layer in a forecast file and Lu's critical humidity.
struct WeatherLevelSettings {
  double bottomHpa = 1000.0;  // the layer's lower bound (higher pressure), 1..1100
  double topHpa = 800.0;      // its upper bound (lower pressure), < bottomHpa
  double rhCritical = 0.8;    // Lu (2): rh_cr, 0..0.99

  bool operator==(const WeatherLevelSettings&) const = default;
};

// The cellular automaton of weather.evolution "ca" (engine/weather/cloud_automaton.h).
struct WeatherAutomatonSettings {
  double stepS = 300.0;       // scene time per automaton step, seconds, 10..3600
  double windowH = 6.0;       // window length when the map has no forecast steps, hours
  double lifetimeMin = 30.0;  // mean life of a cloud voxel (sets Dobashi's p_ext), minutes
  double strength = 1.0;      // how far the automaton's density replaces the map cover, 0..1

  bool operator==(const WeatherAutomatonSettings&) const = default;
};

// weather.source: where the weather map comes from, fbm cover, a painted image or a GRIB2 or
// NetCDF forecast. (WeatherSource, engine/weather/weather_source.h, is the map's builder.)
enum class WeatherMapSource { Procedural, Image, File };
constexpr auto enumNames(WeatherMapSource) {
  return std::to_array<EnumName<WeatherMapSource>>({{WeatherMapSource::Procedural, "procedural"},
                                                    {WeatherMapSource::Image, "image"},
                                                    {WeatherMapSource::File, "file"}});
}

// weather.cloud_type: the map's type channel (cloudTypeValue, engine/weather/weather_map.h).
enum class CloudType { Stratus, Stratocumulus, Cumulus, Altostratus, Altocumulus };
constexpr auto enumNames(CloudType) {
  return std::to_array<EnumName<CloudType>>({{CloudType::Stratus, "stratus"},
                                             {CloudType::Stratocumulus, "stratocumulus"},
                                             {CloudType::Cumulus, "cumulus"},
                                             {CloudType::Altostratus, "altostratus"},
                                             {CloudType::Altocumulus, "altocumulus"}});
}

// weather.cover: a forecast's cover from relative humidity, Lu (1)(2), or the model's own
// layer cloud cover.
enum class WeatherCover { Rh, Tcc };
constexpr auto enumNames(WeatherCover) {
  return std::to_array<EnumName<WeatherCover>>(
      {{WeatherCover::Rh, "rh"}, {WeatherCover::Tcc, "tcc"}});
}

// weather.advection: how the map moves with time (WeatherSettings::advection).
enum class WeatherAdvection { None, Data, Wind };
constexpr auto enumNames(WeatherAdvection) {
  return std::to_array<EnumName<WeatherAdvection>>({{WeatherAdvection::None, "none"},
                                                    {WeatherAdvection::Data, "data"},
                                                    {WeatherAdvection::Wind, "wind"}});
}

// weather.evolution: clouds that grow and dissolve between forecast steps by a cellular
// automaton (Ca), or not.
enum class WeatherEvolution { None, Ca };
constexpr auto enumNames(WeatherEvolution) {
  return std::to_array<EnumName<WeatherEvolution>>(
      {{WeatherEvolution::None, "none"}, {WeatherEvolution::Ca, "ca"}});
}

// The weather map the volumetric clouds read: per lat/lon cell the low and mid cover (Lu's
// CMc), the cloud type and a density scale. See docs/weather.md.
struct WeatherSettings {
  WeatherMapSource source = WeatherMapSource::Procedural;
  // The map's bounds. Absent: a square of cameraRegionKm centred on the camera (snapped to the
  // map's texels), clipped to the data for source "file" (engine/weather/weather_region.h).
  std::optional<WeatherRegion> region;
  double cameraRegionKm = 800.0;  // 10..10000
  // procedural: fbm cover around a mean, per layer.
  double coverLow = 0.0;   // mean low-layer cover, 0..1 (0: no low clouds)
  double coverMid = 0.0;   // mean mid-layer cover, 0..1
  double spread = 0.5;     // how far cover varies around the mean, 0..1
  double scaleKm = 150.0;  // feature size of the cover pattern, km
  int seed = 1;            // 0..2^31-1
  int resolution = 256;    // map texels along its longer side, 8..8192
  // The map's type channel (0 stratiform, 0.5 cellular, 1 convective), shared by both layers.
  CloudType cloudType = CloudType::Cumulus;
  // image: RGBA PNG/EXR over the region (R low cover, G mid cover, B type, A density scale).
  std::string image;
  // file: a GRIB2 or NetCDF forecast; cover from relative humidity (Lu (1)(2)) per layer of
  // pressure levels, or the model's own layer cloud cover ("tcc").
  std::string file;
  WeatherCover cover = WeatherCover::Rh;
  WeatherLevelSettings low{1000.0, 800.0, 0.80};
  WeatherLevelSettings mid{800.0, 450.0, 0.65};
  WeatherLevelSettings high{450.0, 150.0, 0.80};
  // Before the file's first step or after its last (any time, for a single step): Data
  // carries the nearest step's map with the file's wind at steering_hpa, Wind with
  // clouds.wind_*; None holds it.
  WeatherAdvection advection = WeatherAdvection::None;
  double steeringHpa = 500.0;  // 1..1100
  // The instant the map shows at the scene's first frame (ISO 8601, parsed once as the scene
  // is read); later frames of a time-lapse move it on by the same time. Absent: the scene's
  // time.
  std::optional<IsoTime> time;
  // Kozlov section 5's local weather: the cover around the camera filtered over this radius.
  double localRadiusKm = 5.0;  // 0.1..200
  // Cellular-automaton growth and decay between forecast steps (Liu et al. 2015, Dobashi).
  WeatherEvolution evolution = WeatherEvolution::None;
  WeatherAutomatonSettings automaton;

  bool operator==(const WeatherSettings&) const = default;
};

// One palette keyframe: the Kozlov colours at a sun elevation. Colours are scene-linear in
// the renderer's units (1 = 10^4 cd/m^2) as they should appear after the night exposure
// lift (see docs/lighting.md), so night keyframes are small numbers.
struct PaletteKey {
  double sunElevation = 0.0;  // degrees, -90..90
  glm::vec3 skyColor{0.0f};   // Csky
  glm::vec3 fogColor{0.0f};   // Cfog
  glm::vec3 glowColor{0.0f};  // Csun: the glow around the light
  glm::vec3 cloudLit{0.0f};   // C1: dense clouds toward the light (Kozlov 3.3)
  glm::vec3 cloudDark{0.0f};  // C2: dense clouds away from the light
  glm::vec3 ambientTop{0.0f};
  glm::vec3 ambientBottom{0.0f};

  bool operator==(const PaletteKey&) const = default;
};

// The default day-to-night palette (also written out in configs/default.yaml; a test keeps
// the two equal).
std::vector<PaletteKey> defaultPalette();

struct LightingSettings {
  double pressureHpa = 1010.0;  // refraction; 0 turns it off. 0..1200
  double temperatureC = 10.0;   // refraction, -100..100
  // Aerosol optical depth at 550 nm, 0..5 (sun/moon colour, the haze): 0.15, about the mean
  // over land (Remer et al. 2008, MODIS: 0.19 over land, 0.13 over the oceans); 0.1, the
  // default until issue 46, is a clean day, under which a 3 degree sun lit clouds yellower
  // than a typical sunset.
  double turbidity = 0.15;
  // How much of the physical darkening after sunset the exposure makes up, 0..1: night
  // lights (moon, stars, earthshine) are lifted by this fraction of the stops the sky loses.
  double nightAdaptation = 0.75;
  double starBrightness = 1.0;  // multiplies catalogue star fluxes, 0..1e6
  double starExtinction = 0.2;  // magnitudes per air mass, 0..2
  std::vector<PaletteKey> palette = defaultPalette();

  bool operator==(const LightingSettings&) const = default;
};

struct Scene {
  OutputSettings output;
  CameraSettings camera;
  TimeSettings time;
  SunSettings sun;
  MoonSettings moon;
  SkySettings sky;
  AtmosphereSettings atmosphere;
  GroundSettings ground;
  HighCloudSettings highClouds;
  CloudSettings clouds;
  WeatherSettings weather;
  LightingSettings lighting;
  // Not a file key: the folder of the scene file, against which relative paths in it
  // (high_clouds.coefficients, ...) are resolved. Empty for text not read from a file.
  std::filesystem::path baseDir;
  // `path` as written in the scene, resolved against baseDir when relative.
  std::filesystem::path resolvePath(const std::string& path) const;
  // This scene with every file key (high_clouds.cover_map, coefficients, normals,
  // weather.image, weather.file) made absolute, so its printed text means the same from any
  // folder (`skyrender validate`, render reports).
  Scene withAbsolutePaths() const;

  bool operator==(const Scene&) const = default;
};

// A file a render of the scene reads, by the key that names it.
struct SceneInputFile {
  const char* key;              // "high_clouds.coefficients"
  std::string written;          // as the scene gives it
  std::filesystem::path path;   // resolved (Scene::resolvePath)
};
// The files a render reads with the scene's sources: high_clouds.coefficients and normals
// for high_clouds.source image, cover_map for procedural high clouds, weather.image or
// weather.file by weather.source. A weather.file with '*' or '?' is left out (it names
// files by a pattern). `skyrender validate` checks each.
std::vector<SceneInputFile> sceneInputFiles(const Scene& scene);

// clouds.wind_speed_ms from clouds.wind_from as (east, north) m/s.
glm::dvec2 windEastNorthMs(const CloudSettings& clouds);

// What the weather map (engine/weather) is made from: weather.* and the few other facts of
// the scene it reads, each parsed and resolved here once, so no weather function reads a
// whole Scene or resolves a path again.
struct WeatherInputs {
  WeatherSettings settings;          // weather.*, paths as the scene gives them (messages)
  std::filesystem::path image;       // weather.image resolved against the scene's folder
  std::filesystem::path file;        // weather.file resolved (its name may be a pattern)
  glm::dvec2 cameraLatLonDeg{0.0};   // where the default region (no weather.region) centres
  glm::dvec2 windMs{0.0};            // clouds.wind (east, north) m/s: advection "wind"
  IsoTime start;                     // the scene's first frame: the instant weather.time is at
};
WeatherInputs weatherInputs(const Scene& scene);

}  // namespace sky
