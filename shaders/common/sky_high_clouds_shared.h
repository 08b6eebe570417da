// Parameters and bindings of passes/sky_high_clouds (shaders/sky_high_clouds.comp): the
// clear sky and the Kozlov high-cloud layer. The physical variant (SKY_PHYSICAL_SKY 1) also
// binds the atmosphere LUTs of passes/atmosphere_luts. The regional variant
// (SKY_HIGH_CLOUDS_REGIONAL 1, chosen by regional.x) takes the cover per pixel from the
// weather map's high layer: it binds the regional cover, the rank/shape texture and the
// per-cover coarse texture instead of the coefficient, levels and coarse textures.
#ifndef SKY_SKY_HIGH_CLOUDS_SHARED_H
#define SKY_SKY_HIGH_CLOUDS_SHARED_H
#include "shared_prelude.h"
#include "geo_shared.h"
#include "high_cloud_bake_shared.h"
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
// regional cover only (replacing COEFFICIENTS and COARSE):
#define SKY_HIGH_CLOUDS_BINDING_REGIONAL_COVER 11
#define SKY_HIGH_CLOUDS_BINDING_RANK_SHAPE 12
#define SKY_HIGH_CLOUDS_BINDING_COVER_COARSE 13
// the scene's cover only (with COEFFICIENTS and COARSE):
#define SKY_HIGH_CLOUDS_BINDING_LEVELS 14

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
  // Regional cover (regional.x = 1) only:
  GeoFrame geo;      // the camera's ENU frame on the pass's planet: origin.w = layer.x and
                     // origin.z = layer.y - layer.x, so the layer point t V maps to lat/lon
  GeoRegion region;  // the weather map's region; no high cloud outside it
  vec4 regional;     // x: 1 = cover per pixel from the regional cover texture, 0 = the
                     // baked coefficient texture; y: the style's ramp width w; zw: unused
  vec4 farField[HIGH_CLOUD_COVER_STEPS];  // mean coefficients at cover k / (STEPS - 1)
  // The texture's +u axis on the ground, a unit vector (east, north): east for image sources
  // (north up, as drawn), downwind for procedural ones, whose cirrus streaks run along +u, so
  // they lie along the wind (docs/high-clouds.md, "Orientation and tiling"). +v is +u turned
  // 90 degrees clockwise (east to south).
  float tileUEast;
  float tileUNorth;
  float padding0;  // std140: the rest of the row
  float padding1;
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::SkyHighCloudsParams) ==
                  64 + 6 * 16 + 64 + 16 + 16 + HIGH_CLOUD_COVER_STEPS * 16 + 16,
              "std140 layout of SkyHighCloudsParams");
#endif
#endif
