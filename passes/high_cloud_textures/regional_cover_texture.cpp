#include "passes/high_cloud_textures/regional_cover_texture.h"

#include <string>

#include "engine/core/error.h"
#include "engine/gpu/image_upload.h"

namespace sky {

RegionalCoverTexture::RegionalCoverTexture(const Context& ctx)
    : mCtx(ctx), mSampler(ctx, SamplerWrap::Clamp, true) {}

ImageId RegionalCoverTexture::addTo(FrameGraph& graph, const WeatherMap& map, uint64_t revision) {
  if (!mRevision || *mRevision != revision) {
    // Forget the old revision first: if the upload fails, the next call tries again.
    mRevision.reset();
    if (map.width == 0 || map.height == 0 || map.coverHigh.size() != size_t(map.width) * map.height)
      internalError("regional high-cloud cover: the weather map has no high layer (" +
                    std::to_string(map.coverHigh.size()) + " values for " +
                    std::to_string(map.width) + "x" + std::to_string(map.height) + " texels)");
    if (!mCover.image || mCover.image.desc().width != map.width ||
        mCover.image.desc().height != map.height) {
      ImageDesc desc;
      desc.name = "high_cloud_regional_cover";
      desc.about = "the weather map's high cover, 0..1, over its region";
      desc.view = DebugView::Scalar;
      desc.format = VK_FORMAT_R16_SFLOAT;
      desc.width = map.width;
      desc.height = map.height;
      // Sampled by the draw, written by uploads, read back for debug outputs and tests.
      desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                   VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
      checkImageDesc(mCtx, desc);
      mCover = {Image(mCtx, desc), {}};
    }
    uploadImage(mCtx, mCover.image, mCover.state, map.coverHigh);
    ++mUploads;
    mRevision = revision;
  }
  return graph.importImage(mCover);
}

}  // namespace sky
