#version 460
// The final image in scene-linear Rec.709: the clear sky and the high clouds (from
// passes/sky_high_clouds), the star field and the sun and moon discs behind the clouds, and
// the volumetric low and mid clouds (passes/volumetric_clouds) in front of them — or behind
// the high clouds when the camera flies above those. Aerial perspective joins here later.
#include "common/params_block.glsl"
#include "common/atmosphere_composite_shared.h"
#include "common/view.glsl"
#define LIGHTING_BINDING ATMOSPHERE_COMPOSITE_BINDING_LIGHTING
#include "common/lighting.glsl"
#define STAR_FLUX_BINDING ATMOSPHERE_COMPOSITE_BINDING_STARS
#include "common/star_field.glsl"

layout(local_size_x = ATMOSPHERE_COMPOSITE_GROUP_X, local_size_y = ATMOSPHERE_COMPOSITE_GROUP_Y) in;

layout(std140, binding = ATMOSPHERE_COMPOSITE_BINDING_PARAMS) uniform Params {
  AtmosphereCompositeParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_BEAUTY, rgba16f) uniform writeonly image2D beautyImage;
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_SKY, rgba16f) uniform readonly image2D skyImage;
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_HIGH_CLOUDS, rgba16f) uniform readonly image2D
    highCloudImage;
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_CLOUDS, rgba16f) uniform readonly image2D cloudImage;

// Fraction of a pixel of angular size `pixel` covered by a disc of angular radius `radius`
// whose centre is `distance` away (a box-filtered edge). A disc smaller than a pixel is
// spread over one pixel's width with its radiance scaled by the area ratio, so its energy
// stays within ~8 % of pi r^2 L instead of flickering in and out at test sizes like 64x36.
float discCoverage(float distance, float radius, float pixel) {
  float spread = max(radius, pixel);
  float inside = clamp((spread - distance) / pixel + 0.5, 0.0, 1.0);
  return inside * (radius * radius) / (spread * spread);
}

// Radiance of the moon's surface seen in direction V (inside the disc, |offset| < 1 in units
// of the disc radius). Lommel-Seeliger shading with the sun at the phase angle toward the
// bright limb; the earthlit part everywhere (it only shows where sunlight does not).
vec3 moonSurface(LightingState L, vec3 V) {
  vec3 d = L.moon.direction.xyz;
  vec3 limb = L.moonLimb.xyz;
  vec3 across = cross(d, limb);
  float sinR = sin(L.moon.direction.w);
  vec2 q = vec2(dot(V, limb), dot(V, across)) / sinR;
  float r2 = min(dot(q, q), 1.0);
  vec3 n = vec3(q, sqrt(1.0 - r2));  // surface normal in (limb, across, toward us)
  float phase = L.moonLimb.w;
  vec3 s = vec3(sin(phase), 0.0, cos(phase));  // the sun, seen from the moon
  float mu0 = max(dot(n, s), 0.0);
  float shade = mu0 / max(mu0 + n.z, 1e-6);
  return L.moonDisc.rgb * shade + L.moonEarthshine.rgb;
}

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(p, params.view.size.xy))) return;
  vec2 pixelCentre = vec2(p) + 0.5;
  vec3 V = viewDirection(params.view, pixelCentre);
  LightingState L = lighting;

  vec3 sky = imageLoad(skyImage, ivec2(p)).rgb;
  vec4 highClouds = imageLoad(highCloudImage, ivec2(p));  // premultiplied, a = coverage

  float pixelAngle = viewPixelAngle(params.view, V);
  // The ground hides what lies below the horizon, pixel by pixel.
  float aboveHorizon = clamp(V.z / pixelAngle + 0.5, 0.0, 1.0);

  // A disc spread over a pixel wider than itself (see discCoverage) would leak past the
  // horizon; there the share of the disc above the horizon (illuminance.w) hides it instead.
  // Resolved discs are cut pixel by pixel. The two blend as the disc grows past a pixel.
  vec3 S = L.sun.direction.xyz;
  float sunR = L.sun.direction.w;
  float sunCover = discCoverage(acos(clamp(dot(V, S), -1.0, 1.0)), sunR, pixelAngle);
  float sunResolved = smoothstep(1.0, 2.0, sunR / pixelAngle);
  vec3 sunDisc = L.sunDisc.rgb * sunCover * aboveHorizon * mix(L.sun.illuminance.w, 1.0, sunResolved);

  // The moon: resolved discs are shaded per pixel with an anti-aliased edge; discs near or
  // below a pixel in size carry their mean radiance with the sun's coverage rule, so the
  // drawn flux stays right at every resolution. The two blend, so zooming does not pop.
  vec3 M = L.moon.direction.xyz;
  float moonR = L.moon.direction.w;
  float moonDist = acos(clamp(dot(V, M), -1.0, 1.0));
  float moonCover = discCoverage(moonDist, moonR, pixelAngle);
  vec3 moonMean = L.moonDisc.rgb * L.moonEarthshine.w + L.moonEarthshine.rgb;
  vec3 moonResolved = moonDist < moonR + pixelAngle ? moonSurface(L, V) : vec3(0.0);
  float resolved = smoothstep(1.0, 2.0, moonR / pixelAngle);
  vec3 moonDisc = mix(moonMean, moonResolved, resolved) * moonCover * aboveHorizon *
                  mix(L.moon.illuminance.w, 1.0, resolved);

  // Stars shine through the sky light but not through the moon.
  vec3 stars = vec3(starFlux(ivec2(p)) * L.night.z / pixelSolidAngle(params.view, pixelCentre));
  stars *= (1.0 - moonCover) * aboveHorizon;

  // Premultiplied "over": what lies beyond each cloud layer shows through its clear share.
  vec3 beyond = sky + stars + sunDisc + moonDisc;
  vec4 clouds = params.layers.x != 0u ? imageLoad(cloudImage, ivec2(p)) : vec4(0.0);
  vec4 nearer = highClouds, farther = clouds;
  if (params.layers.y == 0u) {  // below the high clouds: the volumetric clouds are nearer
    nearer = clouds;
    farther = highClouds;
  }
  beyond = beyond * (1.0 - farther.a) + farther.rgb;
  imageStore(beautyImage, ivec2(p), vec4(beyond * (1.0 - nearer.a) + nearer.rgb, 1.0));
}
