#pragma once
// 2D and 3D images with one view. Either owns its memory (standalone) or is bound by the
// frame graph into a shared memory slot (transient images that alias). Move-only.
#include <cstdint>
#include <string>

#include <vulkan/vulkan.h>

namespace sky {

class Context;

enum class ImageDim : uint8_t { Tex2D, Tex3D };

// How a debug view shows an image. Every frame-graph image can be requested by its name
// (skyrender --debug-output, skyview's debug view); the pass that creates it says here how
// to look at it, so a new pass's images are viewable with nothing added anywhere else.
enum class DebugView : uint8_t {
  Color,    // radiance or colour data: exposed to its own brightness
  Scalar,   // the first channel in false colour, with a legend of its range
  Normals,  // xyz in -1..1 shown as 0..1
  Depth,    // a distance (m) in the first channel: near bright, far dark, none black
  Heat,     // a count per pixel (samples, steps) in false colour, with a legend
};

struct ImageDesc {
  std::string name;  // for debug output: the name the image is requested by, unique in a frame
  ImageDim dim = ImageDim::Tex2D;
  VkFormat format = VK_FORMAT_R16G16B16A16_SFLOAT;
  uint32_t width = 1, height = 1, depth = 1;
  VkImageUsageFlags usage = 0;  // the frame graph derives this from declared accesses
  // For debug output only (see DebugView): how to show it, its channels' names in an EXR
  // ("view,light": the first channels only; empty: R, G, B, A) and one line on what it holds.
  DebugView view = DebugView::Color;
  std::string channels;
  std::string about;
  // The image's aspects, which its barriers cover: colour, or a host's depth image (depth, and
  // stencil for a format that has it; its view shows the depth alone).
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
};

// Bytes per texel of the formats the engine uses; 0 for anything else.
uint32_t formatTexelSize(VkFormat format);
uint32_t formatChannelCount(VkFormat format);
const char* formatName(VkFormat format);
// Input error naming the image when `desc` is impossible on this device (size limits).
void checkImageDesc(const Context& ctx, const ImageDesc& desc);
// The create-info for `desc` (also used to ask memory requirements before creating).
VkImageCreateInfo imageCreateInfo(const ImageDesc& desc);

class Image {
public:
  Image() = default;
  // Creates the image; with `allocate` it also gets dedicated device-local memory and a view.
  Image(const Context& ctx, const ImageDesc& desc, bool allocate = true);
  // Wraps `image`, which the host owns (skylayers::Sky::record): makes a view of it (its depth
  // alone for a depth image) and destroys only that view. `desc` must say what the image is.
  static Image borrow(const Context& ctx, const ImageDesc& desc, VkImage image);
  ~Image();
  Image(Image&& o) noexcept { *this = std::move(o); }
  Image& operator=(Image&& o) noexcept;
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;

  // Binds shared memory (frame-graph aliasing) and creates the view. Only for allocate=false.
  void bindMemory(VkDeviceMemory memory, VkDeviceSize offset);
  VkMemoryRequirements memoryRequirements() const;

  const ImageDesc& desc() const { return mDesc; }
  VkImage image() const { return mImage; }
  VkImageView view() const { return mView; }
  // Every aspect: what a barrier covers.
  VkImageSubresourceRange range() const { return {mDesc.aspect, 0, 1, 0, 1}; }
  explicit operator bool() const { return mImage != VK_NULL_HANDLE; }

private:
  void createView();
  void reset();

  const Context* mCtx = nullptr;
  ImageDesc mDesc;
  VkImage mImage = VK_NULL_HANDLE;
  VkImageView mView = VK_NULL_HANDLE;
  VkDeviceMemory mOwnedMemory = VK_NULL_HANDLE;
  bool mBorrowed = false;  // mImage is the host's: not destroyed here
};

}  // namespace sky
