#include "engine/render/cloud_reuse.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "engine/core/error.h"
#include "engine/weather/geo.h"
#include "passes/cloud_field/cloud_field.h"

namespace sky {
namespace {

// A history older than this, or a camera moved further, is a cut: the clouds have changed
// too much for reprojection (a time-lapse's steps, a jump).
constexpr double kHistoryMaxGapS = 60.0;
constexpr double kHistoryMaxMoveM = 5000.0;

}  // namespace

Scene withoutPose(const Scene& scene) {
  Scene s = scene;
  s.camera.heading = s.camera.pitch = s.camera.roll = 0.0;
  s.camera.latitude = s.camera.longitude = s.camera.altitudeM = 0.0;
  s.time.start = IsoTime{};
  s.time.end.reset();
  s.time.stepSeconds = 0.0;
  return s;
}

uint64_t SettingsRevisions::of(const Scene& scene) {
  Scene settings = withoutPose(scene);
  auto known = std::find_if(mKnown.begin(), mKnown.end(),
                            [&](const auto& k) { return k.first == settings; });
  std::pair<Scene, uint64_t> entry;
  if (known != mKnown.end()) {
    entry = std::move(*known);
    mKnown.erase(known);
  } else {
    entry = {std::move(settings), mNext++};
    if (mKnown.size() >= kRemembered) mKnown.pop_back();
  }
  mKnown.insert(mKnown.begin(), std::move(entry));
  return mKnown.front().second;
}

CloudReuse::CloudReuse(const Context& ctx, ShaderCompiler& compiler)
    : mCtx(ctx), mTemporal(ctx, compiler), mSampler(ctx, SamplerWrap::Clamp) {}

CloudReuse::Step CloudReuse::step(const Scene& scene, const IsoTime& time,
                                  const shared::ViewState& view, uint64_t mapRevision,
                                  uint64_t cutFrame) {
  ImageDesc desc;
  desc.width = view.size.x;
  desc.height = view.size.y;
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.name = "clouds";
  desc.about = "the clouds after temporal reuse: premultiplied radiance (RGB), opacity (A)";
  mClouds.ensure(mCtx, desc);
  desc.format = VK_FORMAT_R32G32_SFLOAT;
  desc.name = "clouds_depth";
  desc.about = "the clouds' distance (m, R) and shell entry (m, G) after temporal reuse";
  desc.view = DebugView::Depth;
  desc.channels = "depth,shell_entry";
  mDepth.ensure(mCtx, desc);

  Held next;
  next.settings = mSettings.of(scene);
  next.view = view;
  next.latDeg = scene.camera.latitude;
  next.lonDeg = scene.camera.longitude;
  next.altitudeM = scene.camera.altitudeM;
  next.time = time;
  next.mapRevision = mapRevision;

  const Held& last = mHeld;
  const glm::dvec3 here = ecefFromLatLonAltitude(next.latDeg, next.lonDeg, next.altitudeM);
  const glm::dvec3 there = ecefFromLatLonAltitude(last.latDeg, last.lonDeg, last.altitudeM);
  const double gap = time.secondsSince(last.time);
  Step step;
  step.valid = mClouds.valid() && mDepth.valid() && next.settings == last.settings &&
               next.mapRevision == last.mapRevision && std::abs(gap) <= kHistoryMaxGapS &&
               glm::length(here - there) <= kHistoryMaxMoveM;
  next.frame = step.valid ? last.frame + 1 : cutFrame;
  step.frame = next.frame;
  // A cut marches every pixel, so the first frame of a sequence is the still.
  if (step.valid) {
    step.block = static_cast<uint32_t>(scene.clouds.temporal.block);
    step.offset = cloudMarchOffset(step.block, next.frame - 1);
    const glm::dmat3 enuHere = enuToEcefRotation(next.latDeg, next.lonDeg);
    const glm::dmat3 enuThere = enuToEcefRotation(last.latDeg, last.lonDeg);
    step.motion.previousPosition = glm::vec3(glm::transpose(enuHere) * (there - here));
    step.motion.toPrevious = glm::mat3(glm::transpose(enuThere) * enuHere);
    step.motion.windShift = glm::vec3(glm::vec2(cloudWindDriftM(scene.clouds, gap)), 0.0f);
  }
  mNext = std::move(next);
  return step;
}

CloudTemporalPass::Outputs CloudReuse::addTo(FrameGraph& graph, const Step& step, ImageId marched,
                                             ImageId marchedDepth, const Shells& shells) {
  if (!mNext) internalError("cloud reuse: a temporal pass without its step");
  CloudTemporalPass::Inputs t;
  t.params = cloudTemporalParams(mNext->view, mHeld.view, step.motion, step.block, step.offset,
                                 step.valid, shells.planetRadiusM, shells.cameraAltitudeM,
                                 shells.shellBaseM, shells.shellTopM);
  t.marched = marched;
  t.marchedDepth = marchedDepth;
  t.clouds = graph.importHistory(mClouds);
  t.depth = graph.importHistory(mDepth);
  t.historySampler = &mSampler;
  return graph.add(mTemporal, t);
}

void CloudReuse::commit() {
  if (!mNext) return;
  mHeld = std::move(*mNext);
  mNext.reset();
}

void CloudReuse::invalidate() {
  mClouds.invalidate();
  mDepth.invalidate();
  mNext.reset();
}

}  // namespace sky
