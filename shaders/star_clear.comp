#version 460
// First of the star field's two passes: zeroes the flux buffer that star_field.comp then
// accumulates into with atomics, and writes its (width, height) header for the readers.
#include "common/star_field_shared.h"

layout(local_size_x = STAR_CLEAR_GROUP_X, local_size_y = STAR_CLEAR_GROUP_Y) in;

layout(push_constant) uniform Push {
  StarClearParams params;
};
layout(std430, binding = STAR_CLEAR_BINDING_FLUX) writeonly buffer Flux {
  uvec4 fluxSize;
  uint flux[];
};

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(p, params.size.xy))) return;
  if (p == uvec2(0)) fluxSize = uvec4(params.size.xy, 0, 0);
  flux[p.y * params.size.x + p.x] = 0u;
}
