// Guarded: included several times by the include tests.
#ifndef TEST_MATH_GLSL
#define TEST_MATH_GLSL

float testSquare(float x) { return x * x; }

#endif
