// Parameters and bindings of passes/atmosphere_composite (shaders/atmosphere_composite.comp).
#ifndef SKY_ATMOSPHERE_COMPOSITE_SHARED_H
#define SKY_ATMOSPHERE_COMPOSITE_SHARED_H
#include "shared_prelude.h"
#include "view_shared.h"

#define ATMOSPHERE_COMPOSITE_GROUP_X 8
#define ATMOSPHERE_COMPOSITE_GROUP_Y 8
#define ATMOSPHERE_COMPOSITE_BINDING_PARAMS 0
#define ATMOSPHERE_COMPOSITE_BINDING_BEAUTY 1
#define ATMOSPHERE_COMPOSITE_BINDING_SKY 2

SKY_SHARED_BEGIN

struct AtmosphereCompositeParams {
  ViewState view;
  vec4 sunDirection;  // xyz: unit direction to the sun (east-north-up); w: angular radius (rad)
  vec4 sunDisc;       // rgb: disc radiance (scene-linear); w: unused
  vec4 skyColor;      // rgb: Csky;  w: glow size s
  vec4 fogColor;      // rgb: Cfog;  w: haze top hmax (fraction of the dome height)
  vec4 glowColor;     // rgb: Csun;  w: unused
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::AtmosphereCompositeParams) == 64 + 5 * 16,
              "std140 layout of AtmosphereCompositeParams");
#endif
#endif
