#include "engine/render/revisioned_image.h"

#include <utility>

namespace sky {

RevisionedImage::RevisionedImage(const Context& ctx, ImageDesc desc)
    : mCtx(ctx), mDesc(std::move(desc)) {
  mDesc.usage =
      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
}

ImageId RevisionedImage::addTo(FrameGraph& graph, uint64_t revision, uint32_t width,
                               uint32_t height,
                               const std::function<std::vector<float>()>& texels) {
  if (mRevision && *mRevision == revision) return graph.importImage(mImage);
  if (!mImage.image || mImage.image.desc().width != width ||
      mImage.image.desc().height != height) {
    ImageDesc desc = mDesc;
    desc.width = width;
    desc.height = height;
    checkImageDesc(mCtx, desc);
    // A new image holds nothing until its upload lands.
    mRevision.reset();
    mImage = {Image(mCtx, desc), {}};
  }
  const std::vector<float> pixels = texels();
  const ImageId uploaded =
      graph.upload(graph.importImage(mImage), pixels, "upload " + mDesc.name);
  graph.afterExecute([this, revision] {
    mRevision = revision;
    ++mUploads;
  });
  return uploaded;
}

}  // namespace sky
