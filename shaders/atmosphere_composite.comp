#version 460
// The final image in scene-linear Rec.709: the clear sky and the high clouds (from
// passes/sky_high_clouds), the star field and the sun and moon discs behind the clouds, the
// ground below the horizon, and the volumetric low and mid clouds (passes/volumetric_clouds)
// in front of them, or behind the high clouds when the camera flies above those.
//
// The ground is a Lambertian sphere lit by the sun and the moon, shadowed by the clouds
// (passes/cloud_shadow), and by the sky. The ground and the volumetric clouds are seen
// through the air in front of them (aerial perspective): the physical variant
// (ATMOSPHERE_COMPOSITE_PHYSICAL) takes it from its aerial-perspective volume and
// transmittance LUT (Hillaire 2020, section 5.4), the kozlov one from the haze of the
// lighting model's atmosphere (Koschmieder's airlight). The high clouds carry their own.
//
// What a frame does not show is compiled out, not branched around (a software rasteriser
// runs both sides of a branch): ATMOSPHERE_COMPOSITE_SUN_DISC and _MOON_DISC only when the
// disc can reach a pixel of the view, ATMOSPHERE_COMPOSITE_STARS only when the star passes
// ran (passes/atmosphere_composite picks the variant per frame; the image is the same).
// Likewise per band of rows (AtmosphereCompositeBand): ATMOSPHERE_COMPOSITE_GROUND only where
// a row can see below the horizon, ATMOSPHERE_COMPOSITE_CLOUD_AIR only where a row can see
// the volumetric clouds.
//
// ATMOSPHERE_COMPOSITE_HOST draws into a host's own scene-linear colour image as well
// (skylayers::Sky::record): where its depth image (ATMOSPHERE_COMPOSITE_HOST_DEPTH) holds no
// geometry, the frame; where it does, the host's pixel seen through the air to it, behind the
// volumetric clouds in front of it (their march stopped at its depth).
//
// ATMOSPHERE_COMPOSITE_PERCEPTION writes the perception layers as well (docs/outputs.md,
// "Perception layers"): a label and a cloud type per pixel by what its centre ray meets
// first, the air's transmittance to that, and the cloud shadow on the ground there.
#include "common/params_block.glsl"
#include "common/atmosphere_composite_shared.h"
#include "common/cloud_perception_shared.h"
#include "common/view.glsl"
#define LIGHTING_BINDING ATMOSPHERE_COMPOSITE_BINDING_LIGHTING
#include "common/lighting.glsl"
#if ATMOSPHERE_COMPOSITE_STARS
#define STAR_FLUX_BINDING ATMOSPHERE_COMPOSITE_BINDING_STARS
#endif
#include "common/star_field.glsl"
#include "common/cloud_shadow.glsl"
#if ATMOSPHERE_COMPOSITE_PHYSICAL
#include "common/atmosphere.glsl"
#endif

layout(local_size_x = ATMOSPHERE_COMPOSITE_GROUP_X, local_size_y = ATMOSPHERE_COMPOSITE_GROUP_Y) in;

#ifndef ATMOSPHERE_COMPOSITE_GROUND
#define ATMOSPHERE_COMPOSITE_GROUND 1
#endif
#ifndef ATMOSPHERE_COMPOSITE_CLOUD_AIR
#define ATMOSPHERE_COMPOSITE_CLOUD_AIR 1
#endif
#ifndef ATMOSPHERE_COMPOSITE_HOST
#define ATMOSPHERE_COMPOSITE_HOST 0
#endif
#ifndef ATMOSPHERE_COMPOSITE_HOST_DEPTH
#define ATMOSPHERE_COMPOSITE_HOST_DEPTH 0
#endif
#ifndef ATMOSPHERE_COMPOSITE_HOST_FORMAT
#define ATMOSPHERE_COMPOSITE_HOST_FORMAT rgba16f
#endif
#ifndef ATMOSPHERE_COMPOSITE_PERCEPTION
#define ATMOSPHERE_COMPOSITE_PERCEPTION 0
#endif

layout(push_constant) uniform Push {
  AtmosphereCompositeBand band;
};
layout(std140, binding = ATMOSPHERE_COMPOSITE_BINDING_PARAMS) uniform Params {
  AtmosphereCompositeParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_BEAUTY, rgba32f) uniform writeonly image2D beautyImage;
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_SKY, rgba32f) uniform readonly image2D skyImage;
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_HIGH_CLOUDS, rgba32f) uniform readonly image2D
    highCloudImage;
#if ATMOSPHERE_COMPOSITE_CLOUDS
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_CLOUDS, rgba32f) uniform readonly image2D cloudImage;
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_CLOUD_DEPTH, rg32f) uniform readonly image2D
    cloudDepthImage;
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_CLOUD_SHADOW) uniform sampler2D cloudShadow;
#endif
#if ATMOSPHERE_COMPOSITE_HOST
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_HOST_COLOUR, ATMOSPHERE_COMPOSITE_HOST_FORMAT)
uniform image2D hostColour;
#if ATMOSPHERE_COMPOSITE_HOST_DEPTH
#include "common/host_depth.glsl"
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_HOST_DEPTH) uniform sampler2D hostDepth;
#endif
#endif
#if ATMOSPHERE_COMPOSITE_PERCEPTION
#if ATMOSPHERE_COMPOSITE_CLOUDS
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_CLOUD_HIT, rgba32f) uniform readonly image2D
    cloudHitImage;
#endif
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_PERCEPTION, rgba32f) uniform writeonly image2D
    perceptionImage;
#endif
#if ATMOSPHERE_COMPOSITE_PHYSICAL
layout(std140, binding = ATMOSPHERE_COMPOSITE_BINDING_ATMOSPHERE) uniform AtmosphereBlock {
  AtmosphereParams atmosphereBlock[1];
};
#define atmosphere atmosphereBlock[SKY_PARAMS_INDEX]
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_TRANSMITTANCE) uniform sampler2D transmittanceLut;
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_AERIAL_PERSPECTIVE) uniform sampler3D
    aerialPerspectiveLut;
#endif

// Fraction of a pixel of angular size `pixel` covered by a disc of angular radius `radius`
// whose centre is `distance` away (a box-filtered edge). A disc smaller than a pixel is
// spread over one pixel's width with its radiance scaled by the area ratio, so its energy
// stays within ~8 % of pi r^2 L instead of flickering in and out at test sizes like 64x36.
float discCoverage(float distance, float radius, float pixel) {
  float spread = max(radius, pixel);
  float inside = clamp((spread - distance) / pixel + 0.5, 0.0, 1.0);
  return inside * (radius * radius) / (spread * spread);
}

// Limb darkening of the sun's disc at `r` of its radius from the centre, relative to the disc's
// mean radiance, so the disc's flux is unchanged: the linear law I(mu) / I(1) = 1 - u (1 - mu),
// mu = sqrt(1 - r^2), whose mean over the disc is 1 - u / 3. u per channel for 680, 550 and
// 440 nm from Neckel & Labs (1994), rounded: the limb is darker and redder than the centre.
vec3 sunLimbDarkening(float r) {
  const vec3 u = vec3(0.50, 0.60, 0.75);
  float mu = sqrt(max(1.0 - r * r, 0.0));
  return (1.0 - u * (1.0 - mu)) / (1.0 - u / 3.0);
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

// Distance along unit V from the camera (cameraR from the centre, on the z axis) to the
// ground sphere of radius planetR, or -1 where the ray misses it.
float groundDistance(float cameraR, vec3 V, float planetR) {
  float b = cameraR * V.z;
  float c = (cameraR - planetR) * (cameraR + planetR);
  float disc = b * b - c;
  if (V.z >= 0.0 || disc < 0.0) return -1.0;
  // The near root as (product of the roots) / (far root): no cancellation near the camera.
  return c / (-b + sqrt(disc));
}

// What the air between the camera and a point does to the light from it: its transmittance,
// and the light it scatters toward the camera on the way.
struct Air {
  vec3 transmittance;
  vec3 inScattered;
};

#if ATMOSPHERE_COMPOSITE_PHYSICAL
// Hillaire 2020's aerial perspective out to the froxel volume's last slice. Beyond it, the
// sky-view LUT's in-scattering along the whole ray (`skyHere`, to the top of the atmosphere or
// to the ground) is shared out by the transmittance lost from the last slice on: exact where
// the light along the rest of the ray is uniform, and continuous at both ends.
Air airTo(vec3 V, float distanceM, vec2 uv, vec3 skyHere) {
  float d = distanceM * 1e-3;
  float n = atmosphere.aerialPerspective.y;
  float lastSlice = atmosphereApSliceDistance(atmosphere, (n - 0.5) / n);
  Air a;
  mat3 T = transmittancesAlong(atmosphere, transmittanceLut, V, vec3(d, lastSlice, 1e9));
  a.transmittance = T[0];
  vec3 nearS = aerialPerspective(atmosphere, aerialPerspectiveLut, uv, min(d, lastSlice)).rgb;
  vec3 nearT = T[1], endT = T[2];
  vec3 w = clamp((nearT - a.transmittance) / max(nearT - endT, vec3(1e-6)), 0.0, 1.0);
  a.inScattered = (d <= lastSlice ? nearS : mix(nearS, max(skyHere, nearS), w)) * params.airLight;
  return a;
}
#else
// Optical depth of the lighting model's haze (light::hazeMedium) along a straight path of
// length t from altitude h0 to h1 (m above sea level), the altitude taken as changing
// linearly along it: the integral of beta exp(-h / H) is beta exp(-h0 / H) t (1 - e^-x) / x
// with x = (h1 - h0) / H.
vec3 hazeOpticalDepth(float h0, float h1, float t) {
  vec3 tau = vec3(0.0);
  for (int k = 0; k < 2; ++k) {
    vec4 medium = k == 0 ? params.hazeRayleigh : params.hazeAerosol;
    float x = (h1 - h0) / medium.w;
    float f = abs(x) < 1e-3 ? 1.0 - 0.5 * x : (1.0 - exp(-x)) / x;
    tau += medium.rgb * exp(-max(h0, 0.0) / medium.w) * t * f;
  }
  return tau;
}

// Koschmieder: a point at distance t seen through air of transmittance T takes on the
// horizon sky's colour (`horizon`, the airlight of an endless path) by 1 - T.
Air airTo(vec3 V, float distanceM, vec3 horizon) {
  float cameraR = params.cameraRadiusM;
  vec3 end = vec3(0.0, 0.0, cameraR) + distanceM * V;
  float h0 = cameraR - params.planetRadiusM;
  float h1 = length(end) - params.planetRadiusM;
  Air a;
  a.transmittance = exp(-hazeOpticalDepth(h0, h1, distanceM));
  a.inScattered = horizon * (1.0 - a.transmittance) * params.airLight;
  return a;
}
#endif

// The share of the key light's beam the clouds let through to the ground point `hit` (from
// the planet's centre, the camera on the z axis): 1 without clouds.
float groundCloudShadow(vec3 hit) {
  float shadow = 1.0;
#if ATMOSPHERE_COMPOSITE_CLOUDS
  // The map is laid out by ground distance east and north of the point below the camera.
  float across = length(hit.xy);
  vec2 toward = across > 0.0 ? hit.xy / across : vec2(0.0);
  vec2 metres = toward * atan(across, hit.z) * params.planetRadiusM;
  vec2 u = cloudShadowU(params.shadow,
                        metres - vec2(params.shadow.shiftEastM, params.shadow.shiftNorthM));
  shadow = texture(cloudShadow, clamp(u * 0.5 + 0.5, 0.0, 1.0)).r;
  // Past the map's edge the ground takes the mean share of sunlight the cover lets through.
  float outside = smoothstep(0.9, 1.0, max(abs(u.x), abs(u.y)));
  shadow = mix(shadow, 1.0 - params.overcast, outside);
#endif
  return shadow;
}

// The light the ground sends toward the camera from the point at distance t along V:
// albedo times the irradiance of the sun and the moon (each through its share of the cloud
// shadow) and of the sky and the clouds (Kasten & Czeplak's overcast share).
vec3 groundRadiance(LightingState L, vec3 V, float t) {
  vec3 hit = vec3(0.0, 0.0, params.cameraRadiusM) + t * V;
  vec3 up = normalize(hit);
  float muS = max(dot(up, L.sun.direction.xyz), 0.0);
  float muM = max(dot(up, L.moon.direction.xyz), 0.0);
#if ATMOSPHERE_COMPOSITE_PHYSICAL
  float Rg = atmosphere.radii.x;
  vec3 sun = L.sunSpace.rgb * transmittanceToTop(atmosphere, transmittanceLut, Rg, muS);
  vec3 moon = L.moonSpace.rgb * transmittanceToTop(atmosphere, transmittanceLut, Rg, muM);
#else
  vec3 sun = params.sunAtGround.rgb, moon = params.moonAtGround.rgb;
#endif
  float shadow = groundCloudShadow(hit);
  float sunShadow = params.shadow.lightIsSun > 0.5 ? shadow : 1.0;
  float moonShadow = params.shadow.lightIsSun > 0.5 ? 1.0 : shadow;
  vec3 clearDirect = sun * muS + moon * muM;
  vec3 direct = sun * muS * sunShadow + moon * muM * moonShadow;
  // The sky light (radiance of the upper hemisphere; as irradiance the same number in the
  // renderer's units) through the gaps, and the light the cloud cover passes on.
  vec3 skyLight = L.palette.ambientTop.rgb + L.moonPalette.ambientTop.rgb;
  float N = params.overcast;
  vec3 diffuse = skyLight * (1.0 - N) + N * CLOUD_DIFFUSE_TRANSMISSION * (clearDirect + skyLight);
  return params.groundAlbedo.rgb * (direct + diffuse);
}

#if ATMOSPHERE_COMPOSITE_PERCEPTION
// Distance along unit V from the camera to the sphere of altitude `altitudeM` from inside it,
// -1 where the ray does not reach it going out (the camera above it: going down, the near
// root).
float sphereDistance(vec3 V, float altitudeM) {
  float cameraR = params.cameraRadiusM, r = params.planetRadiusM + altitudeM;
  float b = cameraR * V.z, c = (cameraR - r) * (cameraR + r);
  float disc = b * b - c;
  if (disc < 0.0) return -1.0;
  float q = sqrt(disc);
  return c < 0.0 ? -b + q : (-b - q >= 0.0 ? -b - q : -1.0);
}

// The air's transmittance from the camera to the point `distanceM` along V (a huge distance:
// to the top of the atmosphere), as one number: the Rec. 709 luminance weights of its red,
// green and blue.
float perceptionAir(vec3 V, float distanceM) {
#if ATMOSPHERE_COMPOSITE_PHYSICAL
  vec3 T = transmittanceAlong(atmosphere, transmittanceLut, V, distanceM * 1e-3);
#else
  // The kozlov haze, integrated along the bent path (the beauty's airTo takes the altitude
  // as changing linearly, close for the clouds' and the ground's distances but kilometres off
  // along a grazing ray to space): 48 steps, denser near the camera, the altitude exact at
  // each.
  float top = max(sphereDistance(V, 100000.0), 0.0);
  float t = min(distanceM, top);
  vec3 tau = vec3(0.0);
  const int n = 48;
  float prev = 0.0;
  for (int i = 1; i <= n; ++i) {
    float x = float(i) / float(n);
    float ti = t * x * x;
    float tm = 0.5 * (prev + ti);
    vec3 q = vec3(0.0, 0.0, params.cameraRadiusM) + tm * V;
    float h = max(length(q) - params.planetRadiusM, 0.0);
    tau += (params.hazeRayleigh.rgb * exp(-h / params.hazeRayleigh.w) +
            params.hazeAerosol.rgb * exp(-h / params.hazeAerosol.w)) * (ti - prev);
    prev = ti;
  }
  vec3 T = exp(-tau);
#endif
  return dot(T, vec3(0.2126, 0.7152, 0.0722));
}
#endif

// One pixel of the frame and where it looks: the view direction, the pixel's angular size and
// the horizon, which the steps below share.
struct Pixel {
  ivec2 p;
  vec2 centre;  // pixel coordinates of its centre
  vec2 uv;      // the centre in 0..1 of the view
  vec3 V;       // the view direction (unit)
  float angle;  // the pixel's angular size
  float horizonZ;      // the cosine of zenith where rays graze the ground sphere (0 without one)
  float aboveHorizon;  // the share of the pixel above the horizon
  vec3 level;          // the horizontal direction below V
};

Pixel pixelAt(uvec2 p) {
  Pixel px;
  px.p = ivec2(p);
  px.centre = vec2(p) + 0.5;
  px.uv = px.centre / vec2(params.view.size.xy);
  px.V = viewDirection(params.view, px.centre);
  px.angle = viewPixelAngle(params.view, px.V);
  // The ground hides what lies below the horizon, pixel by pixel. Seen from above the ground
  // the horizon dips below the horizontal, to where rays graze the ground sphere.
  float h = params.cameraRadiusM - params.planetRadiusM;
  px.horizonZ = params.observer != 0u
                    ? -sqrt(max(h * (2.0 * params.planetRadiusM + h), 0.0)) / params.cameraRadiusM
                    : 0.0;
  px.aboveHorizon = clamp((px.V.z - px.horizonZ) / px.angle + 0.5, 0.0, 1.0);
  px.level = vec3(length(px.V.xy) > 1e-6 ? normalize(px.V.xy) : vec2(0.0, 1.0), 0.0);
  return px;
}

// The sun's and the moon's discs in the pixel, and how much of it the moon covers (the stars
// do not shine through it), with the distances the perception labels use.
struct Discs {
  vec3 sun, moon;
  float moonCover;
  float sunDistance, moonDistance;  // angles from the pixel's centre to the discs' centres
};

Discs discsIn(Pixel px, LightingState L) {
  Discs d;
  d.sun = vec3(0.0);
  d.moon = vec3(0.0);
  d.moonCover = 0.0;
  d.sunDistance = d.moonDistance = 1e9;
  // A disc spread over a pixel wider than itself (see discCoverage) would leak past the
  // horizon; there the share of the disc above the horizon (illuminance.w) hides it instead.
  // Resolved discs are cut pixel by pixel. The two blend as the disc grows past a pixel.
#if ATMOSPHERE_COMPOSITE_SUN_DISC
  float sunR = L.sun.direction.w;
  d.sunDistance = acos(clamp(dot(px.V, L.sun.direction.xyz), -1.0, 1.0));
  float sunCover = discCoverage(d.sunDistance, sunR, px.angle);
  float sunResolved = smoothstep(1.0, 2.0, sunR / px.angle);
  // A resolved disc shows its limb darkening; one a pixel or less across, its mean.
  vec3 limb = mix(vec3(1.0), sunLimbDarkening(min(d.sunDistance / sunR, 1.0)), sunResolved);
  d.sun = L.sunDisc.rgb * limb * sunCover * px.aboveHorizon *
          mix(L.sun.illuminance.w, 1.0, sunResolved);
#endif
  // The moon: resolved discs are shaded per pixel with an anti-aliased edge; discs near or
  // below a pixel in size carry their mean radiance with the sun's coverage rule, so the
  // drawn flux stays right at every resolution. The two blend, so zooming does not pop.
#if ATMOSPHERE_COMPOSITE_MOON_DISC
  float moonR = L.moon.direction.w;
  d.moonDistance = acos(clamp(dot(px.V, L.moon.direction.xyz), -1.0, 1.0));
  d.moonCover = discCoverage(d.moonDistance, moonR, px.angle);
  vec3 moonMean = L.moonDisc.rgb * L.moonEarthshine.w + L.moonEarthshine.rgb;
  vec3 moonResolved = d.moonDistance < moonR + px.angle ? moonSurface(L, px.V) : vec3(0.0);
  float resolved = smoothstep(1.0, 2.0, moonR / px.angle);
  d.moon = mix(moonMean, moonResolved, resolved) * d.moonCover * px.aboveHorizon *
           mix(L.moon.illuminance.w, 1.0, resolved);
#endif
  return d;
}

// The stars: they shine through the sky light but not through the moon.
vec3 starLight(Pixel px, LightingState L, Discs discs) {
  vec3 stars = vec3(0.0);
#if ATMOSPHERE_COMPOSITE_STARS
  float flux = starFlux(px.p);
  if (flux > 0.0)
    stars = vec3(flux * L.night.z / pixelSolidAngle(params.view, px.centre) *
                 (1.0 - discs.moonCover) * px.aboveHorizon);
#endif
  return stars;
}

// What lies beyond every cloud: the sky, the stars and the discs above the horizon, the ground
// through the air in front of it below.
vec3 beyondTheClouds(Pixel px, LightingState L, vec3 sky, vec3 horizon, Discs discs) {
  // Seen from below the clouds the sky within a few degrees of the horizon is the air under
  // them, lit like it (airLight): under an overcast the distant horizon is no bright band of
  // clear sky. Higher up the sky shows through the gaps as it is.
  float underClouds = params.observer != 0u ? smoothstep(0.0, 0.05, px.V.z - px.horizonZ) : 1.0;
  vec3 beyond = sky * mix(params.airLight, 1.0, underClouds) + starLight(px, L, discs) +
                discs.sun + discs.moon;
#if ATMOSPHERE_COMPOSITE_GROUND
  if (params.observer != 0u && px.aboveHorizon < 1.0) {
    // The part of the pixel below the horizon sees the ground: along V, or where V passes
    // above it, just under the horizon.
    float z = px.horizonZ - 1e-5;
    vec3 Vg = px.V.z < z ? px.V : vec3(px.level.xy * sqrt(max(1.0 - z * z, 0.0)), z);
    float t = max(groundDistance(params.cameraRadiusM, Vg, params.planetRadiusM), 0.0);
#if ATMOSPHERE_COMPOSITE_PHYSICAL
    // The sky-view LUT below the horizon is just the air in front of the ground.
    Air air;
    air.transmittance = transmittanceAlong(atmosphere, transmittanceLut, Vg, t * 1e-3);
    air.inScattered = sky * params.airLight;
#else
    Air air = airTo(Vg, t, horizon);
#endif
    vec3 ground = groundRadiance(L, Vg, t) * air.transmittance + air.inScattered;
    beyond = mix(ground, beyond, px.aboveHorizon);
  }
#endif
  return beyond;
}

// The air between the camera and a point `distanceM` along the pixel's ray, for either sky.
Air airAlong(Pixel px, float distanceM, vec3 sky, vec3 horizon) {
#if ATMOSPHERE_COMPOSITE_PHYSICAL
  return airTo(px.V, distanceM, px.uv, sky);
#else
  return airTo(px.V, distanceM, horizon);
#endif
}

// The volumetric clouds (premultiplied) as the camera sees them, through the air in front of
// them at their transmittance-weighted depth; nothing without them.
vec4 cloudsThroughTheAir(Pixel px, vec3 sky, vec3 horizon) {
  vec4 clouds = vec4(0.0);
#if ATMOSPHERE_COMPOSITE_CLOUDS
  clouds = imageLoad(cloudImage, px.p);
#if ATMOSPHERE_COMPOSITE_CLOUD_AIR
  if (params.observer != 0u && clouds.a > 0.0) {
    Air air = airAlong(px, imageLoad(cloudDepthImage, px.p).r, sky, horizon);
    clouds.rgb = clouds.rgb * air.transmittance + clouds.a * air.inScattered;
  }
#endif
#endif
  return clouds;
}

// Premultiplied "over": what lies beyond each cloud layer shows through its clear share. Below
// the high clouds the volumetric clouds are nearer; above them, the high clouds.
vec3 layered(vec3 beyond, vec4 clouds, vec4 highClouds) {
  vec4 nearer = highClouds, farther = clouds;
  if (params.aboveHighClouds == 0u) {
    nearer = clouds;
    farther = highClouds;
  }
  beyond = beyond * (1.0 - farther.a) + farther.rgb;
  return beyond * (1.0 - nearer.a) + nearer.rgb;
}

#if ATMOSPHERE_COMPOSITE_PERCEPTION
// What the pixel's centre ray meets first (docs/outputs.md, "Perception layers"): its label,
// its cloud type, the air's transmittance to it and, on the ground, the cloud shadow there.
vec4 perceptionOf(Pixel px, vec4 highClouds, Discs discs) {
  vec4 hit = vec4(0.0, 1.0 / 0.0, -1.0, 0.0);  // no volumetric clouds: no hit
#if ATMOSPHERE_COMPOSITE_CLOUDS
  hit = imageLoad(cloudHitImage, px.p);
#endif
  float cameraR = params.cameraRadiusM;
  bool cloudHit = !isinf(hit.g) && hit.b >= 0.0;
  float groundT = params.observer != 0u ? groundDistance(cameraR, px.V, params.planetRadiusM) : -1.0;
  bool groundHit = groundT >= 0.0;
  // The high clouds hide what lies behind them where they hide as much as a tenth of an
  // optical depth of cloud does.
  bool highHit = highClouds.a >= 1.0 - exp(-CLOUD_PERCEPTION_HIT_TAU);
  float highT = sphereDistance(px.V, params.highCloudsAltitudeM);
  // Seen from below, the high clouds lie beyond the volumetric ones and the ground hides
  // them; seen from above, they come first.
  if (params.aboveHighClouds == 0u && (cloudHit || groundHit)) highHit = false;
  if (highT < 0.0) highHit = false;
  int label = PERCEPTION_LABEL_SKY;
  int type = PERCEPTION_TYPE_NONE;
  float distanceM = 1e12;  // to the top of the atmosphere
  if (highHit && params.aboveHighClouds != 0u) {
    label = PERCEPTION_LABEL_HIGH_CLOUD;
    type = PERCEPTION_TYPE_CIRRUS;
    distanceM = highT;
  } else if (cloudHit && (!groundHit || hit.g <= groundT)) {
    bool low = hit.b < 0.5;
    label = low ? PERCEPTION_LABEL_LOW_CLOUD : PERCEPTION_LABEL_MID_CLOUD;
    // The nearest of the map's type keys: 0 stratiform, 0.5 cellular, 1 convective.
    int key = hit.a < 0.25 ? 0 : hit.a < 0.75 ? 1 : 2;
    type = low ? PERCEPTION_TYPE_STRATUS + key
               : (key == 0 ? PERCEPTION_TYPE_ALTOSTRATUS : PERCEPTION_TYPE_ALTOCUMULUS);
    distanceM = hit.g;
  } else if (groundHit) {
    label = PERCEPTION_LABEL_GROUND;
    distanceM = groundT;
  } else if (highHit) {
    label = PERCEPTION_LABEL_HIGH_CLOUD;
    type = PERCEPTION_TYPE_CIRRUS;
    distanceM = highT;
  } else {
    // A disc a pixel or less across labels the pixel its centre falls in.
#if ATMOSPHERE_COMPOSITE_MOON_DISC
    if (discs.moonDistance < max(lighting.moon.direction.w, 0.5 * px.angle))
      label = PERCEPTION_LABEL_MOON;
#endif
#if ATMOSPHERE_COMPOSITE_SUN_DISC
    // The moon in front of the sun in an eclipse.
    if (discs.sunDistance < max(lighting.sun.direction.w, 0.5 * px.angle) &&
        label != PERCEPTION_LABEL_MOON)
      label = PERCEPTION_LABEL_SUN;
#endif
  }
  float air = params.observer != 0u ? perceptionAir(px.V, distanceM) : 1.0;
  float shadow = label == PERCEPTION_LABEL_GROUND
                     ? groundCloudShadow(vec3(0.0, 0.0, cameraR) + groundT * px.V)
                     : 1.0;
  return vec4(float(label), float(type), air, shadow);
}
#endif

#if ATMOSPHERE_COMPOSITE_HOST
// The host's own pixel: where its depth holds no geometry, the frame; where it does, its
// pixel seen through the air to it, behind the clouds in front of it.
vec4 hostPixel(Pixel px, vec3 frame, vec4 clouds, vec4 highClouds, vec3 sky, vec3 horizon) {
  vec4 host = vec4(frame, 1.0);
#if ATMOSPHERE_COMPOSITE_HOST_DEPTH
  float t = hostDistance(params.host, texelFetch(hostDepth, px.p, 0).r, px.V,
                         params.view.forward.xyz);
  if (t > 0.0) {
    host = imageLoad(hostColour, px.p);
    Air air = airAlong(px, t, sky, horizon);
    vec3 object = host.rgb * air.transmittance + air.inScattered;
    // The volumetric clouds in front of it: their march stopped at the host's depth
    // (volumetric_clouds.comp, VOLUMETRIC_CLOUDS_HOST_DEPTH), so all of what they hold lies
    // in front, and an object inside a cloud is seen through exactly the cloud before it.
    vec4 front = vec4(0.0);
#if ATMOSPHERE_COMPOSITE_CLOUDS
    if (params.observer != 0u) front = clouds;
#endif
    // Above the high clouds they lie in front of everything the host draws below them.
    if (params.aboveHighClouds != 0u) front = highClouds + front * (1.0 - highClouds.a);
    host.rgb = object * (1.0 - front.a) + front.rgb;
  }
#endif
  return host;
}
#endif

void main() {
  uvec2 p = gl_GlobalInvocationID.xy + uvec2(0u, band.rows.x);
  if (any(greaterThanEqual(p, params.view.size.xy))) return;
  Pixel px = pixelAt(p);
  LightingState L = lighting;
  vec3 sky = imageLoad(skyImage, px.p).rgb;
  vec4 highClouds = imageLoad(highCloudImage, px.p);  // premultiplied, a = coverage
  // The air toward the horizon below this direction: Kozlov's sky there is the airlight.
  vec3 horizon = clearSky(L, px.level);

  Discs discs = discsIn(px, L);
  vec3 beyond = beyondTheClouds(px, L, sky, horizon, discs);
  vec4 clouds = cloudsThroughTheAir(px, sky, horizon);
  vec3 frame = layered(beyond, clouds, highClouds);
  imageStore(beautyImage, px.p, vec4(frame, 1.0));
#if ATMOSPHERE_COMPOSITE_PERCEPTION
  imageStore(perceptionImage, px.p, perceptionOf(px, highClouds, discs));
#endif
#if ATMOSPHERE_COMPOSITE_HOST
  imageStore(hostColour, px.p, hostPixel(px, frame, clouds, highClouds, sky, horizon));
#endif
}
