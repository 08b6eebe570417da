#version 460
// The cloud shadow map: for each texel, a point on the ground (sea level) and the
// transmittance of the volumetric clouds along a straight ray from it toward the key light,
// exp(-sum sigma_t ds) over CLOUD_SHADOW_STEPS samples of the raymarch's own density field
// (cloud_field.glsl) between the bottom and the top of the cloud shells. Beer-Lambert without
// Lu's clamp: this is the direct beam the ground receives; the light a cloud scatters down is
// the ground's ambient term (atmosphere_composite.comp).
#include "common/volumetric_clouds_shared.h"
#include "common/cloud_shadow_shared.h"
#include "common/geo.glsl"
#include "common/cloud_density.glsl"
#include "common/cloud_field.glsl"
#include "common/cloud_shadow.glsl"
#include "common/cloud_shells.glsl"
#include "common/noise.glsl"

layout(local_size_x = CLOUD_SHADOW_GROUP_X, local_size_y = CLOUD_SHADOW_GROUP_Y) in;

layout(std140, binding = CLOUD_SHADOW_BINDING_MAP_PARAMS) uniform CloudShadowBlock {
  CloudShadowMap shadowBlock[1];
};
#define shadowMap shadowBlock[SKY_PARAMS_INDEX]
layout(binding = CLOUD_SHADOW_BINDING_IMAGE, r16f) uniform writeonly image2D shadowImage;

void main() {
  uvec2 id = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(id, uvec2(CLOUD_SHADOW_SIZE)))) return;
  CloudShadowMap map = shadowMap;
  vec2 u = (vec2(id) + 0.5) / float(CLOUD_SHADOW_SIZE) * 2.0 - 1.0;
  vec2 metres = cloudShadowGround(map, u);
  float distance = length(metres);
  vec2 heading = distance > 0.0 ? metres / distance : vec2(0.0, 1.0);
  // The ground point in the camera's ENU frame, its drop below the camera's horizon plane as
  // 2 R sin^2(angle / 2), which keeps its precision near the camera (cloud_density_slice.comp).
  float R = params.geo.origin.w, cameraAltitude = params.geo.origin.z;
  float angle = distance / R;
  float sh = sin(0.5 * angle);
  vec3 p = vec3(R * sin(angle) * heading, -cameraAltitude - 2.0 * R * sh * sh);
  vec3 L = map.lightDirection.xyz;
  // The ray leaves the ground, enters the shells' bottom and leaves their top.
  float mu = dot(L, geoUp(params.geo, p));
  vec2 r;
  float t0 = cloudSphereRoots(R, 0.0, mu, params.shellBaseM, r) ? max(r.y, 0.0) : 0.0;
  float t1 = cloudSphereRoots(R, 0.0, mu, params.shellTopM, r) ? max(r.y, 0.0) : 0.0;
  t1 = min(t1, t0 + map.maxPathM);
  float dt = max(t1 - t0, 0.0) / float(CLOUD_SHADOW_STEPS);
  // A footprint of a quarter step: noise finer than the step averages out. Not the texel's
  // size: past the shape's outline the field holds its mean density, and Beer-Lambert of a
  // mean is a uniform dusk where the gaps between real clouds let the sun through. A texel
  // wider than a cloud takes the shadow at its centre instead (the distant ground it falls on
  // lies deep in the haze).
  float footprint = clamp(0.25 * dt, 10.0, 100.0);
  // Sample offsets jittered per texel (noise.glsl's hash), so the steps leave no contour lines;
  // the map is read bilinearly.
  float jitter = noiseHashUnit3(uvec3(id, 0x73686477u)).x;
  float tau = 0.0;
  for (int i = 0; i < CLOUD_SHADOW_STEPS && tau < 12.0; ++i) {
    CloudSample s;
    // The shape noise only: the detail's erosion is finer than the map's texels, and leaving
    // it out halves the cost (its mean stands in).
    vec3 x = p + (t0 + (float(i) + jitter) * dt) * L;
    cloudSampleAtLla(x, latLonAltitude(params.geo, x), footprint, true, CLOUD_NOISE_SHAPE, s);
    tau += params.extinction * s.density * dt;
  }
  imageStore(shadowImage, ivec2(id), vec4(exp(-tau), 0.0, 0.0, 0.0));
}
