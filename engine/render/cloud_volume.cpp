#include "engine/render/cloud_volume.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/core/error.h"
#include "engine/lighting/light_model.h"
#include "engine/weather/geo.h"

namespace sky {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kDefaultSideM = 6000.0;
constexpr double kDefaultCentreAheadM = 4000.0;

glm::dvec3 dvec(const glm::vec4& v) {
  return glm::dvec3(v.x, v.y, v.z);
}

std::string metres(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

std::string boxText(const CloudVolumeBox& b) {
  char text[160];
  std::snprintf(text, sizeof text, "%g,%g,%g,%g,%g,%g", b.minM.x, b.minM.y, b.minM.z, b.maxM.x,
                b.maxM.y, b.maxM.z);
  return text;
}

// s_k: how much of the field part k keeps at p (before the finer parts take theirs), rising
// linearly from 0 on each of its handing-over faces to 1 a band inside it. A face hands over
// when the next part reaches past it by at least its own band and two of the next part's
// (there the next part's voxels can hold the ramp, and those of the part after it stay clear
// of it). A face the next part reaches less far past is a face of the field, as one the
// outermost part shares (boxes whose faces nearly meet are best made to meet).
double partKeep(const std::vector<CloudVolumePart>& parts, size_t k, const glm::dvec3& p) {
  const CloudVolumeBox& b = parts[k].box;
  for (int a = 0; a < 3; ++a)
    if (p[a] < b.minM[a] || p[a] > b.maxM[a]) return 0.0;
  const double band = cloudVolumeBlendM(parts, k);
  if (band <= 0.0) return 1.0;
  const CloudVolumeBox& next = parts[k + 1].box;
  const double reach = band + 2.0 * cloudVolumeBlendM(parts, k + 1);
  double nearest = band;
  for (int a = 0; a < 3; ++a) {
    if (b.minM[a] - next.minM[a] >= reach) nearest = std::min(nearest, p[a] - b.minM[a]);
    if (next.maxM[a] - b.maxM[a] >= reach) nearest = std::min(nearest, b.maxM[a] - p[a]);
  }
  return std::clamp(nearest / band, 0.0, 1.0);
}

}  // namespace

void checkCloudVolumeParts(const std::vector<CloudVolumePart>& parts) {
  uint64_t total = 0;
  for (const CloudVolumePart& part : parts) {
    const glm::uvec4 n = cloudVolumeGrid(part.box, part.voxelM).params.voxels;
    total += uint64_t(n.x) * n.y * n.z;
  }
  if (total > kMaxCloudVolumeVoxelsInAll)
    inputError("--box: the " + std::to_string(parts.size()) + " boxes need " +
               std::to_string(total) + " voxels in all, more than the " +
               std::to_string(kMaxCloudVolumeVoxelsInAll) +
               " allowed (use larger voxels or smaller boxes)");
  for (size_t k = 1; k < parts.size(); ++k) {
    const CloudVolumeBox& inner = parts[k - 1].box;
    const CloudVolumeBox& outer = parts[k].box;
    for (int a = 0; a < 3; ++a)
      if (inner.minM[a] < outer.minM[a] || inner.maxM[a] > outer.maxM[a])
        inputError("--box " + boxText(outer) + " (box " + std::to_string(k + 1) +
                   ") must contain --box " + boxText(inner) + " (box " + std::to_string(k) +
                   "): several boxes are nested, finest first");
  }
}

double cloudVolumeBlendM(const std::vector<CloudVolumePart>& parts, size_t k) {
  return k + 1 < parts.size() ? kCloudVolumeBlendVoxels * parts[k + 1].voxelM : 0.0;
}

double cloudVolumeShare(const std::vector<CloudVolumePart>& parts, size_t k, const glm::dvec3& p) {
  double share = partKeep(parts, k, p);
  for (size_t j = 0; j < k && share > 0.0; ++j) share *= 1.0 - partKeep(parts, j, p);
  return share;
}

CloudVolumeBox defaultCloudVolumeBox(const Scene& cloudScene, const glm::vec2& maxCover) {
  const CloudSettings& c = cloudScene.clouds;
  const bool low = maxCover.x > 0.0f, mid = maxCover.y > 0.0f;
  const double base = low || !mid ? c.low.baseM : c.mid.baseM;
  const double top = mid ? c.mid.topM : c.low.topM;
  const double heading = cloudScene.camera.heading * kDeg;
  const glm::dvec2 centre = kDefaultCentreAheadM * glm::dvec2(std::sin(heading), std::cos(heading));
  const double half = 0.5 * kDefaultSideM;
  // The layer's base sinks below the camera's horizontal plane by d^2 / 2R at distance d.
  const double far = glm::length(glm::abs(centre) + glm::dvec2(half));
  const double drop = far * far / (2.0 * kEarthRadiusM);
  const double camera = cloudScene.camera.altitudeM;
  return {glm::dvec3(centre - half, base - camera - drop), glm::dvec3(centre + half, top - camera)};
}

CloudVolumeGrid cloudVolumeGrid(const CloudVolumeBox& box, double voxelM) {
  if (!(voxelM > 0.0) || !std::isfinite(voxelM))
    inputError("--voxel-m " + metres(voxelM) + ": must be above 0");
  CloudVolumeGrid g{box, voxelM, {}};
  uint64_t total = 1;
  for (int a = 0; a < 3; ++a) {
    const double n = std::ceil((box.maxM[a] - box.minM[a]) / voxelM - 1e-9);
    g.params.voxels[a] = static_cast<uint32_t>(std::clamp(n, 1.0, 4.0e9));
    total *= g.params.voxels[a];
  }
  if (total > kMaxCloudVolumeVoxels)
    inputError("--voxel-m " + metres(voxelM) + ": the box needs " +
               std::to_string(g.params.voxels.x) + " x " + std::to_string(g.params.voxels.y) +
               " x " + std::to_string(g.params.voxels.z) + " voxels, more than the " +
               std::to_string(kMaxCloudVolumeVoxels) +
               " allowed (use larger voxels or a smaller --box)");
  g.params.firstVoxelCentreM = glm::vec4(glm::vec3(box.minM + 0.5 * voxelM), 0.0f);
  g.params.voxelM = glm::vec4(glm::vec3(static_cast<float>(voxelM)), 0.0f);
  return g;
}

void setCloudVolumeFootprint(CloudVolumeGrid& grid, CloudVolumeLod lod,
                             const shared::ViewState& view) {
  const bool byView = lod == CloudVolumeLod::View;
  // view.forward.w is the pixel's width per metre of distance, the raymarch's footprint.
  grid.params.footprintPerM = byView ? view.forward.w : 0.0f;
  grid.params.footprintMinM = byView ? static_cast<float>(grid.voxelM) : 0.0f;
}

CloudVolume makeCloudVolume(const Scene& cloudScene, const LightingState& lighting,
                            const IsoTime& time, const shared::ViewState& view,
                            const CloudVolumeGrid& grid, std::vector<float> density,
                            const CloudVolumeBox& lightBox) {
  const CloudSettings& c = cloudScene.clouds;
  CloudVolume v;
  v.extinction.name = "density";
  v.extinction.size = glm::uvec3(grid.params.voxels);
  v.extinction.voxelSize = grid.voxelM;
  v.extinction.firstVoxelCentre = grid.box.minM + 0.5 * grid.voxelM;
  // The GPU evaluates density; extinction per metre is density x clouds.extinction (the
  // raymarch's sigma_t), so the path tracer reads physical units.
  for (float& d : density) d *= static_cast<float>(c.extinction);
  v.extinction.values = std::move(density);

  VdbMetadata& m = v.metadata;
  m["skylayers_frame"] =
      std::string("camera ENU: x east, y north, z up, metres, the camera at the origin");
  m["skylayers_units"] = std::string(
      "density: extinction per metre (scattering = extinction, no absorption); radiance 1 = "
      "1e4 cd/m2; illuminance 1 = pi x radiance 1 (a white Lambertian surface under "
      "illuminance E has radiance E)");
  m["time"] = time.format();
  m["box_min_m"] = grid.box.minM;
  m["box_max_m"] = grid.box.maxM;
  m["voxel_m"] = grid.voxelM;
  m["extinction_per_density"] = c.extinction;
  const bool byView = grid.params.footprintPerM > 0.0f || grid.params.footprintMinM > 0.0f;
  m["lod"] = std::string(enumName(byView ? CloudVolumeLod::View : CloudVolumeLod::Full));
  m["footprint_per_m"] = double(grid.params.footprintPerM);
  m["footprint_min_m"] = double(grid.params.footprintMinM);
  m["grid_index"] = int64_t(0);
  m["grid_count"] = int64_t(1);
  m["blend_m"] = 0.0;

  const CameraSettings& cam = cloudScene.camera;
  m["camera_latitude_deg"] = cam.latitude;
  m["camera_longitude_deg"] = cam.longitude;
  m["camera_altitude_m"] = cam.altitudeM;
  m["camera_heading_deg"] = cam.heading;
  m["camera_pitch_deg"] = cam.pitch;
  m["camera_roll_deg"] = cam.roll;
  m["camera_vertical_fov_deg"] = cam.verticalFov;
  m["camera_projection"] = std::string(enumName(cam.projection));
  m["camera_width"] = int64_t(view.size.x);
  m["camera_height"] = int64_t(view.size.y);
  // The view's axes exactly as the raymarch builds its rays (engine/render/camera.h): pixel
  // centre uv in [0, 1] looks along normalize(forward + (2u-1) tanH right - (2v-1) tanV up).
  m["camera_forward"] = dvec(view.forward);
  m["camera_right"] = dvec(view.right);
  m["camera_up"] = dvec(view.up);

  // Each light's illuminance where the raymarch takes it: the middle of the layer the box's
  // centre lies in (the low layer unless the centre is above its top), as cloudParams() does.
  const double centreAltitude = cam.altitudeM + 0.5 * (lightBox.minM.z + lightBox.maxM.z);
  const bool inMid = centreAltitude > c.low.topM;
  const double lightAltitude =
      inMid ? 0.5 * (c.mid.baseM + c.mid.topM) : 0.5 * (c.low.baseM + c.low.topM);
  m["light_altitude_m"] = lightAltitude;
  // The layers' shells above sea level, so a reader can tell which rays leave the clouds
  // inside the grid (scripts/pathtrace's field of view to the horizon).
  m["low_base_m"] = c.low.baseM;
  m["low_top_m"] = c.low.topM;
  m["mid_base_m"] = c.mid.baseM;
  m["mid_top_m"] = c.mid.topM;
  const BodyLight* bodies[2] = {&lighting.sun, &lighting.moon};
  const glm::vec4* space[2] = {&lighting.gpu.sunSpace, &lighting.gpu.moonSpace};
  const char* names[2] = {"sun", "moon"};
  for (int i = 0; i < 2; ++i) {
    const glm::vec3 e = light::illuminanceAtAltitude(glm::vec3(*space[i]), bodies[i]->elevationDeg,
                                                     bodies[i]->angularRadiusDeg, lightAltitude,
                                                     cloudScene.lighting.turbidity);
    const std::string n = names[i];
    m[n + "_direction"] = bodies[i]->direction;
    m[n + "_illuminance"] = glm::dvec3(e);
    m[n + "_angular_radius_deg"] = bodies[i]->angularRadiusDeg;
    m[n + "_elevation_deg"] = bodies[i]->elevationDeg;
    m[n + "_azimuth_deg"] = bodies[i]->azimuthDeg;
    // And at each layer's base, middle and top: the raymarch lights a sample with the light at
    // its own altitude (log-quadratic through these three, volumetric_clouds.comp keyLightAt),
    // so a low sun lights a layer's base with less and redder light than its top. A path
    // tracer whose sun lamp has one illuminance sees none of that (render_cycles.py gives its
    // lamp the same profile from these).
    const std::pair<const char*, const CloudLayerSettings*> layers[2] = {{"low", &c.low},
                                                                         {"mid", &c.mid}};
    for (const auto& [layer, l] : layers) {
      const light::LayerIlluminance across = light::illuminanceAcrossLayer(
          glm::vec3(*space[i]), bodies[i]->elevationDeg, bodies[i]->angularRadiusDeg, l->baseM,
          l->topM, cloudScene.lighting.turbidity);
      const std::string key = n + "_illuminance_" + layer + "_";
      m[key + "base"] = glm::dvec3(across.base);
      m[key + "middle"] = glm::dvec3(across.middle);
      m[key + "top"] = glm::dvec3(across.top);
    }
  }
  // The sky light the raymarch's ambient term uses: radiance from the upper hemisphere and
  // from the ground below, the sun's and the moon's palettes together.
  // Which sky the scene draws, so a path tracer that lights the grid with that sky (an
  // equirectangular render of the same scene, scripts/pathtrace) can say which it was.
  m["sky_model"] = std::string(enumName(cloudScene.sky.model));
  m["ambient_top"] = dvec(lighting.gpu.palette.ambientTop + lighting.gpu.moonPalette.ambientTop);
  m["ambient_bottom"] =
      dvec(lighting.gpu.palette.ambientBottom + lighting.gpu.moonPalette.ambientBottom);
  const bool dual = c.phase == CloudPhase::DualLobe;
  m["phase"] = std::string(enumName(c.phase));
  m["phase_g"] = c.g;
  m["phase_g_back"] = dual ? c.gBack : 0.0;
  m["phase_back_weight"] = dual ? c.backWeight : 0.0;
  return v;
}

void nameCloudVolumeParts(std::vector<CloudVolume>& volumes,
                          const std::vector<CloudVolumePart>& parts) {
  for (size_t k = 0; k < volumes.size(); ++k) {
    volumes[k].extinction.name = k == 0 ? "density" : "density_" + std::to_string(k);
    volumes[k].metadata["grid_index"] = int64_t(k);
    volumes[k].metadata["grid_count"] = int64_t(volumes.size());
    volumes[k].metadata["blend_m"] = cloudVolumeBlendM(parts, k);
  }
}

void writeCloudVolume(const std::filesystem::path& path, const CloudVolume& volume) {
  writeVdb(path, volume.extinction, volume.metadata);
}

void writeCloudVolumes(const std::filesystem::path& path, const std::vector<CloudVolume>& volumes) {
  std::vector<VdbGridWithMetadata> grids;
  for (const CloudVolume& v : volumes) grids.push_back({&v.extinction, &v.metadata});
  writeVdb(path, grids);
}

}  // namespace sky
