#version 460
layout(local_size_x = 1) in;

// The include below does not exist anywhere.
#include "common/does_not_exist.glsl"

void main() {}
