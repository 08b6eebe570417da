#version 460
// Test shader: out = texture(in) + value + x/1000 (the x term checks the whole image moves).
layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant) uniform Push { float value; };
layout(binding = 0) uniform sampler2D inImage;
layout(binding = 1, r32f) uniform writeonly image2D outImage;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(outImage)))) return;
  imageStore(outImage, p, vec4(texelFetch(inImage, p, 0).r + value, 0, 0, 0));
}
