#version 460
// Debug view "cloud_density_slice": a vertical cut through the cloud density field along the
// camera's heading, from the camera out to params.sliceLengthM metres (across) and from sea level
// up to params.sliceTopM metres (down the image, top row highest). Each texel: r density,
// g the layer's cover there, b the cloud type, a the layer (0 low, 1 mid, -1 none).
#include "common/volumetric_clouds_shared.h"
#include "common/geo.glsl"
#include "common/cloud_density.glsl"
#include "common/cloud_field.glsl"

layout(local_size_x = VOLUMETRIC_CLOUDS_GROUP_X, local_size_y = VOLUMETRIC_CLOUDS_GROUP_Y) in;

layout(binding = CLOUD_SLICE_BINDING_IMAGE, rgba16f) uniform writeonly image2D sliceImage;

void main() {
  uvec2 id = gl_GlobalInvocationID.xy;
  ivec2 size = imageSize(sliceImage);
  if (any(greaterThanEqual(id, uvec2(size)))) return;
  vec2 uv = (vec2(id) + 0.5) / vec2(size);
  // The camera's heading on the ground (the view's forward without its pitch).
  vec3 f = params.view.forward.xyz;
  vec2 heading = length(f.xy) > 1e-6 ? normalize(f.xy) : vec2(0.0, 1.0);
  float distance = uv.x * params.sliceLengthM;
  float altitude = (1.0 - uv.y) * params.sliceTopM;
  // The point `distance` along the ground at `altitude`, in the camera's ENU frame.
  float R = params.geo.origin.w;
  // c + (R + altitude) up with c the Earth's centre, its height written as the drop below the
  // camera's horizon plane, (R + altitude)(1 - cos) = 2 (R + altitude) sin^2(angle / 2): the
  // sum itself cancels in float to half a metre, which across a sharp cloud edge changes the
  // density the slice shows.
  float angle = distance / R;
  float sh = sin(0.5 * angle);
  vec3 p = vec3((R + altitude) * sin(angle) * heading,
                (altitude - params.geo.origin.z) - 2.0 * (R + altitude) * sh * sh);
  CloudSample s;
  cloudSampleAt(p, 0.0, s);
  vec2 wuv;
  vec3 lla = latLonAltitude(params.geo, p);
  bool inside = regionUv(params.region, lla.x, lla.y, wuv);
  vec4 w = inside ? textureLod(weatherMap, wuv, 0.0) : vec4(0.0);
  float cover = s.layer == 1 ? w.g : w.r;
  imageStore(sliceImage, ivec2(id), vec4(s.density, cover, w.b, float(s.layer)));
}
