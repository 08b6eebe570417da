#version 460
// The cloud light volume (passes/cloud_light_volume; docs/clouds.md, "Light volume"): at the
// centre of each texel, the optical depth toward the sun (r) and the moon (g) along the light
// march's whole reach, Lu (24), by the march's own schedule with every step split
// CLOUD_LIGHT_VOLUME_SPLIT ways: the reference's quadrature, once per texel, where the
// raymarch used to march a coarser one at every sample. Each texel's density is filtered to
// its own size, so detail finer than the volume resolves does not alias into it; the
// raymarch marches the nearest steps itself, where that detail shadows the cloud.
#include "common/volumetric_clouds_shared.h"
#include "common/geo.glsl"
#include "common/cloud_density.glsl"
#include "common/cloud_field.glsl"
#include "common/cloud_lighting.glsl"
#include "common/cloud_light_volume.glsl"
#include "common/noise.glsl"
#include "common/cloud_shells.glsl"

layout(local_size_x = CLOUD_LIGHT_VOLUME_GROUP_X, local_size_y = CLOUD_LIGHT_VOLUME_GROUP_Y,
       local_size_z = CLOUD_LIGHT_VOLUME_GROUP_Z) in;
layout(binding = CLOUD_LIGHT_VOLUME_BINDING_IMAGE, rg16f) uniform writeonly image3D lightVolume;

#include "common/cloud_light_march.glsl"

// Every sample reads all the noise, filtered to the texel's size or a quarter of its step;
// the far step's, the clouds' mean (as the raymarch's).
float cloudDensityForLight(CloudLightPath path, vec3 p, float lengthM, int part) {
  CloudSample s;
  cloudSampleAtLla(p, latLonAltitudeOn(params.geo, path.line, p),
                   max(path.footprintM, 0.25 * lengthM), false,
                   part == CLOUD_LIGHT_PART_MEAN ? CLOUD_NOISE_NONE : CLOUD_NOISE_ALL, s);
  return s.density;
}

void main() {
  ivec3 id = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(id, ivec3(CLOUD_LIGHT_VOLUME_SIZE, CLOUD_LIGHT_VOLUME_SIZE,
                                     CLOUD_LIGHT_VOLUME_SLICES))))
    return;
  CloudLightVolume v = params.lightVolume;
  vec2 u = (vec2(id.xy) + 0.5) / float(CLOUD_LIGHT_VOLUME_SIZE) * 2.0 - 1.0;
  vec2 metres = v.radiusM * u * abs(u);
  float slice = (v.topM - v.baseM) / float(CLOUD_LIGHT_VOLUME_SLICES);
  float h = v.baseM + (float(id.z) + 0.5) * slice;
  vec3 p = cloudLightVolumePoint(params.geo, metres, h);
  // The texel's size: ground distance r u |u| puts 4 sqrt(r d) / N metres between texel
  // centres d metres out (at least a texel's worth at the centre).
  vec2 spacing = 4.0 * sqrt(v.radiusM * max(abs(metres), vec2(v.radiusM) /
                                        float(CLOUD_LIGHT_VOLUME_SIZE * CLOUD_LIGHT_VOLUME_SIZE))) /
                 float(CLOUD_LIGHT_VOLUME_SIZE);
  float footprintM = 0.5 * max(max(spacing.x, spacing.y), slice);
  // Each texel places its samples differently inside their steps: no contour lines.
  float offset = noiseHashUnit3(uvec3(id.xy, uint(id.z) + 0x6c766f6cu)).x;
  vec2 tau = vec2(0.0);
  vec2 latLon = latLonAltitude(params.geo, p).xy;
  float distance = params.lightDistanceM;
  int steps = int(params.lightSteps);
  for (int i = 0; i < 2; ++i) {
    if ((i == 0 ? params.sunMarched : params.moonMarched) == 0.0) continue;
    vec3 L = i == 0 ? params.sunDirection.xyz : params.moonDirection.xyz;
    // Every short step split CLOUD_LIGHT_VOLUME_SPLIT ways, the long step in the view march's
    // parts over the clouds it resolves (longer parts miss the small clouds and brighten a low
    // sun's light), then the far step to where the path leaves the shells.
    float longEnd = CLOUD_LIGHT_RESOLVED_REACH * distance;
    float exitM = cloudShellExit(params.geo.origin.w, h, dot(L, geoUp(params.geo, p)),
                                 params.shellBaseM, params.shellTopM);
    float farEnd = clamp(exitM, longEnd, max(CLOUD_LIGHT_FAR_REACH_M, longEnd));
    CloudLightPath path = CloudLightPath(
        p, L, latLonLine(params.geo, p, latLon, L, lightLongStepDistance(distance)), footprintM,
        offset, distance, steps, CLOUD_LIGHT_VOLUME_SPLIT, steps, longEnd,
        cloudLightLongParts(distance, longEnd, CLOUD_LIGHT_LONG_PART_M), farEnd,
        cloudLightFarParts(longEnd, farEnd));
    tau[i] = params.extinction * lightMarchDensity(path);
  }
  imageStore(lightVolume, id, vec4(tau, 0.0, 0.0));
}
