#version 460
// The upper layer: the clear sky (Kozlov 3.1 from the palette, or the physical sky-view LUTs
// with SKY_PHYSICAL_SKY) and the high-cloud layer, a coefficient texture and normal map on a
// sphere at the layer's altitude, shaded by Kozlov 3.2-3.4 for the sun and the moon.
// Writes the sky alone and the clouds premultiplied (rgb radiance, a coverage = 1 - clear).
// With SKY_HIGH_CLOUDS_REGIONAL the cover comes per pixel from the weather map's high layer
// where the ray meets the layer, applied to the baked rank/shape texture.
// SKY_HIGH_CLOUDS_LAYER 0 (no high clouds in the scene) and LIGHTING_MOON 0 (by day) compile
// out what the frame does not show: a software rasteriser runs both sides of a branch.
#include "common/params_block.glsl"
#include "common/sky_high_clouds_shared.h"
#include "common/view.glsl"
#define LIGHTING_BINDING SKY_HIGH_CLOUDS_BINDING_LIGHTING
#include "common/lighting.glsl"
#include "common/kozlov_clouds.glsl"
#if SKY_PHYSICAL_SKY
#include "common/atmosphere.glsl"
#endif
#if SKY_HIGH_CLOUDS_REGIONAL
#include "common/geo.glsl"
#include "common/high_cloud_coverage.glsl"
#endif

layout(local_size_x = SKY_HIGH_CLOUDS_GROUP_X, local_size_y = SKY_HIGH_CLOUDS_GROUP_Y) in;

layout(std140, binding = SKY_HIGH_CLOUDS_BINDING_PARAMS) uniform Params {
  SkyHighCloudsParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
layout(binding = SKY_HIGH_CLOUDS_BINDING_SKY, rgba32f) uniform writeonly image2D skyImage;
layout(binding = SKY_HIGH_CLOUDS_BINDING_CLOUDS, rgba32f) uniform writeonly image2D cloudImage;
layout(binding = SKY_HIGH_CLOUDS_BINDING_NORMALS) uniform sampler2D normalTexture;
#if SKY_HIGH_CLOUDS_REGIONAL
// The weather map's high cover over its region (linear, clamp to edge).
layout(binding = SKY_HIGH_CLOUDS_BINDING_REGIONAL_COVER) uniform sampler2D regionalCover;
// Per texel rank (r) and optical depth factor (g); and the coarse coefficients per cover.
layout(binding = SKY_HIGH_CLOUDS_BINDING_RANK_SHAPE) uniform sampler2D rankShapeTexture;
layout(binding = SKY_HIGH_CLOUDS_BINDING_COVER_COARSE) uniform sampler3D coverCoarseTexture;
#else
layout(binding = SKY_HIGH_CLOUDS_BINDING_COEFFICIENTS) uniform sampler2D coefficientTexture;
// The mip levels between the texture and the coarse one (common/high_cloud_levels.glsl).
layout(binding = SKY_HIGH_CLOUDS_BINDING_LEVELS) uniform sampler2D levelsTexture;
layout(binding = SKY_HIGH_CLOUDS_BINDING_COARSE) uniform sampler2D coarseTexture;
#include "common/high_cloud_levels.glsl"
#endif
#if SKY_PHYSICAL_SKY
layout(std140, binding = SKY_HIGH_CLOUDS_BINDING_ATMOSPHERE) uniform AtmosphereBlock {
  AtmosphereParams atmosphereBlock[1];
};
#define atmosphere atmosphereBlock[SKY_PARAMS_INDEX]
layout(binding = SKY_HIGH_CLOUDS_BINDING_TRANSMITTANCE) uniform sampler2D transmittanceLut;
layout(binding = SKY_HIGH_CLOUDS_BINDING_SKY_VIEW_SUN) uniform sampler2D skyViewSunLut;
#if LIGHTING_MOON
layout(binding = SKY_HIGH_CLOUDS_BINDING_SKY_VIEW_MOON) uniform sampler2D skyViewMoonLut;
#endif
#endif

#include "common/clear_sky.glsl"

// Distance along V from the camera (at height cameraR above the centre, on the z axis) to the
// sphere of radius `radius`, the nearest hit ahead, or -1 if none.
float sphereHit(float cameraR, vec3 V, float radius) {
  float b = cameraR * V.z;
  float c = cameraR * cameraR - radius * radius;
  float disc = b * b - c;
  if (disc < 0.0) return -1.0;
  float s = sqrt(disc);
  // Camera inside the sphere: the far root; outside: the near root if it is ahead.
  if (c < 0.0) return -b + s;
  float t = -b - s;
  return t > 0.0 ? t : -1.0;
}

// The light's illuminance arriving at the layer point `up` (unit, from the planet's centre).
vec3 lightAtLayer(vec3 up, vec3 S, vec3 kozlovValue, vec3 above) {
#if SKY_PHYSICAL_SKY
  // Per pixel through the transmittance LUT (zero where the planet hides the light); the
  // atmosphere works in km.
  return above * transmittanceToTop(atmosphere, transmittanceLut, params.layer.z * 1e-3, dot(up, S));
#else
  return kozlovValue;  // computed on the CPU for the layer's altitude
#endif
}

#if SKY_HIGH_CLOUDS_REGIONAL
// The forecast's high cover at the layer point `enu` (camera ENU frame, metres): bilinear
// between the map's texel centres, clamped at its edges, and 0 outside its region.
float regionalCoverAt(vec3 enu) {
  vec3 lla = latLonAltitude(params.geo, enu);
  vec2 ruv;
  if (!regionUv(params.region, lla.x, lla.y, ruv)) return 0.0;
  return clamp(textureLod(regionalCover, ruv, 0.0).r, 0.0, 1.0);
}

// The mean coefficients at cover c, linear between the table's covers k / (STEPS - 1).
vec4 farFieldAt(float c) {
  float x = c * float(HIGH_CLOUD_COVER_STEPS - 1u);
  int i = min(int(x), int(HIGH_CLOUD_COVER_STEPS) - 2);
  return mix(params.farField[i], params.farField[i + 1], x - float(i));
}
#endif

#if !SKY_HIGH_CLOUDS_REGIONAL
// Mip level `level` of the coefficients at uv: the texture itself (0), the coarse texture
// (coarseLevel) or one of the levels in between.
vec4 coefficientLevel(vec2 uv, int level, int coarseLevel) {
  if (level == 0) return textureLod(coefficientTexture, uv, 0.0);
  if (level >= coarseLevel) return textureLod(coarseTexture, uv, 0.0);
  return highCloudLevelSample(levelsTexture, uint(params.texture.w), level, uv);
}

// The coefficients filtered over a footprint of 2^lod texels: trilinear between the two mip
// levels around it, so fine fibres average out where a pixel covers several of them instead of
// aliasing into moire and false combs.
vec4 trilinearCoefficients(vec2 uv, float lod) {
  int coarseLevel = highCloudCoarseLevel(uint(params.texture.w), uint(params.shading.z));
  lod = clamp(lod, 0.0, float(coarseLevel));
  int lower = min(int(lod), coarseLevel - 1);
  return mix(coefficientLevel(uv, lower, coarseLevel), coefficientLevel(uv, lower + 1, coarseLevel),
             lod - float(lower));
}

// The maximum number of trilinear taps along a footprint's long axis.
#define SKY_HIGH_CLOUDS_MAX_TAPS 4

// The coefficients over a pixel's footprint on the layer, `along` texels long in the uv
// direction `axis` (unit) and `across` texels wide: up to 4 trilinear taps spread along the
// long axis, each at the level of the footprint's length over the number of taps. One tap at
// the long axis's level would blur the clouds toward the horizon by up to 4 times across the
// view; the taps keep them as sharp as the footprint allows (anisotropic filtering by hand).
vec4 filteredCoefficients(vec2 uv, vec2 axis, float along, float across) {
  float taps = clamp(ceil(along / max(across, 1e-6)), 1.0, float(SKY_HIGH_CLOUDS_MAX_TAPS));
  float lod = log2(max(along / taps, 1e-6));
  vec2 step = axis * (along / taps) / params.texture.w;  // uv between taps
  vec4 sum = vec4(0.0);
  for (int i = 0; i < SKY_HIGH_CLOUDS_MAX_TAPS; ++i) {
    if (float(i) >= taps) break;
    sum += trilinearCoefficients(uv + (float(i) - 0.5 * (taps - 1.0)) * step, lod);
  }
  return sum / taps;
}
#endif

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(p, params.view.size.xy))) return;
  vec3 V = viewDirection(params.view, vec2(p) + 0.5);
  LightingState L = lighting;
  vec3 sky = frameSkyRadiance(L, V);
  imageStore(skyImage, ivec2(p), vec4(sky, 1.0));

  vec4 clouds = vec4(0.0);
#if SKY_HIGH_CLOUDS_LAYER
  float planetR = params.layer.x, cameraR = params.layer.y, layerR = params.layer.z;
  float t = params.layer.w > 0.0 ? sphereHit(cameraR, V, layerR) : -1.0;
  // The ground hides the layer behind it (looking down from below the layer).
  float ground = sphereHit(cameraR, V, planetR);
  bool onLayer = t > 0.0 && (ground < 0.0 || ground > t);
#if SKY_HIGH_CLOUDS_REGIONAL
  // The point is t V in the camera's ENU frame; no cloud where the forecast has none.
  float cover = onLayer ? regionalCoverAt(t * V) : 0.0;
  onLayer = onLayer && cover > 0.0;
#endif
  if (onLayer) {
    vec3 hit = vec3(0.0, 0.0, cameraR) + t * V;  // from the planet's centre
    vec3 up = normalize(hit);
    // The layer's tangent frame: east and north at the hit point, turned to the texture's axes:
    // tileU is +u on the ground (east for images, downwind for procedural textures), the
    // normal map's y axis (image up, -v) 90 degrees counter-clockwise from it.
    vec3 east = normalize(vec3(1.0, 0.0, 0.0) - up * up.x);
    vec3 north = cross(up, east);
    vec2 tileU = vec2(params.tileUEast, params.tileUNorth);
    vec2 tileV = vec2(tileU.y, -tileU.x);  // +v on the ground: +u turned clockwise
    vec3 uAxis = tileU.x * east + tileU.y * north;
    vec3 yAxis = cross(up, uAxis);

    // Texture coordinates: ground distance east/north of the camera plus the wind's drift,
    // along the texture's axes, in tiles. A straight line of the texture is a straight line on
    // the ground, so streaks parallel on the tile converge toward one point of the horizon.
    vec2 metres = hit.xy * (layerR / length(hit)) + params.texture.xy;
    vec2 uv = vec2(dot(metres, tileU), dot(metres, tileV)) / params.texture.z;

    // Texture footprint of this pixel: a pixel angle at distance t, stretched by the grazing
    // angle (the footprint's long axis, so nothing aliases along it). Past one texel the
    // detail is sub-pixel: the coefficients come from the mip level of the footprint, and
    // past the coarse level they blend over 4 more octaves to the texture's mean, so the
    // horizon does not shimmer. The normals flatten over the first 4 octaves.
    float grazing = max(abs(dot(V, up)), 0.02);
    float footprintM = viewPixelAngle(params.view, V) * t / grazing;
    float texels = footprintM * params.texture.w / params.texture.z;
    float acrossTexels = texels * grazing;  // across the view the footprint is not stretched
    float lod = log2(max(texels, 1e-6));
    float toCoarse = clamp(lod / 4.0, 0.0, 1.0);
    float coarseTexels = texels * params.shading.z / params.texture.w;
    float toMean = clamp(log2(max(coarseTexels, 1e-6)) / 4.0, 0.0, 1.0);
#if SKY_HIGH_CLOUDS_REGIONAL
    // The same three levels at the local cover: each texel's optical depth from its rank and
    // shape; the coarse level between the per-cover layers bracketing c (trilinear: layer k
    // sits at w = (k + 0.5) / STEPS); the far field from the table.
    vec4 fine = highCloudCoefficients(texture(rankShapeTexture, uv).rg, cover, params.regional.y);
    float layerW = (cover * float(HIGH_CLOUD_COVER_STEPS - 1u) + 0.5) / float(HIGH_CLOUD_COVER_STEPS);
    vec4 coarse = texture(coverCoarseTexture, vec3(uv, layerW));
    vec4 c = mix(mix(fine, coarse, toCoarse), farFieldAt(cover), toMean);
#else
    // The long axis: the view direction along the layer, in uv.
    vec3 level = V - up * dot(V, up);
    vec2 axis = vec2(dot(level, uAxis), -dot(level, yAxis));
    axis = dot(axis, axis) > 1e-12 ? normalize(axis) : vec2(1.0, 0.0);
    vec4 c = mix(filteredCoefficients(uv, axis, texels, acrossTexels), params.meanCoefficients,
                 toMean);
#endif
    c = clamp(c, 0.0, 1.0);
    vec3 n = normalize(mix(texture(normalTexture, uv).xyz, vec3(0.0, 0.0, 1.0), toCoarse));

    vec3 rgb = vec3(0.0);
    float edgeWidth = params.shading.y;
    {
      vec3 S = L.sun.direction.xyz;
      vec3 St = vec3(dot(S, uAxis), dot(S, yAxis), dot(S, up));
      vec3 E = lightAtLayer(up, S, params.sunAtLayer.rgb, L.sunSpace.rgb);
      rgb += kozlovCloudTerms(c, n, St, dot(V, S), E, L.palette, edgeWidth);
    }
#if LIGHTING_MOON
    {
      vec3 M = L.moon.direction.xyz;
      vec3 Mt = vec3(dot(M, uAxis), dot(M, yAxis), dot(M, up));
      vec3 E = lightAtLayer(up, M, params.moonAtLayer.rgb, L.moonSpace.rgb);
      rgb += kozlovCloudTerms(c, n, Mt, dot(V, M), E, L.moonPalette, edgeWidth);
    }
#endif
    rgb *= params.shading.x;
    float coverage = 1.0 - c.b;  // the clear-sky channel is the layer's transmittance

    // Air between the camera and the layer: the clouds fade into the sky toward the horizon.
#if SKY_PHYSICAL_SKY
    vec3 through = transmittanceAlong(atmosphere, transmittanceLut, V, t * 1e-3);
#else
    // Kozlov 3.1's haze h (kozlovHaze) is how much of the sky colour is not fog. Seen from
    // above the layer (an aircraft) the path to it runs downward, so z is measured down.
    float z = cameraR > layerR ? -V.z : V.z;
    vec3 through = vec3(kozlovHaze(z, L.palette.fog.w));
#endif
    clouds = vec4(rgb * through + coverage * (1.0 - through) * sky, coverage);
  }
#endif
  imageStore(cloudImage, ivec2(p), clouds);
}
