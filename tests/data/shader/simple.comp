#version 460
// Smallest useful compute shader: doubles every element of a buffer.
layout(local_size_x = 8, local_size_y = 4, local_size_z = 1) in;

layout(std430, set = 0, binding = 0) buffer Data { float values[]; } data;

void main() {
  uint i = gl_GlobalInvocationID.y * 64u + gl_GlobalInvocationID.x;
  data.values[i] *= 2.0;
}
