// Parameters and bindings of passes/sky_high_clouds (shaders/sky_high_clouds.comp): the
// clear sky and the Kozlov high-cloud layer. The physical variant (SKY_PHYSICAL_SKY 1) also
// binds the atmosphere LUTs of passes/atmosphere_luts.
#ifndef SKY_SKY_HIGH_CLOUDS_SHARED_H
#define SKY_SKY_HIGH_CLOUDS_SHARED_H
#include "shared_prelude.h"
#include "view_shared.h"

#define SKY_HIGH_CLOUDS_GROUP_X 8
#define SKY_HIGH_CLOUDS_GROUP_Y 8
#define SKY_HIGH_CLOUDS_BINDING_PARAMS 0
#define SKY_HIGH_CLOUDS_BINDING_LIGHTING 1
#define SKY_HIGH_CLOUDS_BINDING_SKY 2
#define SKY_HIGH_CLOUDS_BINDING_CLOUDS 3
#define SKY_HIGH_CLOUDS_BINDING_COEFFICIENTS 4
#define SKY_HIGH_CLOUDS_BINDING_NORMALS 5
#define SKY_HIGH_CLOUDS_BINDING_COARSE 6
// sky.model physical only:
#define SKY_HIGH_CLOUDS_BINDING_ATMOSPHERE 7
#define SKY_HIGH_CLOUDS_BINDING_TRANSMITTANCE 8
#define SKY_HIGH_CLOUDS_BINDING_SKY_VIEW_SUN 9
#define SKY_HIGH_CLOUDS_BINDING_SKY_VIEW_MOON 10

SKY_SHARED_BEGIN

struct SkyHighCloudsParams {
  ViewState view;
  vec4 layer;        // x: planet radius (m); y: camera distance from the planet's centre (m);
                     // z: layer radius (m); w: 1 when there are high clouds, else 0
  vec4 texture;      // x: texture offset east (m, the wind's drift); y: offset north (m);
                     // z: tile size (m); w: texels across the fine texture
  vec4 shading;      // x: brightness; y: edge glow width l (rad); z: coarse texels across;
                     // w: unused
  vec4 meanCoefficients;  // the texture's mean (thin lit, dense, clear, edges): the far field
  vec4 sunAtLayer;   // rgb: sun illuminance at the layer (kozlov model; the physical model
                     // takes it from the transmittance LUT per pixel); w: unused
  vec4 moonAtLayer;  // rgb: the same for the moon
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::SkyHighCloudsParams) == 64 + 6 * 16,
              "std140 layout of SkyHighCloudsParams");
#endif
#endif
