#version 460
// Test shader: writes `value` into every texel.
layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant) uniform Push { float value; };
layout(binding = 0, r32f) uniform writeonly image2D outImage;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(outImage)))) return;
  imageStore(outImage, p, vec4(value + float(p.x) * 0.0, 0, 0, 0));
}
