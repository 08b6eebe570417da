#include "engine/render/cloud_field.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

#include "engine/clouds/cloud_math.h"
#include "passes/cloud_field/cloud_field.h"

namespace sky {

namespace {

glm::vec4 texel(const NoiseVolume& v, uint32_t x, uint32_t y, uint32_t z) {
  const size_t i = ((size_t(z) * v.size + y) * v.size + x) * 4;
  return glm::vec4(v.rgba[i], v.rgba[i + 1], v.rgba[i + 2], v.rgba[i + 3]) * (1.0f / 255.0f);
}

// The continuous texel coordinate of a normalised one (centres at (i + 0.5) / size), split
// into the two texels around it (repeat addressing) and the weight of the second.
struct Taps {
  uint32_t i0, i1;
  float t;
};
Taps taps(float u, uint32_t size) {
  const float x = u * float(size) - 0.5f;
  const float f = std::floor(x);
  const int64_t i = static_cast<int64_t>(f);
  const int64_t n = size;
  const uint32_t i0 = static_cast<uint32_t>(((i % n) + n) % n);
  return {i0, (i0 + 1) % size, x - f};
}

// The weather map as the GPU holds it: RGBA16F (engine/render/weather_textures.cpp).
WeatherMap asHalfFloats(WeatherMap map) {
  for (glm::vec4& t : map.texels)
    for (int c = 0; c < 4; ++c) t[c] = glm::unpackHalf1x16(glm::packHalf1x16(t[c]));
  return map;
}

}  // namespace

glm::vec4 sampleRepeat(const NoiseVolume& v, const glm::vec3& uvw) {
  if (v.size == 0) return glm::vec4(0.0f);
  const Taps x = taps(uvw.x, v.size), y = taps(uvw.y, v.size), z = taps(uvw.z, v.size);
  const auto plane = [&](uint32_t k) {
    return glm::mix(glm::mix(texel(v, x.i0, y.i0, k), texel(v, x.i1, y.i0, k), x.t),
                    glm::mix(texel(v, x.i0, y.i1, k), texel(v, x.i1, y.i1, k), x.t), y.t);
  };
  return glm::mix(plane(z.i0), plane(z.i1), z.t);
}

glm::vec4 sampleRepeat(const NoiseVolume& v, const glm::vec2& uv) {
  if (v.size == 0) return glm::vec4(0.0f);
  const Taps x = taps(uv.x, v.size), y = taps(uv.y, v.size);
  return glm::mix(glm::mix(texel(v, x.i0, y.i0, 0), texel(v, x.i1, y.i0, 0), x.t),
                  glm::mix(texel(v, x.i0, y.i1, 0), texel(v, x.i1, y.i1, 0), x.t), y.t);
}

CloudField::CloudField(CloudFieldInputs inputs) : mIn(std::move(inputs)) {
  mIn.weather = asHalfFloats(std::move(mIn.weather));
}

glm::vec4 CloudField::weatherAt(double latDeg, double lonDeg) const {
  glm::dvec2 uv;
  if (!regionUv(mIn.weather.region, latDeg, lonDeg, uv)) return glm::vec4(0.0f);
  return mIn.weather.sample(latDeg, lonDeg);
}

glm::dvec3 CloudField::enuOf(double latDeg, double lonDeg, double altitudeM) const {
  return geoPosition(mIn.camera, latDeg, lonDeg, altitudeM);
}

glm::dvec3 CloudField::latLonAltitudeOf(const glm::dvec3& enu) const {
  return latLonAltitude(mIn.camera, enu);
}

namespace {

// noiseKeep (cloud_field.glsl): how much of a noise channel whose cells are `cellM` wide a
// sample `footprintM` wide resolves.
float noiseKeep(float footprintM, float cellM) {
  const float t = std::clamp((footprintM / cellM - 0.125f) / (0.5f - 0.125f), 0.0f, 1.0f);
  return 1.0f - t * t * (3.0f - 2.0f * t);
}

// cloudOutlineCell (cloud_field.glsl): where the far field takes over the outline.
float cloudOutlineCell(float shapeCellM, float cumulus) {
  return shapeCellM / glm::mix(4.0f, 6.0f, cumulus);
}

// cloudFarChord (cloud_field.glsl): the far field's cloud chord in outline cells.
float cloudFarChord(float cumulus) {
  return glm::mix(float(CLOUD_FAR_MARKOV_CHORD), float(CLOUD_FAR_MARKOV_CHORD_CUMULUS), cumulus);
}

}  // namespace

// cloudSampleAtLla (shaders/common/cloud_field.glsl) with no coarse check and
// CLOUD_NOISE_ALL, for a sample `footprintM` wide: at 0 (full detail) every noiseKeep is 1
// and the far field's mean drops out.
CloudFieldSample CloudField::sample(const glm::dvec3& enu, float footprintM) const {
  using namespace clouds;
  CloudFieldSample s;
  if (!mIn.anyCover) return s;
  const shared::CloudParams& params = mIn.params;
  const glm::dvec3 lla = latLonAltitude(mIn.camera, enu);
  const float h = static_cast<float>(lla.z);
  const int layer = (h >= params.lowBaseM && h <= params.lowTopM)   ? 0
                    : (h >= params.midBaseM && h <= params.midTopM) ? 1
                                                                    : -1;
  if (layer < 0) return s;
  glm::dvec2 uv;
  if (!regionUv(mIn.weather.region, lla.x, lla.y, uv)) return s;  // Lu: only inside the region
  s.layer = layer;
  const glm::vec4 w = mIn.weather.sample(lla.x, lla.y);
  const float cover = layer == 0 ? w.r : w.g;
  const float type = w.b;
  s.cover = cover;
  s.type = type;
  const float base = layer == 0 ? params.lowBaseM : params.midBaseM;
  const float top = layer == 0 ? params.lowTopM : params.midTopM;
  const float f = (h - base) / (top - base);
  const glm::vec2 range = cloudTypeRange(layer, type);
  const float ph = cloudHeightFraction(f, range);
  if (cover <= 0.0f || ph < 0.0f || ph > 1.0f) return s;

  const float profileCover = mIn.calibrated ? 1.0f : cover;
  // The far field: the clouds' mean where the sample resolves none of their outline.
  const float shapeCellM = 1.0f / params.shapeRepeatsPerM;
  // How much of the cloud is shaped as cumulus (cloudCumulusWeight): outline, profile, billows.
  const float cumulus = mIn.cumulus ? cloudCumulusWeight(type) : 0.0f;
  const float keepOutline = noiseKeep(footprintM, cloudOutlineCell(shapeCellM, cumulus));
  const float profile =
      mIn.tang ? tangTypeGradient(ph, type) : cumulusGD(ph, profileCover, cumulus);
  float farDensity;
  if (mIn.calibrated) {
    const glm::vec2 far = farMeanDensity(layer, type, cover, ph);
    const float sigma = params.extinction * w.a;
    farDensity = sigma > 0.0f ? cloudFarExtinction(sigma * far.x, far.y,
                                                   cloudFarChord(cumulus) * shapeCellM / 4.0f) / sigma
                              : 0.0f;
  } else {
    const float cellTau = params.extinction * profile * w.a * CLOUD_FAR_DENSITY *
                          CLOUD_FAR_CHORD * shapeCellM / 4.0f;
    const float clump = cellTau > 1e-4f ? (1.0f - std::exp(-cellTau)) / cellTau : 1.0f;
    farDensity = cover * profile * CLOUD_FAR_DENSITY * clump;
  }
  s.density = farDensity * w.a;
  if (keepOutline <= 0.0f) return s;

  const glm::vec3 p(enu);
  const glm::vec3 offset = p.x * glm::vec3(params.geo.east) + p.y * glm::vec3(params.geo.north) +
                           p.z * glm::vec3(params.geo.up);
  const float roll = mIn.rolls ? cloudRollWeight(layer, type) : 0.0f;
  glm::vec4 shape(0.0f);
  if (roll < 1.0f)
    shape =
        sampleRepeat(mIn.shape, (glm::vec3(params.shapeOrigin) + offset) * params.shapeRepeatsPerM);
  if (roll > 0.0f) {
    const glm::vec3 axis(params.rollAxis);
    const glm::vec3 rolled = glm::vec3(params.rollOrigin) + offset -
                             params.rollCompression * glm::dot(offset, axis) * axis;
    shape = glm::mix(shape, sampleRepeat(mIn.shape, rolled * params.shapeRepeatsPerM), roll);
  }
  if (cumulus > 0.0f) {
    const glm::vec3 quarter =
        (glm::vec3(params.cumulusOrigin) + offset) *
        (params.shapeRepeatsPerM / static_cast<float>(CLOUD_CUMULUS_REPEAT_SHAPES));
    shape = cumulusShape(shape, sampleRepeat(mIn.shape, 2.0f * quarter),
                         sampleRepeat(mIn.shape, quarter), params.shapeMean.r, cumulus);
  }
  const float typeKeep = cloudTypeTexture(type);
  const glm::vec3 keepShape = typeKeep * glm::vec3(noiseKeep(footprintM, shapeCellM / 8.0f),
                                                   noiseKeep(footprintM, shapeCellM / 16.0f),
                                                   noiseKeep(footprintM, shapeCellM / 32.0f));
  const glm::vec3 gba =
      glm::mix(glm::vec3(params.shapeMean.g, params.shapeMean.b, params.shapeMean.a),
               glm::vec3(shape.g, shape.b, shape.a), keepShape);
  shape = glm::vec4(shape.r, gba);
  glm::vec3 dq = (glm::vec3(params.detailOrigin) + offset) * params.detailRepeatsPerM;
  const float detailCellM = static_cast<float>(cloudDetailCellM(
      1.0 / params.detailRepeatsPerM, mIn.tang ? CloudModel::Tang2019 : CloudModel::Lu2023));
  const glm::vec3 keepDetail = typeKeep * glm::vec3(noiseKeep(footprintM, detailCellM),
                                                    noiseKeep(footprintM, detailCellM / 2.0f),
                                                    noiseKeep(footprintM, detailCellM / 4.0f));
  const float threshold = coverageThreshold(layer, type, cover);
  const float nstex = luNStex(shape);
  const float gs = luGS(ph, profileCover);
  const float baseShape = mIn.tang ? tangBaseShape(shape, ph, type) : nstex * gs;
  const float shapeOnly =
      mIn.tang ? tangDensity(baseShape, 0.0f, cover, threshold) : luNSfinal(nstex, gs, threshold);
  s.density = glm::mix(farDensity, 0.0f, keepOutline) * w.a;
  if (shapeOnly <= 0.0f) return s;
  glm::vec3 detail(params.detailMean);
  if (keepDetail.x > 0.0f) {
    const glm::vec2 ground = glm::vec2(params.curlOrigin) + glm::vec2(p);
    const glm::vec3 curl =
        glm::vec3(sampleRepeat(mIn.curl, ground * params.curlRepeatsPerM)) * 2.0f - 1.0f;
    dq += curl * params.curlStrength * (1.0f - ph);
    detail = glm::mix(detail, glm::vec3(sampleRepeat(mIn.detail, dq)), keepDetail);
  }
  const float density = mIn.tang ? tangCloudDensity(shape, detail, ph, cover, type, threshold)
                                 : cumulusCloudDensity(shape, detail, ph, profileCover, threshold,
                                                       cumulus);
  const float sharpness = glm::mix(1.0f, params.edgeSharpness, keepShape.x);
  s.density = glm::mix(farDensity, cloudEdgeDensity(density, sharpness), keepOutline) * w.a;
  return s;
}

// farMeanDensity (cloud_field.glsl): the calibrated far mean and share in cloud, linear in
// height, cover and type.
glm::vec2 CloudField::farMeanDensity(int layer, float type, float cover, float ph) const {
  const auto entry = [&](int index) {
    const glm::vec4& pair = mIn.params.farMeanLut[index >> 1];
    return (index & 1) == 0 ? glm::vec2(pair.x, pair.y) : glm::vec2(pair.z, pair.w);
  };
  const float x = std::clamp(cover, 0.0f, 1.0f) * float(CLOUD_FAR_MEAN_COVERS - 1);
  const float y = std::clamp(type, 0.0f, 1.0f) * float(CLOUD_COVERAGE_TYPE_KEYS - 1);
  const float z = std::clamp(ph * float(CLOUD_FAR_MEAN_HEIGHTS) - 0.5f, 0.0f,
                             float(CLOUD_FAR_MEAN_HEIGHTS - 1));
  const int x0 = std::min(int(x), CLOUD_FAR_MEAN_COVERS - 2);
  const int y0 = std::min(int(y), CLOUD_COVERAGE_TYPE_KEYS - 2);
  const int z0 = std::min(int(z), CLOUD_FAR_MEAN_HEIGHTS - 2);
  const float fx = x - float(x0), fy = y - float(y0), fz = z - float(z0);
  glm::vec2 v[2];
  for (int t = 0; t < 2; ++t) {
    const int row = ((layer * CLOUD_COVERAGE_TYPE_KEYS + y0 + t) * CLOUD_FAR_MEAN_COVERS + x0) *
                        CLOUD_FAR_MEAN_HEIGHTS + z0;
    const int next = row + CLOUD_FAR_MEAN_HEIGHTS;  // the next cover entry
    v[t] = glm::mix(glm::mix(entry(row), entry(row + 1), fz),
                    glm::mix(entry(next), entry(next + 1), fz), fx);
  }
  return glm::mix(v[0], v[1], fy);
}

// coverageThreshold (cloud_field.glsl): the paper's 1 - cover, or the calibrated table's,
// bilinear in cover and type.
float CloudField::coverageThreshold(int layer, float type, float cover) const {
  if (!mIn.calibrated) return 1.0f - cover;
  const auto entry = [&](int index) { return mIn.params.coverageLut[index >> 2][index & 3]; };
  const float x = std::clamp(cover, 0.0f, 1.0f) * float(CLOUD_COVERAGE_LUT_SIZE - 1);
  const float y = std::clamp(type, 0.0f, 1.0f) * float(CLOUD_COVERAGE_TYPE_KEYS - 1);
  const int x0 = std::min(int(x), CLOUD_COVERAGE_LUT_SIZE - 2);
  const int y0 = std::min(int(y), CLOUD_COVERAGE_TYPE_KEYS - 2);
  const float fx = x - float(x0), fy = y - float(y0);
  const int base = layer * CLOUD_COVERAGE_TYPE_KEYS * CLOUD_COVERAGE_LUT_SIZE;
  const int r0 = base + y0 * CLOUD_COVERAGE_LUT_SIZE + x0;
  const int r1 = r0 + CLOUD_COVERAGE_LUT_SIZE;
  const float a = glm::mix(entry(r0), entry(r0 + 1), fx);
  const float b = glm::mix(entry(r1), entry(r1 + 1), fx);
  return glm::mix(a, b, fy);
}

double CloudField::extinction(const glm::dvec3& enu) const {
  return double(sample(enu).density) * double(mIn.params.extinction);
}

double CloudField::cloudOpticalDepth(const glm::dvec3& a, const glm::dvec3& b, double stepM) const {
  const double length = glm::length(b - a);
  if (!mIn.anyCover || length <= 0.0) return 0.0;
  const int64_t steps = std::max<int64_t>(1, static_cast<int64_t>(std::ceil(length / stepM)));
  const double ds = length / double(steps);
  const glm::dvec3 dir = (b - a) / length;
  double tau = 0.0;
  for (int64_t i = 0; i < steps; ++i) tau += extinction(a + dir * ((double(i) + 0.5) * ds)) * ds;
  return tau;
}

glm::dvec3 CloudField::airExtinction(const glm::dvec3& enu) const {
  // atmosphereMedium (atmosphere.glsl), altitude in km above the ground, per km.
  const shared::AtmosphereParams& p = mIn.air;
  const double h = std::max(latLonAltitude(mIn.camera, enu).z * 1e-3, 0.0);
  const double rayleigh = std::exp(-h / p.rayleighScattering.w);
  const double mie = std::exp(-h / p.mieScattering.w);
  const double ozone = std::max(0.0, 1.0 - std::abs(h - p.ozoneProfile.x) / p.ozoneProfile.y);
  return (glm::dvec3(p.rayleighScattering) * rayleigh + glm::dvec3(p.mieExtinction) * mie +
          glm::dvec3(p.ozoneAbsorption) * ozone) *
         1e-3;
}

glm::dvec3 CloudField::airOpticalDepth(const glm::dvec3& a, const glm::dvec3& b) const {
  const double length = glm::length(b - a);
  if (length <= 0.0) return glm::dvec3(0.0);
  // The medium falls off over kilometres (the Mie scale height is 1.2 km): 50 m steps, at
  // most 4096 of them.
  const int64_t steps =
      std::clamp<int64_t>(static_cast<int64_t>(std::ceil(length / 50.0)), 16, 4096);
  const double ds = length / double(steps);
  const glm::dvec3 dir = (b - a) / length;
  glm::dvec3 tau(0.0);
  for (int64_t i = 0; i < steps; ++i) tau += airExtinction(a + dir * ((double(i) + 0.5) * ds)) * ds;
  return tau;
}

std::optional<double> CloudField::distanceToOpticalDepth(const glm::dvec3& origin,
                                                         const glm::dvec3& dir, double maxM,
                                                         double tau, double stepM) const {
  if (!mIn.anyCover || maxM <= 0.0) return std::nullopt;
  const int64_t steps = std::max<int64_t>(1, static_cast<int64_t>(std::ceil(maxM / stepM)));
  const double ds = maxM / double(steps);
  double sum = 0.0;
  for (int64_t i = 0; i < steps; ++i) {
    const double e = extinction(origin + dir * ((double(i) + 0.5) * ds));
    if (sum + e * ds >= tau) return double(i) * ds + (tau - sum) / e;  // inside this step
    sum += e * ds;
  }
  return std::nullopt;
}

}  // namespace sky
