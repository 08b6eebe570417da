#pragma once
// The perception layers' numbers for the whole frame (docs/outputs.md, "Perception layers"):
// the visibility at the camera, how much of the sun reaches it, and the share of each label.
// From the CPU twin of the clouds' density field (engine/render/cloud_field.h), the field the
// library's queries read, so a frame's numbers and a query's agree.
#include <array>

#include <glm/vec3.hpp>

#include "engine/io/exr.h"
#include "engine/render/cloud_field.h"
#include "shaders/common/cloud_perception_shared.h"

namespace sky {

struct PerceptionSummary {
  // The meteorological optical range at the camera: where a black object's contrast against
  // the horizon falls to 5 %, ln 20 / beta (about 3 / beta) with beta the extinction there
  // (the air's at 550 nm, the green channel, plus the cloud's when the camera is in one), m.
  double visibilityM = 0.0;
  // The share of the sun's light that reaches the camera through the clouds and the air
  // (Rec. 709 luminance of the air's transmittance), 0 with the sun below the horizon; and
  // the clouds' part of it alone.
  double sunVisible = 0.0;
  double sunCloud = 1.0;
  // The share of the frame's pixels with each label (PERCEPTION_LABEL_*), summing to 1.
  std::array<double, PERCEPTION_LABEL_COUNT> labelShares{};
};

// The names of the labels and of the cloud types, by their numbers in the layers.
const char* perceptionLabelName(int label);
const char* perceptionTypeName(int type);

// Extinction (1/m) at the camera: the air's at 550 nm plus the cloud's.
double cameraExtinction(const CloudField& field);
// The share of the light from unit direction `dir` (ENU) that reaches the camera through the
// clouds alone: the optical depth along the line up past the top of the highest layer.
double cloudTransmittanceToward(const CloudField& field, const glm::dvec3& dir);
// The air's transmittance (R, G, B) from the camera to the top of the atmosphere along `dir`;
// 0 where the ray meets the ground.
glm::dvec3 airTransmittanceToward(const CloudField& field, const glm::dvec3& dir);

// The frame's numbers: `sun` is the sun's direction (ENU), `labels` the frame's layer ""
// of label and cloud_type (appendPerceptionLayers).
PerceptionSummary perceptionSummary(const CloudField& field, const glm::dvec3& sun,
                                    const ImageLayer& labels);

}  // namespace sky
