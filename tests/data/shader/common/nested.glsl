#ifndef TEST_NESTED_GLSL
#define TEST_NESTED_GLSL
// Relative to this file's folder (common/), twice: the guard must drop the second copy.
#include "math.glsl"
#include "math.glsl"

float testQuad(float x) { return testSquare(testSquare(x)); }
#endif
