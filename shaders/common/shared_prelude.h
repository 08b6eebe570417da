// Included first by every header shared between GLSL and C++ (see STYLE.md).
// C++ gets GLM types inside namespace sky::shared; GLSL gets empty wrappers.
#ifndef SKY_SHARED_PRELUDE_H
#define SKY_SHARED_PRELUDE_H
#ifdef __cplusplus
#include "engine/gpu/glsl_types.h"
#else
#define SKY_SHARED_BEGIN
#define SKY_SHARED_END
#endif
#endif
