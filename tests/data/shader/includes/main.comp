#version 460
#include "local.glsl"
#include "common/nested.glsl"
#include <common/math.glsl>

layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { float result[]; };

void main() { result[0] = testLocal(2.0) + testQuad(2.0) + testSquare(3.0); }
