#version 460
// Three preprocessor errors: the preprocessing pass must report all of them.
#include "missing_one.glsl"
#include "missing_two.glsl"
#error third problem
layout(local_size_x = 1) in;
void main() {}
