#include "passes/display_transform/display_transform.h"

#include <cmath>

#include "engine/color/display_lut.h"
#include "engine/core/error.h"

namespace sky {

DisplayTransformPass::DisplayTransformPass(const Context& ctx, ShaderCompiler& compiler)
    : mCtx(ctx),
      mPipeline(buildComputePipeline(ctx, compiler, "display_transform.comp", kName)),
      mSampler(ctx, SamplerWrap::Clamp) {}

DisplayTransformPass::Outputs DisplayTransformPass::addTo(FrameGraph& graph, const Inputs& in) {
  const DisplayTransformSettings& s = in.settings;
  if (!s.ocio) internalError("display_transform: no OCIO config");
  const std::string key = s.display + "\n" + s.view;
  if (key != mLutKey) {
    const DisplayLut lut = bakeDisplayLut(*s.ocio, s.display, s.view);
    if (!mLut.image) {
      ImageDesc d;
      d.name = "display_lut";
      d.about = "the OCIO view baked as a 3D LUT over log2 radiance (slices side by side)";
      d.dim = ImageDim::Tex3D;
      d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
      d.width = d.height = d.depth = DisplayLut::kSize;
      d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
      mLut.image = Image(mCtx, d);
    }
    // Uploaded in this frame's graph; the key is kept once the frame has run, so a frame that
    // fails uploads it again.
    mLutId = graph.upload(graph.importImage(mLut), lut.rgba, "upload display_lut");
    graph.afterExecute([this, key] { mLutKey = key; });
  } else {
    mLutId = graph.importImage(mLut);
  }
  GraphBuilder b = graph.addPass(kName, [this](PassContext& ctx) { execute(ctx); });
  return setup(b, in);
}

DisplayTransformPass::Outputs DisplayTransformPass::setup(GraphBuilder& b, const Inputs& in) {
  mParams = {};
  mParams.exposureScale = static_cast<float>(std::exp2(in.settings.exposureEv));
  mParams.nightLook = in.settings.nightLook ? 1u : 0u;
  mParams.lutMinLog2 = DisplayLut::kMinLog2;
  mParams.lutMaxLog2 = DisplayLut::kMaxLog2;
  mParams.lutSize = static_cast<float>(DisplayLut::kSize);
  mBeauty = b.read(in.beauty, Access::StorageReadCompute);
  b.read(mLutId, Access::SampledCompute);
  ImageDesc d;
  d.name = "display";
  d.about = "the display image: 8-bit codes through the OCIO view, as the PNG holds them";
  d.format = VK_FORMAT_R8G8B8A8_UNORM;
  d.width = in.width;
  d.height = in.height;
  mOutputs.display = b.write(b.create(d), Access::StorageWriteCompute);
  return mOutputs;
}

void DisplayTransformPass::execute(PassContext& ctx) const {
  const ImageDesc& d = ctx.image(mOutputs.display).desc();
  ctx.dispatch(mPipeline,
               {Binding::of(DISPLAY_TRANSFORM_BINDING_PARAMS, ctx.uniform(mParams)),
                Binding::of(DISPLAY_TRANSFORM_BINDING_BEAUTY, mBeauty),
                Binding::of(DISPLAY_TRANSFORM_BINDING_LUT, mLutId, &mSampler),
                Binding::of(DISPLAY_TRANSFORM_BINDING_DISPLAY, mOutputs.display)},
               mPipeline.groupsX(d.width), mPipeline.groupsY(d.height));
}

}  // namespace sky
