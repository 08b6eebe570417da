#include "engine/gpu/image.h"

#include <utility>

#include "engine/gpu/context.h"
#include "engine/gpu/vk_check.h"

namespace sky {

uint32_t formatTexelSize(VkFormat f) {
  switch (f) {
    case VK_FORMAT_R8_UNORM:
      return 1;
    case VK_FORMAT_R16_SFLOAT:
      return 2;
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
      return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT:
      return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return 16;
    default:
      return 0;
  }
}

uint32_t formatChannelCount(VkFormat f) {
  switch (f) {
    case VK_FORMAT_R8_UNORM:
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R32_SFLOAT:
      return 1;
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT:
      return 2;
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return 4;
    default:
      return 0;
  }
}

const char* formatName(VkFormat f) {
  switch (f) {
    case VK_FORMAT_R8_UNORM:
      return "r8";
    case VK_FORMAT_R16_SFLOAT:
      return "r16f";
    case VK_FORMAT_R32_SFLOAT:
      return "r32f";
    case VK_FORMAT_R16G16_SFLOAT:
      return "rg16f";
    case VK_FORMAT_R32G32_SFLOAT:
      return "rg32f";
    case VK_FORMAT_R8G8B8A8_UNORM:
      return "rgba8";
    case VK_FORMAT_R8G8B8A8_SRGB:
      return "rgba8_srgb";
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      return "rgba16f";
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return "rgba32f";
    default:
      return "format?";
  }
}

void checkImageDesc(const Context& ctx, const ImageDesc& desc) {
  const auto& limits = ctx.properties().limits;
  uint32_t maxDim =
      desc.dim == ImageDim::Tex3D ? limits.maxImageDimension3D : limits.maxImageDimension2D;
  if (desc.width == 0 || desc.height == 0 || desc.depth == 0 || desc.width > maxDim ||
      desc.height > maxDim || desc.depth > maxDim)
    inputError("image '" + desc.name + "': " + std::to_string(desc.width) + "x" +
               std::to_string(desc.height) + "x" + std::to_string(desc.depth) +
               " is not possible on " + ctx.deviceName() + " (each side 1.." +
               std::to_string(maxDim) + ")");
  if (formatTexelSize(desc.format) == 0)
    internalError(std::string("image '") + desc.name + "': unsupported format");
}

VkImageCreateInfo imageCreateInfo(const ImageDesc& desc) {
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = desc.dim == ImageDim::Tex3D ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
  info.format = desc.format;
  info.extent = {desc.width, desc.height, desc.dim == ImageDim::Tex3D ? desc.depth : 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = desc.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  return info;
}

Image::Image(const Context& ctx, const ImageDesc& desc, bool allocate) : mCtx(&ctx), mDesc(desc) {
  checkImageDesc(ctx, desc);
  VkImageCreateInfo info = imageCreateInfo(desc);
  SKY_VK(vkCreateImage(ctx.device(), &info, nullptr, &mImage));
  ctx.setName(VK_OBJECT_TYPE_IMAGE, reinterpret_cast<uint64_t>(mImage), desc.name);
  if (!allocate) return;

  VkMemoryRequirements req = memoryRequirements();
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = ctx.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  try {
    mOwnedMemory = ctx.allocate(alloc, "image '" + desc.name + "'");
  } catch (...) {
    reset();
    throw;
  }
  SKY_VK(vkBindImageMemory(ctx.device(), mImage, mOwnedMemory, 0));
  createView();
}

Image Image::borrow(const Context& ctx, const ImageDesc& desc, VkImage image) {
  Image wrapped;
  wrapped.mCtx = &ctx;
  wrapped.mDesc = desc;
  wrapped.mImage = image;
  wrapped.mBorrowed = true;
  wrapped.createView();
  return wrapped;
}

Image& Image::operator=(Image&& o) noexcept {
  if (this != &o) {
    reset();
    mCtx = std::exchange(o.mCtx, nullptr);
    mDesc = o.mDesc;
    mImage = std::exchange(o.mImage, VK_NULL_HANDLE);
    mView = std::exchange(o.mView, VK_NULL_HANDLE);
    mOwnedMemory = std::exchange(o.mOwnedMemory, VK_NULL_HANDLE);
    mBorrowed = std::exchange(o.mBorrowed, false);
  }
  return *this;
}

Image::~Image() {
  reset();
}

void Image::reset() {
  if (!mCtx) return;
  VkDevice d = mCtx->device();
  if (mView) vkDestroyImageView(d, mView, nullptr);
  if (mImage && !mBorrowed) vkDestroyImage(d, mImage, nullptr);
  if (mOwnedMemory) vkFreeMemory(d, mOwnedMemory, nullptr);
  mView = VK_NULL_HANDLE;
  mImage = VK_NULL_HANDLE;
  mOwnedMemory = VK_NULL_HANDLE;
  mBorrowed = false;
}

VkMemoryRequirements Image::memoryRequirements() const {
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(mCtx->device(), mImage, &req);
  return req;
}

void Image::bindMemory(VkDeviceMemory memory, VkDeviceSize offset) {
  SKY_VK(vkBindImageMemory(mCtx->device(), mImage, memory, offset));
  createView();
}

void Image::createView() {
  VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  info.image = mImage;
  info.viewType = mDesc.dim == ImageDim::Tex3D ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D;
  info.format = mDesc.format;
  info.subresourceRange = range();
  // A depth-stencil image is sampled through its depth alone.
  if (mDesc.aspect & VK_IMAGE_ASPECT_DEPTH_BIT)
    info.subresourceRange.aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT;
  SKY_VK(vkCreateImageView(mCtx->device(), &info, nullptr, &mView));
}

}  // namespace sky
