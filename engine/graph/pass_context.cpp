#include "engine/graph/pass_context.h"

#include <vector>

#include "engine/core/error.h"
#include "engine/gpu/compute_pipeline.h"
#include "engine/gpu/context.h"
#include "engine/gpu/sampler.h"
#include "engine/graph/frame_graph.h"

namespace sky {

const Context& PassContext::gpu() const {
  return mGraph.mRuntime->gpu();
}

const ResourceAccess* PassContext::declared(uint32_t resource) const {
  for (const ResourceAccess& a : mGraph.mDesc.passes[mPass].accesses)
    if (a.resource == resource) return &a;
  const std::string name =
      resource < mGraph.mDesc.resources.size() ? mGraph.mDesc.resources[resource].name : "?";
  internalError("pass '" + mGraph.mDesc.passes[mPass].name + "' uses '" + name +
                "' without declaring it in setup");
}

const Image& PassContext::image(ImageId h) const {
  declared(h.id);
  const auto& rec = mGraph.mResources[h.id];
  return rec.image ? rec.image->image : mGraph.mRuntime->transients(mGraph.mUse).images[h.id];
}

const Buffer& PassContext::buffer(BufferId h) const {
  declared(h.id);
  const auto& rec = mGraph.mResources[h.id];
  return rec.buffer ? rec.buffer->buffer : mGraph.mRuntime->transients(mGraph.mUse).buffers[h.id];
}

UniformRange PassContext::uniform(const void* data, VkDeviceSize size) const {
  return mGraph.mRuntime->uploadUniform(data, size);
}

void PassContext::dispatch(const ComputePipeline& pipeline, std::span<const Binding> bindings,
                           uint32_t gx, uint32_t gy, uint32_t gz, const void* push,
                           uint32_t pushSize) const {
  // Built only when a check fails: dispatch runs for every pass every frame.
  auto where = [&] {
    return "pass '" + mGraph.mDesc.passes[mPass].name + "', shader '" + pipeline.name() + "'";
  };
  const ShaderReflection& refl = pipeline.reflection();
  for (const DescriptorBinding& d : refl.bindings) {
    size_t n = 0;
    for (const Binding& b : bindings) n += b.binding == d.binding;
    if (n != 1)
      internalError(where() + ": binding " + std::to_string(d.binding) + " ('" + d.name +
                    "') given " + std::to_string(n) + " times; it must be given once");
  }
  if (pushSize != refl.pushConstantSize)
    internalError(where() + ": push constants of " + std::to_string(pushSize) +
                  " bytes, shader wants " + std::to_string(refl.pushConstantSize));

  std::vector<VkWriteDescriptorSet> writes;
  std::vector<VkDescriptorImageInfo> imageInfos;
  std::vector<VkDescriptorBufferInfo> bufferInfos;
  imageInfos.reserve(bindings.size());
  bufferInfos.reserve(bindings.size());
  VkDescriptorSet set = mGraph.mRuntime->mDescriptors.allocate(pipeline.setLayout());
  for (const Binding& b : bindings) {
    const DescriptorBinding* d = pipeline.binding(b.binding);
    if (!d) internalError(where() + ": the shader has no binding " + std::to_string(b.binding));
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set;
    w.dstBinding = b.binding;
    w.descriptorCount = 1;
    w.descriptorType = d->type;
    auto mismatch = [&](const char* what) {
      internalError(where() + ": binding " + std::to_string(b.binding) + " ('" + d->name + "') " +
                    what);
    };
    switch (d->type) {
      case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
      case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER: {
        if (b.kind != Binding::Kind::Image) mismatch("is an image in the shader");
        const ResourceAccess* a = declared(b.image.id);
        const bool storage = d->type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        const bool storageAccess = a->access != Access::SampledCompute;
        if (storage != storageAccess || a->access == Access::TransferSrc ||
            a->access == Access::TransferDst)
          mismatch(storage ? "is a storage image but setup declared another access"
                           : "is a sampled image but setup declared another access");
        if (!storage && !b.sampler) mismatch("needs a sampler");
        const Image& img = image(b.image);
        if ((d->viewType == VK_IMAGE_VIEW_TYPE_3D) != (img.desc().dim == ImageDim::Tex3D))
          mismatch("has a different dimensionality than the image");
        imageInfos.push_back({b.sampler ? b.sampler->sampler() : VK_NULL_HANDLE, img.view(),
                              accessInfo(a->access).layout});
        w.pImageInfo = &imageInfos.back();
        break;
      }
      // Either kind takes a graph buffer or a range of the uniform arena.
      case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
      case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER: {
        if (b.kind == Binding::Kind::Uniform) {
          bufferInfos.push_back({b.uniform.buffer, b.uniform.offset, b.uniform.size});
        } else if (b.kind == Binding::Kind::Buffer) {
          bufferInfos.push_back({buffer(b.buffer).buffer(), 0, VK_WHOLE_SIZE});
        } else {
          mismatch(d->type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                       ? "is a storage buffer in the shader"
                       : "is a uniform buffer in the shader");
        }
        w.pBufferInfo = &bufferInfos.back();
        break;
      }
      default:
        mismatch("has a descriptor type the frame graph does not bind");
    }
    writes.push_back(w);
  }
  const Context& ctx = gpu();
  vkUpdateDescriptorSets(ctx.device(), static_cast<uint32_t>(writes.size()), writes.data(), 0,
                         nullptr);
  vkCmdBindPipeline(mCmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline());
  vkCmdBindDescriptorSets(mCmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 0, 1, &set, 0,
                          nullptr);
  if (pushSize)
    vkCmdPushConstants(mCmd, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, pushSize, push);
  vkCmdDispatch(mCmd, gx, gy, gz);
}

}  // namespace sky
