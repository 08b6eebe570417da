#include "engine/graph/frame_graph.h"

#include <algorithm>
#include <cstring>
#include <memory>
#include <utility>

#include "engine/core/error.h"
#include "engine/gpu/texel_convert.h"
#include "engine/graph/graph_runtime.h"
#include "engine/graph/pass_context.h"

namespace sky {
namespace {

const char* kindName(ResourceKind k) {
  return k == ResourceKind::Image ? "image" : "buffer";
}

}  // namespace

FrameGraph::FrameGraph(GraphRuntime& runtime, GraphUse use) : mRuntime(&runtime), mUse(use) {}
FrameGraph::FrameGraph() = default;
FrameGraph::~FrameGraph() = default;

uint32_t FrameGraph::addResource(ResourceNode node, ResourceRecord record) {
  if (mCompiled) internalError("frame graph: resource '" + node.name + "' added after compile()");
  mDesc.resources.push_back(std::move(node));
  mResources.push_back(record);
  return static_cast<uint32_t>(mDesc.resources.size() - 1);
}

ImageId FrameGraph::importImage(PersistentImage& image) {
  if (!image.image) internalError("frame graph: importing an empty image");
  const ImageDesc& d = image.image.desc();
  ResourceNode node{.name = d.name,
                    .kind = ResourceKind::Image,
                    .imported = true,
                    .image = d,
                    .initial = image.state};
  return {addResource(std::move(node), {&image, nullptr, -1}), 0};
}

ImageId FrameGraph::importExternal(PersistentImage& image, VkImageLayout hostLayout) {
  // Whatever the host did to it before may be any access at any stage.
  image.state = {hostLayout, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT};
  const ImageId id = importImage(image);
  mExternals.push_back({id.id, hostLayout});
  return id;
}

void HistoryImage::ensure(const Context& ctx, const ImageDesc& wanted) {
  ImageDesc desc = wanted;
  desc.usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  const ImageDesc& have = mImages[0].image.desc();
  if (mImages[0].image && have.format == desc.format && have.width == desc.width &&
      have.height == desc.height && have.depth == desc.depth && have.dim == desc.dim)
    return;
  for (int i = 0; i < 2; ++i) {
    ImageDesc d = desc;
    d.name = desc.name + (i == 0 ? "_history_a" : "_history_b");
    mImages[i] = PersistentImage{Image(ctx, d), {}};
  }
  mName = desc.name;
  mWrite = 0;
  mValid = false;
}

HistoryIds FrameGraph::importHistory(HistoryImage& history) {
  if (!history.mImages[0].image) internalError("frame graph: importing a history never ensured");
  if (std::find(mHistories.begin(), mHistories.end(), &history) != mHistories.end())
    internalError("frame graph: a history imported twice into one frame");
  mHistories.push_back(&history);
  const HistoryIds ids{importImage(history.mImages[1 - history.mWrite]),
                       importImage(history.mImages[history.mWrite]), history.mValid};
  // Named by their part in this frame, not by which of the two images they are, so a debug
  // view asks for the same name every frame.
  mDesc.resources[ids.previous.id].name = history.mName + "_history_previous";
  mDesc.resources[ids.next.id].name = history.mName + "_history";
  return ids;
}

BufferId FrameGraph::importBuffer(PersistentBuffer& buffer) {
  if (!buffer.buffer) internalError("frame graph: importing an empty buffer");
  const BufferDesc& d = buffer.buffer.desc();
  ResourceNode node{.name = d.name,
                    .kind = ResourceKind::Buffer,
                    .imported = true,
                    .buffer = d,
                    .initial = buffer.state};
  return {addResource(std::move(node), {nullptr, &buffer, -1}), 0};
}

namespace {

// The image an upload fills, and its texel count (layers of a 3D image included). Internal
// error for a handle that is not an image.
std::pair<const ImageDesc*, size_t> uploadTarget(const GraphDesc& desc, ImageId image,
                                                 const std::string& name) {
  if (image.id >= desc.resources.size() || desc.resources[image.id].kind != ResourceKind::Image)
    internalError("frame graph: upload '" + name + "' to an invalid image handle");
  const ImageDesc& d = desc.resources[image.id].image;
  const uint32_t depth = d.dim == ImageDim::Tex3D ? d.depth : 1;
  return {&d, size_t(d.width) * d.height * depth};
}

}  // namespace

ImageId FrameGraph::upload(ImageId image, std::span<const float> pixels, std::string name) {
  const auto [d, texels] = uploadTarget(mDesc, image, name);
  if (pixels.size() != texels * formatChannelCount(d->format))
    internalError("upload to image '" + d->name + "': " + std::to_string(pixels.size()) +
                  " values for " + std::to_string(texels) + " texels of " + formatName(d->format));
  return uploadTexels(image, floatsToTexels(d->format, pixels), std::move(name));
}

ImageId FrameGraph::uploadTexels(ImageId image, std::span<const uint8_t> bytes, std::string name) {
  const auto [target, texels] = uploadTarget(mDesc, image, name);
  const ImageDesc& d = *target;
  if (bytes.size() != texels * formatTexelSize(d.format))
    internalError("upload to image '" + d.name + "': " + std::to_string(bytes.size()) +
                  " bytes for " + std::to_string(texels) + " texels of " + formatName(d.format));
  Buffer* staging = nullptr;
  if (mRuntime) {  // a graph without a GPU records the pass and never runs it
    mStaging.push_back(std::make_unique<Buffer>(
        mRuntime->gpu(), BufferDesc{"upload " + d.name, bytes.size(),
                                    VK_BUFFER_USAGE_TRANSFER_SRC_BIT, BufferMemory::HostVisible}));
    staging = mStaging.back().get();
    // Host-coherent memory: the writes are visible to the device at submit without a flush.
    std::memcpy(staging->mapped(), bytes.data(), bytes.size());
  }
  const VkExtent3D extent{d.width, d.height, d.dim == ImageDim::Tex3D ? d.depth : 1u};
  // The graph's barriers put the image in TRANSFER_DST_OPTIMAL before the copy and make it
  // visible to whatever reads it next, in this frame or a later one (its ResourceState).
  GraphBuilder b = addPass(std::move(name), [staging, extent, image](PassContext& ctx) {
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = extent;
    vkCmdCopyBufferToImage(ctx.cmd(), staging->buffer(), ctx.image(image).image(),
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  });
  const ImageId written = b.write(image, Access::TransferDst);
  b.sideEffect();
  return written;
}

FrameResult uploadNow(GraphRuntime& runtime, std::initializer_list<ImageFill> fills) {
  FrameGraph graph(runtime, GraphUse::Bake);
  for (const ImageFill& f : fills) {
    const ImageId image = graph.importImage(*f.image);
    const std::string name = "upload " + f.image->image.desc().name;
    (void)(f.texels.empty() ? graph.upload(image, f.pixels, name)
                            : graph.uploadTexels(image, f.texels, name));
  }
  return graph.execute();
}

void FrameGraph::afterExecute(std::function<void()> done) {
  mAfterExecute.push_back(std::move(done));
}

GraphBuilder FrameGraph::addPass(std::string name, std::function<void(PassContext&)> execute) {
  if (mCompiled) internalError("frame graph: pass '" + name + "' added after compile()");
  mDesc.passes.push_back({std::move(name), {}, false});
  mPasses.push_back({std::move(execute)});
  return GraphBuilder(*this, static_cast<uint32_t>(mDesc.passes.size() - 1));
}

uint32_t FrameGraph::declare(uint32_t pass, uint32_t resource, uint32_t version, Access access,
                             ResourceKind kind) {
  const std::string& passName = mDesc.passes[pass].name;
  if (resource >= mDesc.resources.size())
    internalError("pass '" + passName + "' uses an invalid " + kindName(kind) + " handle");
  ResourceNode& res = mDesc.resources[resource];
  if (res.kind != kind)
    internalError("pass '" + passName + "': '" + res.name + "' is not a " + kindName(kind));
  const uint32_t current = res.versions - 1;
  if (version != current) {
    int writer = mResources[resource].lastWriter;
    internalError(
        "pass '" + passName + "' uses a stale handle to '" + res.name + "' (version " +
        std::to_string(version) + "; " +
        (writer >= 0 ? "pass '" + mDesc.passes[static_cast<size_t>(writer)].name + "'" : "a pass") +
        " wrote version " + std::to_string(current) + " since)");
  }
  const AccessInfo& info = accessInfo(access);
  if (kind == ResourceKind::Image && info.imageUsage == 0)
    internalError("pass '" + passName + "': access '" + info.name + "' is not valid for image '" +
                  res.name + "'");
  if (kind == ResourceKind::Buffer && info.bufferUsage == 0)
    internalError("pass '" + passName + "': access '" + info.name + "' is not valid for buffer '" +
                  res.name + "'");
  if (!res.imported && version == 0 && access != Access::StorageWriteCompute &&
      access != Access::TransferDst)
    internalError("pass '" + passName + "' reads '" + res.name + "' before any pass wrote it");
  for (const ResourceAccess& a : mDesc.passes[pass].accesses)
    if (a.resource == resource)
      internalError("pass '" + passName + "' declares '" + res.name +
                    "' twice; use one access kind");
  if (res.imported) {
    VkFlags have = kind == ResourceKind::Image ? res.image.usage : res.buffer.usage;
    VkFlags need = kind == ResourceKind::Image ? info.imageUsage : info.bufferUsage;
    if ((have & need) != need)
      internalError("pass '" + passName + "': imported '" + res.name +
                    "' was created without the usage '" + info.name + "' needs");
  } else if (kind == ResourceKind::Image) {
    res.image.usage |= info.imageUsage;  // transient usage is exactly what the passes declare
  } else {
    res.buffer.usage |= info.bufferUsage;
  }
  mDesc.passes[pass].accesses.push_back({resource, version, access});
  if (info.write) {
    ++res.versions;
    mResources[resource].lastWriter = static_cast<int>(pass);
    return version + 1;
  }
  return version;
}

ImageId GraphBuilder::create(const ImageDesc& desc) {
  ResourceNode node;
  node.name = mGraph.mNamePrefix + desc.name;
  node.kind = ResourceKind::Image;
  node.image = desc;
  node.image.name = node.name;
  node.image.usage = 0;
  return {mGraph.addResource(std::move(node), {}), 0};
}

BufferId GraphBuilder::create(const BufferDesc& desc) {
  if (desc.memory != BufferMemory::Device)
    internalError("transient buffer '" + desc.name +
                  "' must be device memory; use uniform() for uploads");
  ResourceNode node;
  node.name = mGraph.mNamePrefix + desc.name;
  node.kind = ResourceKind::Buffer;
  node.buffer = desc;
  node.buffer.name = node.name;
  node.buffer.usage = 0;
  return {mGraph.addResource(std::move(node), {}), 0};
}

ImageId GraphBuilder::read(ImageId h, Access a) {
  if (accessInfo(a).write)
    internalError("read() with write access '" + std::string(accessInfo(a).name) + "'");
  return {h.id, mGraph.declare(mPass, h.id, h.version, a, ResourceKind::Image)};
}
BufferId GraphBuilder::read(BufferId h, Access a) {
  if (accessInfo(a).write)
    internalError("read() with write access '" + std::string(accessInfo(a).name) + "'");
  return {h.id, mGraph.declare(mPass, h.id, h.version, a, ResourceKind::Buffer)};
}
ImageId GraphBuilder::write(ImageId h, Access a) {
  if (!accessInfo(a).write)
    internalError("write() with read access '" + std::string(accessInfo(a).name) + "'");
  return {h.id, mGraph.declare(mPass, h.id, h.version, a, ResourceKind::Image)};
}
BufferId GraphBuilder::write(BufferId h, Access a) {
  if (!accessInfo(a).write)
    internalError("write() with read access '" + std::string(accessInfo(a).name) + "'");
  return {h.id, mGraph.declare(mPass, h.id, h.version, a, ResourceKind::Buffer)};
}
void GraphBuilder::sideEffect() {
  mGraph.mDesc.passes[mPass].sideEffect = true;
}

OutputId FrameGraph::requestOutput(ImageId image, std::string label) {
  if (mCompiled) internalError("frame graph: output '" + label + "' requested after compile()");
  if (image.id >= mDesc.resources.size() || mDesc.resources[image.id].kind != ResourceKind::Image)
    internalError("frame graph: output '" + label + "' is not an image");
  for (const auto& o : mOutputs)
    if (o.label == label) internalError("frame graph: output '" + label + "' requested twice");
  mOutputs.push_back({image.id, image.version, std::move(label)});
  return {static_cast<uint32_t>(mOutputs.size() - 1)};
}

OutputId FrameGraph::requestOutput(const GraphImage& image, std::string label) {
  if (image.latest.valid()) return requestOutput(image.latest, std::move(label));
  if (mCompiled) internalError("frame graph: output '" + label + "' requested after compile()");
  if (!image.buffer.valid() || mDesc.resources[image.buffer.id].buffer.image.width == 0)
    internalError("frame graph: output '" + label + "' is not an image");
  for (const auto& o : mOutputs)
    if (o.label == label) internalError("frame graph: output '" + label + "' requested twice");
  mOutputs.push_back({image.buffer.id, image.buffer.version, std::move(label)});
  return {static_cast<uint32_t>(mOutputs.size() - 1)};
}

std::vector<GraphImage> FrameGraph::images() const {
  std::vector<GraphImage> out;
  for (uint32_t r = 0; r < mDesc.resources.size(); ++r) {
    const ResourceNode& node = mDesc.resources[r];
    const bool image = node.kind == ResourceKind::Image;
    if (!image && node.buffer.image.width == 0) continue;
    const int writer = mResources[r].lastWriter;
    GraphImage g;
    g.name = node.name;
    g.writer = writer >= 0 ? mDesc.passes[static_cast<size_t>(writer)].name : std::string();
    if (image) {
      g.latest = ImageId{r, node.versions - 1};
      g.desc = node.image;
    } else {
      const BufferImage& b = node.buffer.image;
      g.buffer = BufferId{r, node.versions - 1};
      g.desc.name = node.name;
      g.desc.format = VK_FORMAT_R32_SFLOAT;
      g.desc.width = b.width;
      g.desc.height = b.height;
      g.desc.view = b.view;
      g.desc.about = b.about;
    }
    out.push_back(std::move(g));
  }
  return out;
}

GraphImage FrameGraph::image(std::string_view name) const {
  std::vector<GraphImage> all = images();
  for (GraphImage& g : all)
    if (g.name == name) return g;
  std::vector<std::string> known;
  for (const GraphImage& g : all) known.push_back(g.name);
  throw UnknownImageName(std::string(name), std::move(known));
}

namespace {

std::string knownList(const std::vector<std::string>& known) {
  std::string s;
  for (const std::string& k : known) s += (s.empty() ? "" : ", ") + k;
  return s;
}

}  // namespace

UnknownImageName::UnknownImageName(std::string name, std::vector<std::string> known)
    : Error(ErrorKind::BadInput,
            "no image named '" + name + "' in this frame (it has: " + knownList(known) + ")"),
      mName(std::move(name)),
      mKnown(std::move(known)) {}

const ReadbackImage& FrameResult::output(OutputId id) const {
  if (!id.valid() || id.index >= outputs.size())
    internalError("frame result has no output " + std::to_string(id.index));
  return outputs[id.index];
}

ReadbackImage& FrameResult::output(OutputId id) {
  if (!id.valid() || id.index >= outputs.size())
    internalError("frame result has no output " + std::to_string(id.index));
  return outputs[id.index];
}

const ReadbackImage& FrameResult::output(std::string_view label) const {
  for (const ReadbackImage& o : outputs)
    if (o.label == label) return o;
  internalError("frame result has no output '" + std::string(label) + "'");
}

}  // namespace sky
