#include "engine/render/perception.h"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "engine/core/error.h"

namespace sky {

const char* perceptionLabelName(int label) {
  static const char* const kNames[PERCEPTION_LABEL_COUNT] = {
      "sky", "ground", "low_cloud", "mid_cloud", "high_cloud", "sun", "moon"};
  if (label < 0 || label >= PERCEPTION_LABEL_COUNT)
    internalError("perception: no label " + std::to_string(label));
  return kNames[label];
}

const char* perceptionTypeName(int type) {
  static const char* const kNames[PERCEPTION_TYPE_COUNT] = {
      "none", "stratus", "stratocumulus", "cumulus", "altostratus", "altocumulus", "cirrus"};
  if (type < 0 || type >= PERCEPTION_TYPE_COUNT)
    internalError("perception: no cloud type " + std::to_string(type));
  return kNames[type];
}

double cameraExtinction(const CloudField& field) {
  const glm::dvec3 origin(0.0);
  return field.airExtinction(origin).y + field.extinction(origin);
}

double cloudTransmittanceToward(const CloudField& field, const glm::dvec3& dir) {
  if (!field.anyCover() || dir.z < -0.035) return 1.0;  // 2 degrees below the horizon
  const shared::CloudParams& p = field.params();
  const double camera = field.latLonAltitudeOf(glm::dvec3(0.0)).z;
  const double top = std::max(p.lowTopM, p.midTopM);
  if (camera >= top) return 1.0;
  // Long enough to climb out of the layers (a low sun's line crosses them far away), and
  // no longer than the weather map's reach.
  const double rise = std::max(dir.z, 0.02);
  const double length = std::clamp((top - camera + 500.0) / rise, 1000.0, 200000.0);
  return std::exp(-field.cloudOpticalDepth(glm::dvec3(0.0), dir * length, 10.0));
}

glm::dvec3 airTransmittanceToward(const CloudField& field, const glm::dvec3& dir) {
  // The camera on the z axis of a sphere of the planet's radius (km, as the LUTs take it).
  const shared::AtmosphereParams& a = field.air();
  const double r = field.latLonAltitudeOf(glm::dvec3(0.0)).z * 1e-3 + a.radii.x;
  const double mu = dir.z, b = r * mu;
  const double ground = b * b - (r * r - double(a.radii.x) * a.radii.x);
  if (mu < 0.0 && ground >= 0.0) return glm::dvec3(0.0);
  const double top = -b + std::sqrt(std::max(b * b - (r * r - double(a.radii.y) * a.radii.y), 0.0));
  if (top <= 0.0) return glm::dvec3(1.0);
  return glm::exp(-field.airOpticalDepth(glm::dvec3(0.0), dir * (top * 1e3)));
}

PerceptionSummary perceptionSummary(const CloudField& field, const glm::dvec3& sun,
                                    const ImageLayer& labels) {
  PerceptionSummary s;
  const double beta = cameraExtinction(field);
  s.visibilityM = beta > 0.0 ? std::log(20.0) / beta : 1e9;
  s.sunCloud = cloudTransmittanceToward(field, sun);
  const glm::dvec3 air = airTransmittanceToward(field, sun);
  s.sunVisible = s.sunCloud * glm::dot(air, glm::dvec3(0.2126, 0.7152, 0.0722));
  const size_t c = labels.channels.size();
  if (c == 0 || labels.channels[0] != "label")
    internalError("perceptionSummary: the layer holds no labels");
  const size_t n = labels.pixels.size() / c;
  for (size_t i = 0; i < n; ++i) {
    const int label = static_cast<int>(std::lround(labels.pixels[i * c]));
    if (label >= 0 && label < PERCEPTION_LABEL_COUNT) s.labelShares[size_t(label)] += 1.0;
  }
  for (double& share : s.labelShares) share /= std::max<double>(double(n), 1.0);
  return s;
}

}  // namespace sky
