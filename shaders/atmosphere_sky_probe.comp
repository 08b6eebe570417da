#version 460
// Sky probe: an equirectangular image of the whole sphere as the renderer sees the physical
// sky, through the same skyViewRadiance() (sun plus moon LUT). Column 0 starts at north and
// azimuth grows eastward; row 0 is the zenith, the last row the nadir. A debug view, and the
// "LUT path" the atmosphere tests compare with a direct reference.
#include "common/params_block.glsl"
#include "common/atmosphere.glsl"

layout(local_size_x = ATMOSPHERE_GROUP_X, local_size_y = ATMOSPHERE_GROUP_Y) in;

layout(std140, binding = ATMOSPHERE_BINDING_PARAMS) uniform Params {
  AtmosphereParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
layout(binding = ATMOSPHERE_SKY_PROBE_BINDING_SUN) uniform sampler2D skyViewSun;
layout(binding = ATMOSPHERE_SKY_PROBE_BINDING_MOON) uniform sampler2D skyViewMoon;
layout(binding = ATMOSPHERE_SKY_PROBE_BINDING_OUT, rgba32f) uniform writeonly image2D probeImage;

void main() {
  ivec2 size = imageSize(probeImage);
  ivec2 id = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(id, size))) return;
  AtmosphereParams p = params;
  float azimuth = 2.0 * ATMOSPHERE_PI * (float(id.x) + 0.5) / float(size.x);
  float elevation = 0.5 * ATMOSPHERE_PI - ATMOSPHERE_PI * (float(id.y) + 0.5) / float(size.y);
  vec3 V = vec3(sin(azimuth) * cos(elevation), cos(azimuth) * cos(elevation), sin(elevation));
  vec3 sky = skyViewRadiance(p, skyViewSun, V, p.sunDirection.xyz) +
             skyViewRadiance(p, skyViewMoon, V, p.moonDirection.xyz);
  imageStore(probeImage, id, vec4(sky, 1.0));
}
