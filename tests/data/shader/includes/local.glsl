// Sits next to includes/main.comp and is found relative to it.
#include "../common/math.glsl"
float testLocal(float x) { return testSquare(x) + 1.0; }
