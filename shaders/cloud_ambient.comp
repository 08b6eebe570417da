#version 460
// The volumetric clouds' ambient light from the sky that is actually there (passes/
// cloud_ambient): the frame's clear sky (either model, clear_sky.glsl) sampled over the upper
// hemisphere, its light on a surface of each normal of a table (cloud_ambient_shared.h), and
// the ground below lit by the sun, the moon and that sky. Before, the clouds took the palette's
// two constant colours, which left backlit cores lit almost only by the warm sun diffusing
// through them (tan, where the blue sky behind the camera makes real ones blue-grey). The
// raymarch looks the table up once per ray.
#include "common/params_block.glsl"
#include "common/cloud_ambient_shared.h"
#define LIGHTING_BINDING CLOUD_AMBIENT_BINDING_LIGHTING
#include "common/lighting.glsl"
#if SKY_PHYSICAL_SKY
#include "common/atmosphere.glsl"
#endif

layout(local_size_x = CLOUD_AMBIENT_GROUP) in;

layout(std140, binding = CLOUD_AMBIENT_BINDING_PARAMS) uniform CloudAmbientBlock {
  CloudAmbientParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
layout(binding = CLOUD_AMBIENT_BINDING_OUT, rgba32f) uniform writeonly image2D ambientImage;
#if SKY_PHYSICAL_SKY
layout(std140, binding = CLOUD_AMBIENT_BINDING_ATMOSPHERE) uniform AtmosphereBlock {
  AtmosphereParams atmosphereBlock[1];
};
#define atmosphere atmosphereBlock[SKY_PARAMS_INDEX]
layout(binding = CLOUD_AMBIENT_BINDING_TRANSMITTANCE) uniform sampler2D transmittanceLut;
layout(binding = CLOUD_AMBIENT_BINDING_SKY_VIEW_SUN) uniform sampler2D skyViewSunLut;
#if LIGHTING_MOON
layout(binding = CLOUD_AMBIENT_BINDING_SKY_VIEW_MOON) uniform sampler2D skyViewMoonLut;
#endif
#endif
#include "common/clear_sky.glsl"
#include "common/cloud_lighting.glsl"

#define AMBIENT_PI 3.14159265358979
#define AMBIENT_DIRECTIONS (CLOUD_AMBIENT_RINGS * CLOUD_AMBIENT_AZIMUTHS)
#define AMBIENT_NORMALS (CLOUD_AMBIENT_MAP_WIDTH * CLOUD_AMBIENT_MAP_HEIGHT)

// The sampled sky: direction j of a grid of rings equal in solid angle (uniform in the cosine
// of the zenith angle) by azimuths, and its radiance (16 KB of shared memory: Vulkan's least).
shared vec3 skyRadiance[AMBIENT_DIRECTIONS];
shared vec3 groundShared;  // groundRadiance, once for the workgroup
shared vec3 meanShared;    // the upper hemisphere's mean radiance (skyHidden)

float ringCosZenith(int ring) {
  return (float(ring) + 0.5) / float(CLOUD_AMBIENT_RINGS);
}
float columnAzimuth(int column) {
  return 2.0 * AMBIENT_PI * (float(column) + 0.5) / float(CLOUD_AMBIENT_AZIMUTHS);
}
vec3 gridDirection(int ring, int column) {
  float cz = ringCosZenith(ring), phi = columnAzimuth(column);
  float s = sqrt(max(1.0 - cz * cz, 0.0));
  return vec3(s * cos(phi), s * sin(phi), cz);
}

// The unit normal of table texel (i, j) (cloud_ambient_shared.h).
vec3 tableNormal(int i, int j) {
  float elevation = AMBIENT_PI * (float(j) / float(CLOUD_AMBIENT_MAP_HEIGHT - 1) - 0.5);
  float azimuth = 2.0 * AMBIENT_PI * float(i) / float(CLOUD_AMBIENT_MAP_WIDTH);
  return vec3(cos(elevation) * cos(azimuth), cos(elevation) * sin(azimuth), sin(elevation));
}

// The sky's light on a surface of normal n: the irradiance of the sampled radiances over pi,
// each direction standing for 2 pi / N sr.
vec3 skyLightOn(vec3 n) {
  vec3 sum = vec3(0.0);
  for (int ring = 0; ring < CLOUD_AMBIENT_RINGS; ++ring) {
    float cz = ringCosZenith(ring), s = sqrt(max(1.0 - cz * cz, 0.0));
    for (int column = 0; column < CLOUD_AMBIENT_AZIMUTHS; ++column) {
      float phi = columnAzimuth(column);
      vec3 w = vec3(s * cos(phi), s * sin(phi), cz);
      sum += skyRadiance[ring * CLOUD_AMBIENT_AZIMUTHS + column] * max(dot(w, n), 0.0);
    }
  }
  return sum * (2.0 / float(AMBIENT_DIRECTIONS));
}

// The ground's own radiance: Lambertian under the sun and the moon (their illuminance at the
// ground on a surface facing them, times the sine of their elevation) and the sky (its light
// on a level surface), with the share the cloud cover lets through.
vec3 groundRadiance(LightingState L) {
  vec3 sunlit = L.sun.illuminance.rgb * max(L.sun.direction.z, 0.0);
#if LIGHTING_MOON
  sunlit += L.moon.illuminance.rgb * max(L.moon.direction.z, 0.0);
#endif
  return params.groundAlbedo.rgb * (sunlit + skyLightOn(vec3(0.0, 0.0, 1.0))) * params.groundLight;
}

// Below the horizon the clouds see the ground through the air between them (Koschmieder, as
// the composite draws it): the ground's radiance, taking on the colour of the sky at the
// horizon in the same azimuth (the lowest ring) by 1 - T, T = exp(-airDepth / sin(depression))
// along the slant path. Straight down that is a tenth of the light; toward the horizon it is
// the bright haze, which lights a cloud's sides and base. The grid is the upper one mirrored:
// direction (ring, column) below has the depression of `ring` and the azimuth of `column`.
// airTransmittance(ring) is T for the ring: one exp a ring, not one a direction.
vec3 airTransmittance(int ring) {
  return exp(-params.airDepth.rgb / ringCosZenith(ring));
}
vec3 belowRadiance(vec3 T, vec3 ground, int column) {
  return mix(skyRadiance[column], ground, T);
}
vec3 belowDirection(int ring, int column) {
  vec3 s = gridDirection(ring, column);
  return vec3(s.xy, -s.z);
}

// The sky's and the ground's light on a surface of normal n (cloud_ambient_shared.h).
// The sky of `ring` as a cloud among others sees it: its own radiance r where no other cloud
// hides it, the sky's mean where one does (CLOUD_AMBIENT_OCCLUSION_PER_COVER).
vec3 skyHidden(vec3 r, int ring) {
  return mix(meanShared, r, exp(-params.skyOcclusion / ringCosZenith(ring)));
}
vec3 lightOn(vec3 n, vec3 ground) {
  vec3 above = vec3(0.0), below = vec3(0.0);
  for (int ring = 0; ring < CLOUD_AMBIENT_RINGS; ++ring) {
    vec3 T = airTransmittance(ring);
    for (int column = 0; column < CLOUD_AMBIENT_AZIMUTHS; ++column) {
      above += skyHidden(skyRadiance[ring * CLOUD_AMBIENT_AZIMUTHS + column], ring) *
               max(dot(gridDirection(ring, column), n), 0.0);
      below += belowRadiance(T, ground, column) * max(dot(belowDirection(ring, column), n), 0.0);
    }
  }
  return (above + below) * (2.0 / float(AMBIENT_DIRECTIONS));
}

// The sky and the ground through the air scattered once toward the eye by a ray along d, less
// their mean radiance (what an isotropic phase scatters): P(d) - Lmean
// (cloud_ambient_shared.h).
vec3 phaseExcess(vec3 d, vec3 ground) {
  vec3 sum = vec3(0.0), total = vec3(0.0);
  for (int ring = 0; ring < CLOUD_AMBIENT_RINGS; ++ring) {
    vec3 T = airTransmittance(ring);
    for (int column = 0; column < CLOUD_AMBIENT_AZIMUTHS; ++column) {
      vec3 up = skyRadiance[ring * CLOUD_AMBIENT_AZIMUTHS + column];
      vec3 down = belowRadiance(T, ground, column);
      // Light seen in direction s travels along -s; toward the eye along -d: cos = s . d.
      sum += up * dualLobeHG(dot(gridDirection(ring, column), d), params.phaseG,
                             params.phaseGBack, params.phaseBackWeight) +
             down * dualLobeHG(dot(belowDirection(ring, column), d), params.phaseG,
                               params.phaseGBack, params.phaseBackWeight);
      total += up + down;
    }
  }
  float dw = 2.0 * AMBIENT_PI / float(AMBIENT_DIRECTIONS);  // each direction's solid angle
  return sum * dw - total * dw / (4.0 * AMBIENT_PI);
}

void main() {
  int i = int(gl_LocalInvocationID.x);
  LightingState L = lighting;
  for (int k = 0; k < CLOUD_AMBIENT_DIRECTIONS_PER_INVOCATION; ++k) {
    int j = i * CLOUD_AMBIENT_DIRECTIONS_PER_INVOCATION + k;
    skyRadiance[j] = frameSkyRadiance(L, gridDirection(j / CLOUD_AMBIENT_AZIMUTHS,
                                                        j % CLOUD_AMBIENT_AZIMUTHS));
  }
  barrier();
  if (i == 0) {
    groundShared = groundRadiance(L);
    vec3 sum = vec3(0.0);
    for (int j = 0; j < AMBIENT_DIRECTIONS; ++j) sum += skyRadiance[j];
    meanShared = sum / float(AMBIENT_DIRECTIONS);
  }
  barrier();
  if (i < AMBIENT_NORMALS) {
    int column = i % CLOUD_AMBIENT_MAP_WIDTH, row = i / CLOUD_AMBIENT_MAP_WIDTH;
    vec3 n = tableNormal(column, row);
    vec3 ground = groundShared;
    imageStore(ambientImage, ivec2(column, row), vec4(lightOn(n, ground), 0.0));
    imageStore(ambientImage, ivec2(column, CLOUD_AMBIENT_PHASE_ROW + row),
               vec4(phaseExcess(n, ground), 0.0));
  }
  // The ground's row: the ground's own radiance in its first texel (for the debug image; the
  // table above already holds its light through the air), the rest zero.
  if (i < CLOUD_AMBIENT_MAP_WIDTH)
    imageStore(ambientImage, ivec2(i, CLOUD_AMBIENT_GROUND_ROW),
               vec4(i == 0 ? groundShared : vec3(0.0), 0.0));
}
