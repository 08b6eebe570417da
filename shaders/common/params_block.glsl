// The per-frame parameter blocks of the passes (params, lighting, atmosphere) are std140
// uniform blocks read as element SKY_PARAMS_INDEX of a one-element array:
//
//   layout(std140, binding = MY_PASS_BINDING_PARAMS) uniform Params { MyPassParams paramsBlock[1]; };
//   #define params paramsBlock[SKY_PARAMS_INDEX]
//
// On lavapipe (Mesa 22.3, Debian 12) the index is an expression that is always 0 but that the
// compiler cannot fold. lavapipe inlines uniform values that feed a branch or a loop bound
// into a shader it compiles anew each time the pipeline is bound, and keeps every copy until
// the pipeline is destroyed: a JIT compile per pass per frame, and a time-lapse that grew 2 MB
// a frame. It does so only for loads at a constant offset, which an unknown index is not.
// Everywhere else (Context::shaderDefines) the index is the literal 0: a plain uniform block.
// A read-only storage block would dodge the inlining as well, but lavapipe bounds-checks
// every storage load, which made the cloud raymarch 8 % slower.
#ifndef SKY_PARAMS_BLOCK_GLSL
#define SKY_PARAMS_BLOCK_GLSL

#if defined(SKY_UNFOLDABLE_PARAMS_INDEX) && SKY_UNFOLDABLE_PARAMS_INDEX
#define SKY_PARAMS_INDEX (gl_NumWorkGroups.x / (gl_NumWorkGroups.x + 1u))
#else
#define SKY_PARAMS_INDEX 0
#endif

#endif
