// Bindings and constants of passes/cloud_perception (shaders/cloud_perception.comp) and of the
// perception part of passes/atmosphere_composite: the ground truth of docs/outputs.md,
// "Perception layers". The march binds the cloud pass's own parameters and textures at the
// slots of volumetric_clouds_shared.h (cloud_field.glsl declares them) and adds its image.
#ifndef SKY_CLOUD_PERCEPTION_SHARED_H
#define SKY_CLOUD_PERCEPTION_SHARED_H
#include "shared_prelude.h"

// out: r the clouds' optical depth along the ray (to the ground or out of the shells, never
// stopped early), g the distance (m) at which it passes CLOUD_PERCEPTION_HIT_TAU (+inf where
// it never does), b the layer there (0 low, 1 mid, -1 none), a the map's type there.
#define CLOUD_PERCEPTION_BINDING_HIT 2

// The optical depth at which a ray is said to hit a cloud (clouds.distance, the labels): a
// tenth, where the cloud hides a tenth of what lies behind it (1 - e^-0.1 = 9.5 %), as the
// library's firstCloud() takes it by default.
#define CLOUD_PERCEPTION_HIT_TAU 0.1
// The longest step of the march, as optical depth at the density of the sample before: the
// hit is placed within a tenth of the hit depth, the optical depth within 2 %.
#define CLOUD_PERCEPTION_STEP_TAU 0.05
// A ray's samples at most (a grazing ray through 300 km of cloud at 2-20 m steps).
#define CLOUD_PERCEPTION_MAX_STEPS 8192

// The labels (docs/outputs.md), in the `label` layer as these numbers.
#define PERCEPTION_LABEL_SKY 0
#define PERCEPTION_LABEL_GROUND 1
#define PERCEPTION_LABEL_LOW_CLOUD 2
#define PERCEPTION_LABEL_MID_CLOUD 3
#define PERCEPTION_LABEL_HIGH_CLOUD 4
#define PERCEPTION_LABEL_SUN 5
#define PERCEPTION_LABEL_MOON 6
#define PERCEPTION_LABEL_COUNT 7

// The cloud types at a ray's first hit, in the `cloud_type` layer: the layer and the weather
// map's type channel there (nearest of 0 stratiform, 0.5 cellular, 1 convective), or the
// high-cloud layer.
#define PERCEPTION_TYPE_NONE 0
#define PERCEPTION_TYPE_STRATUS 1
#define PERCEPTION_TYPE_STRATOCUMULUS 2
#define PERCEPTION_TYPE_CUMULUS 3
#define PERCEPTION_TYPE_ALTOSTRATUS 4
#define PERCEPTION_TYPE_ALTOCUMULUS 5
#define PERCEPTION_TYPE_CIRRUS 6
#define PERCEPTION_TYPE_COUNT 7

#endif
