// FrameGraph::compile and FrameGraph::execute: the GPU side of the frame graph.
#include <algorithm>
#include <chrono>
#include <set>

#include "engine/core/error.h"
#include "engine/gpu/barriers.h"
#include "engine/gpu/context.h"
#include "engine/gpu/texel_convert.h"
#include "engine/gpu/timestamp_pool.h"
#include "engine/gpu/vk_check.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/graph/pass_context.h"

namespace sky {
namespace {

VkDeviceSize texelBytes(const ImageDesc& d) {
  return VkDeviceSize(d.width) * d.height * (d.dim == ImageDim::Tex3D ? d.depth : 1) *
         formatTexelSize(d.format);
}

MemoryRequirement requirementOf(const Context& ctx, const ResourceNode& r) {
  VkMemoryRequirements2 req{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
  if (r.kind == ResourceKind::Image) {
    checkImageDesc(ctx, r.image);
    VkImageCreateInfo info = imageCreateInfo(r.image);
    VkDeviceImageMemoryRequirements q{VK_STRUCTURE_TYPE_DEVICE_IMAGE_MEMORY_REQUIREMENTS};
    q.pCreateInfo = &info;
    vkGetDeviceImageMemoryRequirements(ctx.device(), &q, &req);
  } else {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = r.buffer.size;
    info.usage = r.buffer.usage;
    VkDeviceBufferMemoryRequirements q{VK_STRUCTURE_TYPE_DEVICE_BUFFER_MEMORY_REQUIREMENTS};
    q.pCreateInfo = &info;
    vkGetDeviceBufferMemoryRequirements(ctx.device(), &q, &req);
  }
  return {req.memoryRequirements.size, req.memoryRequirements.alignment,
          req.memoryRequirements.memoryTypeBits};
}

// Without a device: the texel bytes, as if every resource could share every slot.
MemoryRequirement estimatedRequirement(const ResourceNode& r) {
  return {r.kind == ResourceKind::Image ? texelBytes(r.image) : r.buffer.size, 256, ~0u};
}

}  // namespace

const CompiledGraph& FrameGraph::compile() {
  if (mCompiled) return *mCompiled;
  if (!mOutputs.empty()) {
    // Readback is an ordinary side-effect pass, so its barriers come from the same rules.
    GraphBuilder b = addPass("readback", [this](PassContext& ctx) {
      for (size_t i = 0; i < mOutputs.size(); ++i) {
        const Output& o = mOutputs[i];
        const VkBuffer target = mRuntime->readback(mUse)[i].buffer();
        if (mDesc.resources[o.resource].kind == ResourceKind::Buffer) {
          // A buffer that holds an image: its texels, from where they start.
          const BufferImage& layout = mDesc.resources[o.resource].buffer.image;
          const VkBufferCopy region{layout.offset, 0,
                                    VkDeviceSize(layout.width) * layout.height * 4};
          vkCmdCopyBuffer(ctx.cmd(), ctx.buffer(BufferId{o.resource, o.version}).buffer(), target,
                          1, &region);
          continue;
        }
        const Image& image = ctx.image(ImageId{o.resource, o.version});
        const ImageDesc& d = image.desc();
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {d.width, d.height, d.dim == ImageDim::Tex3D ? d.depth : 1};
        vkCmdCopyImageToBuffer(ctx.cmd(), image.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               target, 1, &region);
      }
    });
    b.sideEffect();
    std::set<uint32_t> declared;
    for (const Output& o : mOutputs) {
      if (!declared.insert(o.resource).second) continue;
      if (mDesc.resources[o.resource].kind == ResourceKind::Buffer)
        b.read(BufferId{o.resource, o.version}, Access::TransferSrc);
      else
        b.read(ImageId{o.resource, o.version}, Access::TransferSrc);
    }
  }
  CompiledGraph c;
  c.alive = cull(mDesc);
  c.order = order(mDesc, c.alive);
  c.lifetimes = computeLifetimes(mDesc, c.order);
  std::vector<MemoryRequirement> req(mDesc.resources.size());
  for (uint32_t r = 0; r < mDesc.resources.size(); ++r)
    if (!mDesc.resources[r].imported && c.lifetimes[r].used())
      req[r] = mRuntime ? requirementOf(mRuntime->gpu(), mDesc.resources[r])
                        : estimatedRequirement(mDesc.resources[r]);
  c.memory = assignMemory(mDesc, c.lifetimes, req);
  c.barriers = buildBarriers(mDesc, c.order, c.memory);
  mCompiled = std::move(c);
  return *mCompiled;
}

void FrameGraph::allocateTransients() {
  GraphRuntime& runtime = *mRuntime;
  const CompiledGraph& c = *mCompiled;
  const Context& ctx = runtime.gpu();
  GraphRuntime::Transients& t = runtime.transients(mUse);

  // Transient memory: reuse last frame's allocation while the graph keeps its shape.
  std::string key;
  for (uint32_t r = 0; r < mDesc.resources.size(); ++r) {
    const ResourceNode& n = mDesc.resources[r];
    if (n.imported || c.memory.slotOf[r] < 0) continue;
    key += std::to_string(r) + ":" + n.name + ":" + std::to_string(c.memory.slotOf[r]) + ":";
    key += n.kind == ResourceKind::Image
               ? std::to_string(n.image.format) + "," + std::to_string(n.image.width) + "," +
                     std::to_string(n.image.height) + "," + std::to_string(n.image.depth) + "," +
                     std::to_string(static_cast<int>(n.image.dim)) + "," +
                     std::to_string(n.image.usage)
               : std::to_string(n.buffer.size) + "," + std::to_string(n.buffer.usage);
    key += ";";
  }
  if (key != t.key || t.images.size() != mDesc.resources.size()) {
    runtime.releaseTransients(mUse);
    if (mUse == GraphUse::Frame) ++runtime.mTransientAllocations;
    for (const MemorySlot& slot : c.memory.slots) {
      VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
      alloc.allocationSize = slot.size;
      alloc.memoryTypeIndex = ctx.memoryType(slot.typeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
      t.memory.push_back(ctx.allocate(alloc, "the frame graph's transient images"));
      t.bytes += slot.size;
    }
    t.images.resize(mDesc.resources.size());
    t.buffers.resize(mDesc.resources.size());
    for (uint32_t r = 0; r < mDesc.resources.size(); ++r) {
      const ResourceNode& n = mDesc.resources[r];
      int slot = c.memory.slotOf[r];
      if (n.imported || slot < 0) continue;
      if (n.kind == ResourceKind::Image) {
        t.images[r] = Image(ctx, n.image, false);
        t.images[r].bindMemory(t.memory[static_cast<size_t>(slot)], 0);
      } else {
        t.buffers[r] = Buffer(ctx, n.buffer, false);
        t.buffers[r].bindMemory(t.memory[static_cast<size_t>(slot)], 0);
      }
    }
    t.key = key;
  }
}

void FrameGraph::recordPasses(VkCommandBuffer cmd, TimestampPool* timestamps) {
  const CompiledGraph& c = *mCompiled;
  GraphRuntime::Transients& t = mRuntime->transients(mUse);
  for (size_t pos = 0; pos < c.order.size(); ++pos) {
    const uint32_t pass = c.order[pos];
    if (timestamps) timestamps->begin(cmd, static_cast<uint32_t>(pos));
    std::vector<VkImageMemoryBarrier2> images;
    std::vector<VkBufferMemoryBarrier2> buffers;
    for (const Barrier& b : c.barriers.before[pos]) {
      const ResourceNode& n = mDesc.resources[b.resource];
      if (n.kind == ResourceKind::Image) {
        VkImageMemoryBarrier2 ib{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        ib.srcStageMask = b.srcStage;
        ib.srcAccessMask = b.srcAccess;
        ib.dstStageMask = b.dstStage;
        ib.dstAccessMask = b.dstAccess;
        ib.oldLayout = b.oldLayout;
        ib.newLayout = b.newLayout;
        ib.srcQueueFamilyIndex = ib.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        ib.image =
            n.imported ? mResources[b.resource].image->image.image() : t.images[b.resource].image();
        ib.subresourceRange = {n.image.aspect, 0, 1, 0, 1};
        images.push_back(ib);
      } else {
        VkBufferMemoryBarrier2 bb{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
        bb.srcStageMask = b.srcStage;
        bb.srcAccessMask = b.srcAccess;
        bb.dstStageMask = b.dstStage;
        bb.dstAccessMask = b.dstAccess;
        bb.srcQueueFamilyIndex = bb.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        bb.buffer = n.imported ? mResources[b.resource].buffer->buffer.buffer()
                               : t.buffers[b.resource].buffer();
        bb.size = VK_WHOLE_SIZE;
        buffers.push_back(bb);
      }
    }
    if (!images.empty() || !buffers.empty()) {
      VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
      dep.imageMemoryBarrierCount = static_cast<uint32_t>(images.size());
      dep.pImageMemoryBarriers = images.data();
      dep.bufferMemoryBarrierCount = static_cast<uint32_t>(buffers.size());
      dep.pBufferMemoryBarriers = buffers.data();
      vkCmdPipelineBarrier2(cmd, &dep);
    }
    PassContext pc(*this, pass, cmd);
    mPasses[pass].execute(pc);
    if (timestamps) timestamps->end(cmd, static_cast<uint32_t>(pos));
  }
  // The host's images go back to its layouts, everything written made available to it.
  std::vector<VkImageMemoryBarrier2> back;
  for (const External& e : mExternals) {
    if (!c.lifetimes[e.resource].used()) continue;
    VkImageMemoryBarrier2 ib{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    ib.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    ib.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    ib.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    ib.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    ib.oldLayout = c.barriers.finalState[e.resource].layout;
    ib.newLayout = e.hostLayout;
    ib.srcQueueFamilyIndex = ib.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    ib.image = mResources[e.resource].image->image.image();
    ib.subresourceRange = mResources[e.resource].image->image.range();
    back.push_back(ib);
  }
  if (!back.empty()) {
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = static_cast<uint32_t>(back.size());
    dep.pImageMemoryBarriers = back.data();
    vkCmdPipelineBarrier2(cmd, &dep);
  }
}

void FrameGraph::finishFrame() {
  const CompiledGraph& c = *mCompiled;
  for (uint32_t r = 0; r < mDesc.resources.size(); ++r) {
    if (!mDesc.resources[r].imported || !c.lifetimes[r].used()) continue;
    if (mResources[r].image) mResources[r].image->state = c.barriers.finalState[r];
    if (mResources[r].buffer) mResources[r].buffer->state = c.barriers.finalState[r];
  }
  // This frame's results become the next frame's history.
  for (HistoryImage* h : mHistories) {
    h->mWrite = 1 - h->mWrite;
    h->mValid = true;
  }
  // Uploads landed (or, recorded, will have when the host runs the frame): tell the images'
  // owners.
  for (const std::function<void()>& done : mAfterExecute) done();
}

FrameResult FrameGraph::record(VkCommandBuffer cmd) {
  if (mExecuted) internalError("frame graph executed twice; build a new graph per frame");
  mExecuted = true;
  if (!mRuntime) internalError("frame graph built without a GPU runtime cannot record");
  if (!mOutputs.empty()) internalError("frame graph: a recorded frame reads nothing back");
  const auto start = std::chrono::steady_clock::now();
  const CompiledGraph& c = compile();
  mRuntime->beginHostFrame();
  allocateTransients();
  recordPasses(cmd, nullptr);
  FrameResult result;
  for (uint32_t pass : c.order) result.passes.push_back({mDesc.passes[pass].name, 0.0, 0});
  // The uploads' staging lives until the host has run the frame (the next frame frees it).
  for (std::unique_ptr<Buffer>& b : mStaging) mRuntime->mHostStaging.push_back(std::move(b));
  mStaging.clear();
  finishFrame();
  result.wallMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

FrameResult FrameGraph::execute() {
  if (mExecuted) internalError("frame graph executed twice; build a new graph per frame");
  mExecuted = true;
  if (!mRuntime) internalError("frame graph built without a GPU runtime cannot execute");
  GraphRuntime& runtime = *mRuntime;
  const auto start = std::chrono::steady_clock::now();
  const CompiledGraph& c = compile();
  const Context& ctx = runtime.gpu();
  allocateTransients();

  // Host-visible buffers for the requested outputs.
  std::vector<Buffer>& readback = runtime.readback(mUse);
  readback.resize(mOutputs.size());
  for (size_t i = 0; i < mOutputs.size(); ++i) {
    const ResourceNode& n = mDesc.resources[mOutputs[i].resource];
    const VkDeviceSize bytes = n.kind == ResourceKind::Buffer
                                   ? VkDeviceSize(n.buffer.image.width) * n.buffer.image.height * 4
                                   : texelBytes(n.image);
    if (!readback[i] || readback[i].size() != bytes)
      readback[i] = Buffer(ctx, {"readback " + mOutputs[i].label, bytes,
                                 VK_BUFFER_USAGE_TRANSFER_DST_BIT, BufferMemory::HostVisible});
  }

  VkCommandBuffer cmd = runtime.beginFrame();
  TimestampPool timestamps(ctx, static_cast<uint32_t>(c.order.size()));
  timestamps.reset(cmd);
  recordPasses(cmd, &timestamps);
  // The copies must be visible to the host reading the mapped buffers after the fence.
  if (!mOutputs.empty()) copiesVisibleToHost(cmd);
  runtime.submitAndWait();

  FrameResult result;
  std::vector<double> ms = timestamps.resultsMs();
  for (size_t pos = 0; pos < c.order.size(); ++pos) {
    double passMs = pos < ms.size() ? ms[pos] : 0.0;
    const PassNode& node = mDesc.passes[c.order[pos]];
    uint64_t texels = 0;
    for (const ResourceAccess& a : node.accesses) {
      const ResourceNode& r = mDesc.resources[a.resource];
      if (accessInfo(a.access).write && r.kind == ResourceKind::Image)
        texels = std::max(texels, uint64_t(r.image.width) * r.image.height * r.image.depth);
    }
    result.passes.push_back({node.name, passMs, texels});
    result.gpuMs += passMs;
  }
  for (size_t i = 0; i < mOutputs.size(); ++i) {
    const ResourceNode& n = mDesc.resources[mOutputs[i].resource];
    const Buffer& buf = readback[i];
    buf.invalidate();
    ReadbackImage out;
    out.label = mOutputs[i].label;
    if (n.kind == ResourceKind::Buffer) {
      const BufferImage& layout = n.buffer.image;
      out.width = layout.width;
      out.height = layout.height;
      out.channels = 1;
      out.format = VK_FORMAT_R32_SFLOAT;
      const uint32_t* values = static_cast<const uint32_t*>(buf.mapped());
      out.pixels.resize(size_t(layout.width) * layout.height);
      for (size_t k = 0; k < out.pixels.size(); ++k)
        out.pixels[k] = static_cast<float>(values[k]) * layout.scale;
      result.outputs.push_back(std::move(out));
      continue;
    }
    const ImageDesc& d = n.image;
    out.width = d.width;
    out.height = d.height;
    out.depth = d.dim == ImageDim::Tex3D ? d.depth : 1;
    out.channels = formatChannelCount(d.format);
    out.format = d.format;
    out.pixels = texelsToFloat(d.format, {static_cast<const uint8_t*>(buf.mapped()), buf.size()});
    result.outputs.push_back(std::move(out));
  }
  // A bake's memory is freed at once (GraphUse).
  if (mUse == GraphUse::Bake) {
    runtime.releaseTransients(GraphUse::Bake);
    readback.clear();
  }
  mStaging.clear();  // the uploads landed
  finishFrame();
  result.wallMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace sky
