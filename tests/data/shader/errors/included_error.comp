#version 460
#include "broken.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { float result[]; };
void main() { result[0] = brokenHelper(1.0); }
