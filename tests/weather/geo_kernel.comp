#version 460
// Kernel for geo_kernel_test.cpp: calls shaders/common/geo.glsl for GEO_KERNEL_QUERIES
// queries (x) in each of GEO_KERNEL_FRAMES camera frames and regions (y).
// Row 3y: latLonAltitude(frame, point); row 3y + 1: geoPosition(frame, lat, lon, altitude)
// and w = geoAltitude of it; row 3y + 2: regionUv(region, lat, lon) as (u, v, inside, 0).
#include <common/geo.glsl>

#define GEO_KERNEL_QUERIES 64
#define GEO_KERNEL_FRAMES 4
layout(local_size_x = GEO_KERNEL_QUERIES) in;

layout(std140, binding = 0) uniform Frames {
  GeoFrame frames[GEO_KERNEL_FRAMES];
  GeoRegion regions[GEO_KERNEL_FRAMES];
};
// [i]: xyz a point in the ENU frame (metres); [GEO_KERNEL_QUERIES + i]: latitude, longitude,
// altitude (degrees, metres). Each frame offsets them by its own camera (see the test).
layout(std140, binding = 1) uniform Queries {
  vec4 queries[2 * GEO_KERNEL_QUERIES * GEO_KERNEL_FRAMES];
};
layout(binding = 2, rgba32f) uniform writeonly image2D results;

void main() {
  uint i = gl_LocalInvocationIndex, f = gl_WorkGroupID.y;
  uint base = 2u * GEO_KERNEL_QUERIES * f;
  vec3 p = queries[base + i].xyz;
  vec3 g = queries[base + GEO_KERNEL_QUERIES + i].xyz;
  GeoFrame frame = frames[f];
  imageStore(results, ivec2(i, 3 * f), vec4(latLonAltitude(frame, p), 0.0));
  vec3 q = geoPosition(frame, g.x, g.y, g.z);
  imageStore(results, ivec2(i, 3 * f + 1), vec4(q, geoAltitude(frame, q)));
  vec2 uv;
  bool inside = regionUv(regions[f], g.x, g.y, uv);
  imageStore(results, ivec2(i, 3 * f + 2), vec4(uv, inside ? 1.0 : 0.0, 0.0));
}
