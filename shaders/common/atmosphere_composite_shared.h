// Parameters and bindings of passes/atmosphere_composite (shaders/atmosphere_composite.comp).
#ifndef SKY_ATMOSPHERE_COMPOSITE_SHARED_H
#define SKY_ATMOSPHERE_COMPOSITE_SHARED_H
#include "shared_prelude.h"
#include "view_shared.h"

#define ATMOSPHERE_COMPOSITE_GROUP_X 8
#define ATMOSPHERE_COMPOSITE_GROUP_Y 8
#define ATMOSPHERE_COMPOSITE_BINDING_PARAMS 0
#define ATMOSPHERE_COMPOSITE_BINDING_BEAUTY 1
#define ATMOSPHERE_COMPOSITE_BINDING_SKY 2  // read: from passes/sky_high_clouds
#define ATMOSPHERE_COMPOSITE_BINDING_LIGHTING 3
#define ATMOSPHERE_COMPOSITE_BINDING_STARS 4
#define ATMOSPHERE_COMPOSITE_BINDING_HIGH_CLOUDS 5  // read: from passes/sky_high_clouds
#define ATMOSPHERE_COMPOSITE_BINDING_CLOUDS 6       // read: from passes/volumetric_clouds

SKY_SHARED_BEGIN

struct AtmosphereCompositeParams {
  ViewState view;
  uvec4 layers;  // x: 1 when the volumetric clouds are bound; y: 1 when the camera is above
                 // the high-cloud layer (they then lie in front of the volumetric clouds)
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::AtmosphereCompositeParams) == 64 + 16,
              "std140 layout of AtmosphereCompositeParams");
#endif
#endif
