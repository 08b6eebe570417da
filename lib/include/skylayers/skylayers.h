#pragma once
// skylayers: the public C++ API (docs/library.md).
//
//   find_package(skylayers CONFIG REQUIRED)
//   target_link_libraries(app PRIVATE skylayers::skylayers)
//   #include <skylayers/skylayers.h>
//
// A Sky holds one scene and everything made for it on the GPU: the pipelines, the baked
// textures, the atmosphere LUTs, the noise and the weather map. Each stays from frame to
// frame and is made again only when what it depends on changes, so make a Sky once and
// render many frames through it. This header uses the standard library only; the engine's
// frame graph and Vulkan wrappers stay inside the library.
//
// Errors are skylayers::Error: one line saying what and where (a scene file's line and key
// path, the key of a set() call), with kind() BadInput for anything the caller can fix.
// A failed call leaves the Sky as it was.
#include <array>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

// What the shared library exports (it is built with hidden visibility: the engine's own
// symbols stay inside). Error's type must be the library's too, so a host catches it.
#define SKYLAYERS_API __attribute__((visibility("default")))

namespace skylayers {

// The library's version ("0.1.0"), the project's CMake version.
SKYLAYERS_API const char* version();
// The folder the shaders and configs are read from: $SKY_DATA_DIR, else the installed
// PREFIX/share/skylayers, else the source tree the library was built from.
SKYLAYERS_API std::string dataDirectory();

class SKYLAYERS_API Error : public std::runtime_error {
public:
  enum class Kind {
    BadInput,  // a scene, key, value or file the caller can fix
    Internal,  // the device, the driver, or a bug
  };
  Error(Kind kind, const std::string& message) : std::runtime_error(message), mKind(kind) {}
  Kind kind() const { return mKind; }

private:
  Kind mKind;
};

// The host's own Vulkan device and a frame in its images: defined in <skylayers/vulkan.h>.
struct VulkanDevice;
struct HostFrame;

// Where a Sky runs.
struct DeviceOptions {
  // "" picks a GPU (discrete, then integrated, then virtual), and the CPU device lavapipe
  // last; a decimal number picks by index, anything else by a case-insensitive part of the
  // name (skyrender --gpu).
  std::string gpu;
  // Khronos validation layers. Off unless $SKY_VALIDATION=1 asks for them.
  bool validation = false;
  bool validationFromEnvironment = true;  // false: `validation` alone decides
  // The OpenColorIO config of display images: "" is $OCIO, else the installed one.
  std::string ocioConfig;
  // The host's Vulkan device to run on (<skylayers/vulkan.h>), instead of one of the Sky's
  // own; `gpu` and `validation` are then ignored. Read during the Sky's creation only.
  const VulkanDevice* vulkan = nullptr;
};

// A camera's place and direction on the Earth (WGS84 latitude and longitude, metres above
// sea level; heading clockwise from north, pitch above the horizon, roll about the view
// direction, positive banking right as an aircraft does; all in degrees).
struct GeoPose {
  double latitudeDeg = 0.0;
  double longitudeDeg = 0.0;
  double altitudeM = 0.0;
  double headingDeg = 0.0;
  double pitchDeg = 0.0;
  double rollDeg = 0.0;
};

// One image of a frame, 32-bit floats, row 0 the top, channels interleaved.
struct SKYLAYERS_API Image {
  std::string name;  // "beauty", "sky", "high_clouds", "clouds"
  int width = 0;
  int height = 0;
  std::vector<std::string> channels;  // "R", "G", "B", "A", then any others ("depth")
  std::vector<float> pixels;          // width * height * channels.size()

  // The value of `channel` at column x, row y; std::out_of_range outside the image or for a
  // channel it lacks.
  float at(int x, int y, const std::string& channel) const;
};

// What render() reads back besides the beauty.
struct RenderRequest {
  // The layers the EXR of `skyrender render` holds: "sky" (R,G,B), "high_clouds" (R,G,B,A),
  // "clouds" (R,G,B,A,depth: the transmittance-weighted distance in metres).
  bool layers = false;
  // The display image: scene-linear through the scene's exposure and the OCIO
  // output.display / output.view, as 8-bit RGBA codes: the codes of `skyrender render`'s
  // PNG, output.dither included.
  bool display = false;
};

struct SKYLAYERS_API Frame {
  // Scene-linear RGB (1 = 10^4 cd/m^2, docs/outputs.md) and the clouds' coverage in A.
  Image beauty;
  std::vector<Image> layers;     // as RenderRequest::layers asked
  std::vector<uint8_t> display;  // as RenderRequest::display asked: width * height * 4
  double exposureEv = 0.0;       // the scene's exposure for the frame, in stops
  double gpuMs = 0.0;            // the frame's GPU time
  std::string time;              // the instant drawn, ISO 8601
  // The render report as JSON text, as `skyrender render` writes it beside the EXR
  // (docs/outputs.md): the settings, the sun and moon, each pass's GPU ms, the costs.
  std::string report;

  // The layer named `name`, or "beauty"; std::out_of_range when the frame lacks it.
  const Image& layer(const std::string& name) const;
};

// One camera of a frame of several views (Sky::renderViews): where it looks, its field of
// view and its image size. Every view stands at the Sky's camera place (a vehicle's rig of
// cameras), so they share the frame's lights, bakes, LUTs, weather map, noise and shadow map.
struct View {
  double headingDeg = 0.0;  // as GeoPose
  double pitchDeg = 0.0;
  double rollDeg = 0.0;
  double verticalFovDeg = 60.0;
  int width = 0, height = 0;
};

// A light for the host's own scene, at the camera's place and time.
struct Light {
  std::array<double, 3> direction{};  // unit vector toward the body: east, north, up
  double azimuthDeg = 0.0;            // from north through east
  double elevationDeg = 0.0;          // apparent (refracted)
  // Illuminance on a surface facing the body, after the atmosphere, the horizon and the
  // clouds between (cloudTransmittance), in lux, per linear Rec.709 channel.
  std::array<double, 3> illuminanceLux{};
  // The share of the body's light the clouds let through on the line toward it (1: none in
  // the way), from the same field the queries read. 1 from lightingAt, which knows no clouds.
  double cloudTransmittance = 1.0;
};

struct Lighting {
  Light sun;
  Light moon;
  // The day<->night interpolation the renderer uses: 1 by day, 0 by night.
  double dayFactor = 1.0;
  std::string key;  // the key light: "sun" or "moon"
};

// A place: latitude and longitude (degrees, WGS84 taken as a sphere) and metres above sea
// level.
struct GeoPoint {
  double latitudeDeg = 0.0;
  double longitudeDeg = 0.0;
  double altitudeM = 0.0;
};

// What a straight line between two points lets through.
struct Transmittance {
  double cloud = 1.0;                        // through the clouds alone: e^-cloudOpticalDepth
  double cloudOpticalDepth = 0.0;            // tau through the clouds
  std::array<double, 3> air{1.0, 1.0, 1.0};  // through the air alone, per Rec.709 channel
  // Both together, per channel.
  std::array<double, 3> total() const { return {cloud * air[0], cloud * air[1], cloud * air[2]}; }
};

// The weather map at a place.
struct CloudCover {
  double low = 0.0;   // cover of the low layer, 0..1
  double mid = 0.0;   // of the mid layer
  double type = 0.0;  // 0 stratiform, 0.5 cellular, 1 convective
};

// A forecast's cloud map on its lat/lon grid.
struct WeatherGrid {
  // Channels cover_low, cover_mid, cover_high (0..1), type (0 stratiform, 0.5 cellular,
  // 1 convective), then low_base_m, low_top_m, mid_base_m, mid_top_m, high_base_m,
  // high_top_m (m above sea level); row 0 the north edge, column 0 the west edge, texel
  // centres at (i + 0.5) / width of the region.
  Image image;
  double southDeg = 0.0, northDeg = 0.0, westDeg = 0.0, eastDeg = 0.0;
};

// The cloud map a GRIB2 or NetCDF forecast file gives, as `skyrender weather FILE` writes
// it: what the renderer would draw at the default scene's first instant, over the file's
// whole grid. `overrides` are scene keys: "weather.region.lat=[0,55]", "weather.cover=tcc",
// "time=...", "weather.time=...". CPU only. BadInput naming the file or the key.
SKYLAYERS_API WeatherGrid weatherMap(const std::string& file,
                                     const std::vector<std::string>& overrides = {});

// The channels of an EXR that skyrender or a dataset wrote, one image per layer: "beauty" for
// the main layer's R, G, B, A, "label" and "cloud_type" for the perception labels, each other
// layer by its name ("clouds": R, G, B, A, depth, optical_depth, distance). CPU only;
// BadInput naming the file when it cannot be read.
SKYLAYERS_API std::vector<Image> readExr(const std::string& path);

// Nine real spherical-harmonic coefficients (bands l = 0, 1, 2) per linear Rec.709 channel,
// over directions in east-north-up (x east, y north, z up), in the order Y00, Y1-1 (y),
// Y10 (z), Y11 (x), Y2-2 (xy), Y2-1 (yz), Y20 (3z^2 - 1), Y21 (xz), Y22 (x^2 - y^2), with
// the usual constants (0.282095, 0.488603, 1.092548, 0.315392, 0.546274).
using SphericalHarmonics = std::array<std::array<double, 3>, 9>;

// The illuminance (lux, per channel) on a surface with unit normal `normal` (ENU) under
// radiance `sh` in cd/m^2: the cosine lobe's convolution (Ramamoorthi and Hanrahan 2001:
// A0 = pi, A1 = 2 pi / 3, A2 = pi / 4).
SKYLAYERS_API std::array<double, 3> irradiance(const SphericalHarmonics& sh,
                                               const std::array<double, 3>& normal);

// The sun and moon at a place and instant with the default scene's atmosphere, with no Sky
// and no GPU: where they are and how much light they give under a clear sky (an ephemeris).
SKYLAYERS_API Lighting lightingAt(double latitudeDeg, double longitudeDeg, double altitudeM,
                                  const std::string& iso8601);

class SKYLAYERS_API Sky {
public:
  // A scene file (YAML or JSON, by its extension); `overrides` are "key.path=value" as
  // skyrender's --set takes them.
  static Sky fromFile(const std::string& path, const std::vector<std::string>& overrides = {},
                      const DeviceOptions& device = {});
  // Scene text; format "yaml" or "json"; `sourceName` names it in errors. Relative file
  // paths in it are taken from the working folder.
  static Sky fromText(const std::string& text, const std::string& format = "yaml",
                      const std::string& sourceName = "<text>",
                      const std::vector<std::string>& overrides = {},
                      const DeviceOptions& device = {});
  // The built-in default scene (configs/default.yaml).
  static Sky fromDefault(const std::vector<std::string>& overrides = {},
                         const DeviceOptions& device = {});

  Sky(Sky&&) noexcept;
  Sky& operator=(Sky&&) noexcept;
  ~Sky();

  // Any scene key by its path, with the value as a scene file would write it:
  // set("clouds.cover", "0.6"), set("weather.file", "gfs.grib2"), set("time",
  // "2024-06-21T20:30:00+02:00"). The scene is checked as a file is; a bad key or value
  // throws BadInput naming it, and the Sky keeps its scene.
  void set(const std::string& keyPath, const std::string& value);
  // Several at once, as "key.path=value", checked together.
  void set(const std::vector<std::string>& assignments);

  void setTime(const std::string& iso8601);  // "2024-06-21T12:00:00+02:00"
  std::string time() const;
  void setCamera(const GeoPose& pose);
  GeoPose camera() const;
  // The camera's direction from a host's own camera axes: its forward (the view direction)
  // and up vectors in the camera's east-north-up frame (the columns of a local camera
  // matrix), which need not be unit or exactly orthogonal. Sets heading, pitch and roll;
  // BadInput for a zero vector or an up along forward.
  void setCameraAxes(const std::array<double, 3>& forward, const std::array<double, 3>& up);
  // The camera from a host's Earth-centred, Earth-fixed pose (WGS84 ECEF, metres: x toward
  // 0N 0E, y toward 0N 90E, z toward the north pole): its position and its forward and up
  // vectors in ECEF (the columns of an ECEF camera matrix; not necessarily unit or exactly
  // orthogonal). The position becomes the latitude, longitude and height above the WGS84
  // ellipsoid (the altitude); the axes, heading, pitch and roll in the east-north-up frame
  // there. All or nothing: BadInput for a position not near the Earth's surface (within
  // 1000 km of its centre, or not finite), or axes as setCameraAxes refuses them.
  void setCameraEcef(const std::array<double, 3>& position, const std::array<double, 3>& forward,
                     const std::array<double, 3>& up);
  // The image size in pixels and, for a perspective camera, the vertical field of view.
  void setSize(int width, int height);
  void setVerticalFov(double degrees);
  // The field of view from a host's projection matrix (column-major, OpenGL or Vulkan clip
  // conventions alike): a symmetric perspective frustum, whose m[1][1] = 1 / tan(fov / 2).
  // BadInput for an orthographic or off-centre matrix, or one whose aspect (m[1][1] /
  // m[0][0]) differs from the image's by more than 0.1 %.
  void setProjectionMatrix(const std::array<double, 16>& columnMajor);

  // The effective scene (defaults filled in) as YAML; a file of it renders the same.
  std::string sceneYaml() const;

  // Renders the scene at its time. With clouds.temporal.mode on, frames rendered one after
  // another reuse each other's clouds, as the window does.
  Frame render(const RenderRequest& request = {});
  // Several views at the camera's place in one frame: one frame graph and one submit, with
  // everything that does not depend on where a camera looks made once. Each Frame is the one
  // render() gives with the camera turned and sized as its view says (the same bits, tested),
  // its report holding the whole frame's passes. No temporal reuse across such frames, and a
  // histogram exposure meters each view on its own. BadInput for no view or an empty one.
  std::vector<Frame> renderViews(const std::vector<View>& views, const RenderRequest& request = {});
  // Draws the frame into the host's own images (<skylayers/vulkan.h>, docs/library.md, "Into
  // the host's images"): records into the host's command buffer, submits nothing. The Sky
  // must be on the host's device (DeviceOptions::vulkan). Where the host's depth holds no
  // geometry its colour becomes the frame render() gives; where it does, the host's pixel is
  // seen through the air to it and behind the clouds in front of it. The camera is the
  // Sky's (setCamera or setCameraAxes, setVerticalFov or setProjectionMatrix); the colour's
  // size becomes the Sky's. The returned Frame has no images, only its time, exposure and
  // report (GPU times 0: the host times its own queue). The host must submit the command
  // buffer, and it must have completed before the Sky's next record() or render(). The Sky
  // keeps a view of the images until then (or forgetHostImages()).
  Frame record(const HostFrame& frame);
  // Drops the Sky's views of the images of the last record(), which must have completed:
  // before the host destroys them (a swapchain that is made again).
  void forgetHostImages();

  // The sun and moon at the camera's place and time, behind the clouds there: on the CPU,
  // no frame needed (the clouds' field is made at the first call, as for the queries below).
  Lighting lighting() const;
  // The same at another instant or place (altitude in metres above sea level), with this
  // scene's atmosphere and clouds; the Sky's own time and camera stay as they are. Each call
  // makes the clouds' field for that instant and place.
  Lighting lighting(const std::string& iso8601) const;
  Lighting lighting(const std::string& iso8601, double latitudeDeg, double longitudeDeg,
                    double altitudeM) const;

  // The light around the camera for the host's ambient: the radiance (cd/m^2) of the whole
  // sphere as the scene shows it (the sky, the clouds, the ground below the horizon, through
  // the air) without the sun's and moon's discs, which lighting() gives as directional
  // lights, projected on spherical harmonics. It renders the sphere at 64 x 32 (about a
  // second on lavapipe): once per change of time or weather, not every frame. The Sky's own
  // frames and their temporal reuse are left as they were.
  SphericalHarmonics ambient();

  // --- Queries, on the CPU ---
  // From the same density field the GPU marches (engine/render/cloud_field.h: the twin of
  // shaders/common/cloud_field.glsl at full detail) at the scene's time, and the physical
  // atmosphere's air. The field is made at the first query after the scene changes (the
  // noise and weather map as a frame makes them) and kept. Queries integrate along their
  // lines every `kQueryStepM`: for a line of sight or a swarm, not for every pixel of every
  // frame. Points outside the weather map's region have no cloud.
  static constexpr double kQueryStepM = 10.0;
  Transmittance transmittance(const GeoPoint& from, const GeoPoint& to);
  // Many lines at once, spread over the machine's cores.
  std::vector<Transmittance> transmittance(const std::vector<std::array<GeoPoint, 2>>& lines);
  // Extinction through cloud at a point, 1/m.
  double cloudExtinction(const GeoPoint& point);
  CloudCover cover(double latitudeDeg, double longitudeDeg);
  // How far (m) from `from` toward `to` the line's cloud optical depth passes `opticalDepth`;
  // -1 when it does not before `to`.
  double firstCloud(const GeoPoint& from, const GeoPoint& to, double opticalDepth = 0.1);
  // The point `distanceM` from the camera along the ray through pixel (x, y) of the image
  // (pixel centres at integer + 0.5, row 0 the top).
  GeoPoint pixelPoint(double x, double y, double distanceM) const;

  // The name of the device the Sky renders on.
  std::string deviceName() const;
  // Vulkan validation messages seen so far (DeviceOptions::validation); each was also
  // printed to stderr. Tests fail when this moves.
  uint64_t validationMessages() const;

private:
  struct Impl;
  explicit Sky(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> mImpl;
};

}  // namespace skylayers
