#include "passes/display_transform/display_transform.h"

#include <cmath>
#include <memory>

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
  ImageId lutId;
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
    lutId = graph.upload(graph.importImage(mLut), lut.rgba, "upload display_lut");
    graph.afterExecute([this, key] { mLutKey = key; });
  } else {
    lutId = graph.importImage(mLut);
  }
  auto data = std::make_shared<Data>();
  data->lut = lutId;
  GraphBuilder b = graph.addPass(kName, [this, data](PassContext& ctx) { execute(ctx, *data); });
  return setup(b, in, *data);
}

DisplayTransformPass::Outputs DisplayTransformPass::setup(GraphBuilder& b, const Inputs& in,
                                                          Data& d) {
  d.params = {};
  d.params.exposureScale = static_cast<float>(std::exp2(in.settings.exposureEv));
  d.params.nightLook = in.settings.nightLook ? 1u : 0u;
  d.params.lutMinLog2 = DisplayLut::kMinLog2;
  d.params.lutMaxLog2 = DisplayLut::kMaxLog2;
  d.params.lutSize = static_cast<float>(DisplayLut::kSize);
  d.beauty = b.read(in.beauty, Access::StorageReadCompute);
  b.read(d.lut, Access::SampledCompute);
  if (in.target.valid()) {
    d.outputs.display = b.write(in.target, Access::StorageWriteCompute);
    b.sideEffect();  // the window shows it, after the frame
    return d.outputs;
  }
  ImageDesc desc;
  desc.name = "display";
  desc.about = "the display image: 8-bit codes through the OCIO view, as the PNG holds them";
  desc.format = VK_FORMAT_R8G8B8A8_UNORM;
  desc.width = in.width;
  desc.height = in.height;
  d.outputs.display = b.write(b.create(desc), Access::StorageWriteCompute);
  return d.outputs;
}

void DisplayTransformPass::execute(PassContext& ctx, const Data& d) const {
  const ImageDesc& size = ctx.image(d.outputs.display).desc();
  ctx.dispatch(mPipeline,
               {Binding::of(DISPLAY_TRANSFORM_BINDING_PARAMS, ctx.uniform(d.params)),
                Binding::of(DISPLAY_TRANSFORM_BINDING_BEAUTY, d.beauty),
                Binding::of(DISPLAY_TRANSFORM_BINDING_LUT, d.lut, &mSampler),
                Binding::of(DISPLAY_TRANSFORM_BINDING_DISPLAY, d.outputs.display)},
               mPipeline.groupsX(size.width), mPipeline.groupsY(size.height));
}

}  // namespace sky
