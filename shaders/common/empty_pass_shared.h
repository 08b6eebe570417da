// Bindings of the benchmark harness's yardstick (shaders/empty_pass.comp, benchmarks/skybench):
// a full-screen pass that only writes its image. What a pass costs beyond it is its own work.
#ifndef SKY_EMPTY_PASS_SHARED_H
#define SKY_EMPTY_PASS_SHARED_H
#include "shared_prelude.h"

// The group of every full-screen pass of the frame (atmosphere_composite, cloud_upsample, ...).
#define EMPTY_PASS_GROUP_X 8
#define EMPTY_PASS_GROUP_Y 8
#define EMPTY_PASS_BINDING_OUT 0

#endif
