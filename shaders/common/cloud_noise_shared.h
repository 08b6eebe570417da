// Parameters, bindings and sizes of the cloud-noise bake in passes/cloud_noise
// (shaders/cloud_noise_volume.comp: the shape and detail volumes; cloud_noise_curl.comp).
// What each channel holds is in docs/cloud-noise.md.
//
// All three textures are R8G8B8A8_UNORM and tile along every axis (sample them with repeat):
//   shape  (128^3): R low-frequency Perlin-Worley (lu2023) or simplex fbm (tang2019);
//                   G, B, A inverted Worley fbm of medium, high and highest frequency
//   detail (32^3 lu2023, 64^3 tang2019): R, G, B inverted Worley fbm of low, medium and high
//                   frequency; A = Lu (14)'s fbm of R, G, B
//   curl   (128^2): xyz = 0.5 + 0.5 v, v the curl of a Perlin vector potential scaled to
//                   [-1, 1]; A = 1
#ifndef SKY_CLOUD_NOISE_SHARED_H
#define SKY_CLOUD_NOISE_SHARED_H
#include "shared_prelude.h"

#define CLOUD_NOISE_GROUP_3D 4  // 4x4x4 invocations a workgroup for the volumes
#define CLOUD_NOISE_GROUP_2D 8  // 8x8 for the curl texture

#define CLOUD_NOISE_BINDING_OUT 0

// CloudNoiseParams.size.y
#define CLOUD_NOISE_MODEL_LU2023 0u
#define CLOUD_NOISE_MODEL_TANG2019 1u

// CloudNoiseParams.size.z of cloud_noise_volume.comp
#define CLOUD_NOISE_VOLUME_SHAPE 0u
#define CLOUD_NOISE_VOLUME_DETAIL 1u

#define CLOUD_NOISE_SHAPE_SIZE 128u
#define CLOUD_NOISE_DETAIL_SIZE_LU2023 32u
#define CLOUD_NOISE_DETAIL_SIZE_TANG2019 64u
#define CLOUD_NOISE_CURL_SIZE 128u

SKY_SHARED_BEGIN

// Push constants of the three bake shaders.
struct CloudNoiseParams {
  uvec4 size;  // x: N, texels along each axis; y: CLOUD_NOISE_MODEL_*;
               // z: CLOUD_NOISE_VOLUME_* (volume shader); w: unused
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::CloudNoiseParams) == 16, "layout of CloudNoiseParams");
#endif
#endif
