#include "engine/shader/spirv_reflect.h"

#include <algorithm>
#include <optional>
#include <string_view>
#include <unordered_map>

#include <glslang/SPIRV/spirv.hpp>

#include "engine/core/error.h"

namespace sky {

namespace {

// Where an id was defined: its opcode and the word range of that instruction.
struct Definition {
  uint32_t op = spv::OpNop;
  size_t offset = 0;  // index of the instruction's first word
  uint32_t wordCount = 0;
};

struct Decorations {
  std::optional<uint32_t> set, binding, arrayStride, builtIn;
  bool block = false, bufferBlock = false;
};

struct MemberDecorations {
  std::optional<uint32_t> offset, matrixStride;
  bool rowMajor = false;
};

struct Variable {
  uint32_t id = 0, pointerType = 0, storageClass = 0;
  size_t offset = 0;
};

// One pass over the instruction stream collects everything reflection needs; the
// interpretation happens afterwards because SPIR-V allows decorations before their targets.
class Reflector {
public:
  explicit Reflector(std::span<const uint32_t> words) : mWords(words) {}

  ShaderReflection run() {
    scan();
    ShaderReflection out;
    out.localSize = localSize();
    for (const Variable& v : mVariables) {
      if (v.storageClass == spv::StorageClassPushConstant) {
        out.pushConstantSize =
            std::max(out.pushConstantSize, typeSize(pointee(v.pointerType, v.offset), v.offset));
      } else if (v.storageClass == spv::StorageClassUniformConstant ||
                 v.storageClass == spv::StorageClassUniform ||
                 v.storageClass == spv::StorageClassStorageBuffer) {
        out.bindings.push_back(binding(v));
      }
    }
    // Vulkan wants push-constant ranges in multiples of 4; only 8/16-bit members at the end
    // of the block can make the raw end unaligned.
    out.pushConstantSize = (out.pushConstantSize + 3u) & ~3u;
    std::stable_sort(out.bindings.begin(), out.bindings.end(),
                     [](const DescriptorBinding& a, const DescriptorBinding& b) {
                       return a.set != b.set ? a.set < b.set : a.binding < b.binding;
                     });
    return out;
  }

private:
  [[noreturn]] void fail(size_t wordOffset, const std::string& what) const {
    internalError("SPIR-V reflection: word " + std::to_string(wordOffset) + ": " + what);
  }

  // Operand `i` of the instruction at `offset` (operand 0 is the opcode word itself).
  uint32_t operand(size_t offset, uint32_t wordCount, uint32_t i) const {
    if (i >= wordCount)
      fail(offset, "opcode " + std::to_string(mWords[offset] & 0xffffu) + " has " +
                       std::to_string(wordCount) + " words, operand " + std::to_string(i) +
                       " is missing");
    return mWords[offset + i];
  }

  std::string literalString(size_t offset, uint32_t wordCount, uint32_t first) const {
    std::string s;
    for (uint32_t i = first; i < wordCount; ++i) {
      uint32_t w = mWords[offset + i];
      for (int b = 0; b < 4; ++b) {
        char c = static_cast<char>((w >> (8 * b)) & 0xffu);
        if (c == '\0') return s;
        s.push_back(c);
      }
    }
    fail(offset, "literal string is not NUL-terminated");
  }

  void define(uint32_t id, uint32_t op, size_t offset, uint32_t wordCount) {
    if (id == 0 || id >= mBound)
      fail(offset, "id " + std::to_string(id) + " is outside the bound " + std::to_string(mBound));
    mDefs[id] = {op, offset, wordCount};
  }

  const Definition& def(uint32_t id, size_t usedAt) const {
    auto it = mDefs.find(id);
    if (it == mDefs.end()) fail(usedAt, "id " + std::to_string(id) + " is used but never defined");
    return it->second;
  }

  const std::string& name(uint32_t id) const {
    static const std::string kNone;
    auto it = mNames.find(id);
    return it == mNames.end() ? kNone : it->second;
  }

  void scan() {
    if (mWords.size() < 5)
      fail(0, "module has " + std::to_string(mWords.size()) + " words, fewer than the header");
    if (mWords[0] != spv::MagicNumber) fail(0, "bad magic number (not SPIR-V, or byte-swapped)");
    // Maps rather than vectors indexed by id: a corrupt bound must not cost gigabytes.
    mBound = mWords[3];

    for (size_t pos = 5; pos < mWords.size();) {
      const uint32_t wc = mWords[pos] >> 16;
      const uint32_t op = mWords[pos] & 0xffffu;
      if (wc == 0) fail(pos, "instruction with word count 0");
      if (pos + wc > mWords.size()) fail(pos, "instruction runs past the end of the module");
      auto arg = [&](uint32_t i) { return operand(pos, wc, i); };

      switch (op) {
        case spv::OpName: {
          mNames[arg(1)] = literalString(pos, wc, 2);
          break;
        }
        case spv::OpEntryPoint:
          if (mEntryPoint == 0 || (mEntryModel != spv::ExecutionModelGLCompute &&
                                   arg(1) == spv::ExecutionModelGLCompute)) {
            mEntryModel = arg(1);
            mEntryPoint = arg(2);
          }
          break;
        case spv::OpExecutionMode:
        case spv::OpExecutionModeId:
          if (arg(2) == spv::ExecutionModeLocalSize || arg(2) == spv::ExecutionModeLocalSizeId)
            mLocalSizeModes.push_back({pos, wc});
          break;
        case spv::OpDecorate: {
          Decorations& d = mDecorations[arg(1)];
          mDecorationOffsets[arg(1)] = pos;
          switch (arg(2)) {
            case spv::DecorationDescriptorSet:
              d.set = arg(3);
              break;
            case spv::DecorationBinding:
              d.binding = arg(3);
              break;
            case spv::DecorationArrayStride:
              d.arrayStride = arg(3);
              break;
            case spv::DecorationBuiltIn:
              d.builtIn = arg(3);
              break;
            case spv::DecorationBlock:
              d.block = true;
              break;
            case spv::DecorationBufferBlock:
              d.bufferBlock = true;
              break;
            default:
              break;
          }
          break;
        }
        case spv::OpMemberDecorate: {
          std::vector<MemberDecorations>& members = mMemberDecorations[arg(1)];
          uint32_t index = arg(2);
          if (index >= 65536) fail(pos, "member index " + std::to_string(index) + " too large");
          if (members.size() <= index) members.resize(index + 1);
          switch (arg(3)) {
            case spv::DecorationOffset:
              members[index].offset = arg(4);
              break;
            case spv::DecorationMatrixStride:
              members[index].matrixStride = arg(4);
              break;
            case spv::DecorationRowMajor:
              members[index].rowMajor = true;
              break;
            default:
              break;
          }
          break;
        }
        case spv::OpTypeVoid:
        case spv::OpTypeBool:
        case spv::OpTypeInt:
        case spv::OpTypeFloat:
        case spv::OpTypeVector:
        case spv::OpTypeMatrix:
        case spv::OpTypeImage:
        case spv::OpTypeSampler:
        case spv::OpTypeSampledImage:
        case spv::OpTypeArray:
        case spv::OpTypeRuntimeArray:
        case spv::OpTypeStruct:
        case spv::OpTypePointer:
        case spv::OpTypeAccelerationStructureKHR:
          define(arg(1), op, pos, wc);
          break;
        case spv::OpConstant:
        case spv::OpSpecConstant:
        case spv::OpConstantComposite:
        case spv::OpSpecConstantComposite:
          define(arg(2), op, pos, wc);
          break;
        case spv::OpVariable:
          define(arg(2), op, pos, wc);
          mVariables.push_back({arg(2), arg(1), arg(3), pos});
          break;
        default:
          break;
      }
      pos += wc;
    }
  }

  // Value of an integer OpConstant / OpSpecConstant (its default); the low word for 64-bit.
  uint32_t constantValue(uint32_t id, size_t usedAt) const {
    const Definition& d = def(id, usedAt);
    if (d.op != spv::OpConstant && d.op != spv::OpSpecConstant)
      fail(usedAt, "id " + std::to_string(id) + " is not a scalar constant");
    return operand(d.offset, d.wordCount, 3);
  }

  std::array<uint32_t, 3> localSize() const {
    std::array<uint32_t, 3> size{1, 1, 1};
    for (auto [pos, wc] : mLocalSizeModes) {
      if (operand(pos, wc, 1) != mEntryPoint) continue;
      bool byId = (mWords[pos] & 0xffffu) == spv::OpExecutionModeId;
      for (uint32_t i = 0; i < 3; ++i) {
        uint32_t v = operand(pos, wc, 3 + i);
        size[i] = byId ? constantValue(v, pos) : v;
      }
    }
    // A constant decorated BuiltIn WorkgroupSize overrides the execution mode (SPIR-V 2.16);
    // glslang emits one when the shader uses local_size_x_id specialization constants.
    for (const auto& [id, deco] : mDecorations) {
      if (deco.builtIn != spv::BuiltInWorkgroupSize) continue;
      const Definition& d = def(id, mDecorationOffsets.at(id));
      if (d.op != spv::OpConstantComposite && d.op != spv::OpSpecConstantComposite) continue;
      for (uint32_t i = 0; i < 3; ++i)
        size[i] = constantValue(operand(d.offset, d.wordCount, 3 + i), d.offset);
    }
    return size;
  }

  uint32_t pointee(uint32_t pointerType, size_t usedAt) const {
    const Definition& d = def(pointerType, usedAt);
    if (d.op != spv::OpTypePointer)
      fail(d.offset, "variable type " + std::to_string(pointerType) + " is not a pointer");
    return operand(d.offset, d.wordCount, 3);
  }

  const Decorations* decorations(uint32_t id) const {
    auto it = mDecorations.find(id);
    return it == mDecorations.end() ? nullptr : &it->second;
  }

  // Byte size of a type inside an explicitly laid out block: offset + size of the last
  // member for structs, stride x length for arrays and matrices.
  uint32_t typeSize(uint32_t type, size_t usedAt, std::optional<uint32_t> matrixStride = {},
                    bool rowMajor = false, int depth = 0) const {
    if (depth > 64) fail(usedAt, "type nesting deeper than 64 (cyclic type?)");
    const Definition& d = def(type, usedAt);
    auto arg = [&](uint32_t i) { return operand(d.offset, d.wordCount, i); };
    switch (d.op) {
      case spv::OpTypeBool:
        return 4;  // only appears in blocks as a 32-bit value
      case spv::OpTypeInt:
      case spv::OpTypeFloat:
        return arg(2) / 8;
      case spv::OpTypeVector:
        return arg(3) * typeSize(arg(2), d.offset, {}, false, depth + 1);
      case spv::OpTypeMatrix: {
        uint32_t columns = arg(3);
        const Definition& column = def(arg(2), d.offset);
        uint32_t rows = operand(column.offset, column.wordCount, 3);
        uint32_t vectors = rowMajor ? rows : columns;
        if (matrixStride) return vectors * *matrixStride;
        return columns * typeSize(arg(2), d.offset, {}, false, depth + 1);
      }
      case spv::OpTypeArray: {
        uint32_t length = constantValue(arg(3), d.offset);
        const Decorations* deco = decorations(type);
        if (deco && deco->arrayStride) return length * *deco->arrayStride;
        return length * typeSize(arg(2), d.offset, matrixStride, rowMajor, depth + 1);
      }
      case spv::OpTypeRuntimeArray:
        return 0;
      case spv::OpTypeStruct: {
        auto it = mMemberDecorations.find(type);
        uint32_t end = 0;
        for (uint32_t m = 0; m + 2 < d.wordCount; ++m) {
          const MemberDecorations* md =
              (it != mMemberDecorations.end() && m < it->second.size()) ? &it->second[m] : nullptr;
          uint32_t size = typeSize(arg(2 + m), d.offset, md ? md->matrixStride : std::nullopt,
                                   md && md->rowMajor, depth + 1);
          uint32_t offset = (md && md->offset) ? *md->offset : end;
          end = std::max(end, offset + size);
        }
        return end;
      }
      default:
        fail(d.offset, "type " + std::to_string(type) + " (opcode " + std::to_string(d.op) +
                           ") has no size in a block");
    }
  }

  static VkImageViewType viewType(uint32_t dim, bool arrayed) {
    switch (dim) {
      case spv::Dim1D:
        return arrayed ? VK_IMAGE_VIEW_TYPE_1D_ARRAY : VK_IMAGE_VIEW_TYPE_1D;
      case spv::Dim3D:
        return VK_IMAGE_VIEW_TYPE_3D;
      case spv::DimCube:
        return arrayed ? VK_IMAGE_VIEW_TYPE_CUBE_ARRAY : VK_IMAGE_VIEW_TYPE_CUBE;
      default:
        return arrayed ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
    }
  }

  // Fills type, view type and format from an OpTypeImage (operands: sampled type, Dim,
  // Depth, Arrayed, MS, Sampled, Format).
  void describeImage(uint32_t imageType, size_t usedAt, bool combined, DescriptorBinding& b) const {
    const Definition& d = def(imageType, usedAt);
    if (d.op != spv::OpTypeImage) fail(d.offset, "sampled image of a non-image type");
    uint32_t dim = operand(d.offset, d.wordCount, 3);
    bool arrayed = operand(d.offset, d.wordCount, 5) != 0;
    bool storage = operand(d.offset, d.wordCount, 7) == 2;
    b.viewType = viewType(dim, arrayed);
    if (dim == spv::DimBuffer) {
      b.type = storage ? VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER
                       : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    } else if (dim == spv::DimSubpassData) {
      b.type = VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT;
    } else if (combined) {
      b.type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    } else {
      b.type = storage ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    }
    if (storage) b.storageFormat = vkFormatFromSpirv(operand(d.offset, d.wordCount, 8));
  }

  DescriptorBinding binding(const Variable& v) const {
    DescriptorBinding b;
    if (const Decorations* deco = decorations(v.id)) {
      b.set = deco->set.value_or(0);
      b.binding = deco->binding.value_or(0);
    }
    uint32_t type = pointee(v.pointerType, v.offset);
    size_t usedAt = v.offset;
    for (int depth = 0;; ++depth) {
      if (depth > 8) fail(usedAt, "descriptor array nesting deeper than 8");
      const Definition& d = def(type, usedAt);
      usedAt = d.offset;
      if (d.op == spv::OpTypeArray) {
        b.count *= constantValue(operand(d.offset, d.wordCount, 3), d.offset);
      } else if (d.op == spv::OpTypeRuntimeArray) {
        b.count = 0;
      } else {
        break;
      }
      type = operand(d.offset, d.wordCount, 2);
    }
    const Definition& d = def(type, usedAt);
    switch (d.op) {
      case spv::OpTypeStruct: {
        const Decorations* deco = decorations(type);
        bool ssbo = v.storageClass == spv::StorageClassStorageBuffer || (deco && deco->bufferBlock);
        b.type = ssbo ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER : VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        break;
      }
      case spv::OpTypeImage:
        describeImage(type, usedAt, false, b);
        break;
      case spv::OpTypeSampledImage:
        describeImage(operand(d.offset, d.wordCount, 2), d.offset, true, b);
        break;
      case spv::OpTypeSampler:
        b.type = VK_DESCRIPTOR_TYPE_SAMPLER;
        break;
      case spv::OpTypeAccelerationStructureKHR:
        b.type = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
        break;
      default:
        fail(d.offset, "variable " + std::to_string(v.id) + " ('" + name(v.id) +
                           "') has a type that is not a descriptor (opcode " +
                           std::to_string(d.op) + ")");
    }
    // glslang names an anonymous block's variable ""; the block type's name is what the
    // shader author wrote.
    b.name = name(v.id).empty() ? name(type) : name(v.id);
    return b;
  }

  std::span<const uint32_t> mWords;
  uint32_t mBound = 0;
  std::unordered_map<uint32_t, Definition> mDefs;
  std::unordered_map<uint32_t, std::string> mNames;
  std::unordered_map<uint32_t, Decorations> mDecorations;
  std::unordered_map<uint32_t, size_t> mDecorationOffsets;  // last OpDecorate of each id
  std::unordered_map<uint32_t, std::vector<MemberDecorations>> mMemberDecorations;
  std::vector<Variable> mVariables;
  std::vector<std::pair<size_t, uint32_t>> mLocalSizeModes;  // (offset, word count)
  uint32_t mEntryPoint = 0;
  uint32_t mEntryModel = 0;
};

}  // namespace

VkFormat vkFormatFromSpirv(uint32_t f) {
  switch (static_cast<spv::ImageFormat>(f)) {
    case spv::ImageFormatRgba32f:
      return VK_FORMAT_R32G32B32A32_SFLOAT;
    case spv::ImageFormatRgba16f:
      return VK_FORMAT_R16G16B16A16_SFLOAT;
    case spv::ImageFormatR32f:
      return VK_FORMAT_R32_SFLOAT;
    case spv::ImageFormatRgba8:
      return VK_FORMAT_R8G8B8A8_UNORM;
    case spv::ImageFormatRgba8Snorm:
      return VK_FORMAT_R8G8B8A8_SNORM;
    case spv::ImageFormatRg32f:
      return VK_FORMAT_R32G32_SFLOAT;
    case spv::ImageFormatRg16f:
      return VK_FORMAT_R16G16_SFLOAT;
    case spv::ImageFormatR11fG11fB10f:
      return VK_FORMAT_B10G11R11_UFLOAT_PACK32;
    case spv::ImageFormatR16f:
      return VK_FORMAT_R16_SFLOAT;
    case spv::ImageFormatRgba16:
      return VK_FORMAT_R16G16B16A16_UNORM;
    case spv::ImageFormatRgb10A2:
      return VK_FORMAT_A2B10G10R10_UNORM_PACK32;
    case spv::ImageFormatRg16:
      return VK_FORMAT_R16G16_UNORM;
    case spv::ImageFormatRg8:
      return VK_FORMAT_R8G8_UNORM;
    case spv::ImageFormatR16:
      return VK_FORMAT_R16_UNORM;
    case spv::ImageFormatR8:
      return VK_FORMAT_R8_UNORM;
    case spv::ImageFormatRgba16Snorm:
      return VK_FORMAT_R16G16B16A16_SNORM;
    case spv::ImageFormatRg16Snorm:
      return VK_FORMAT_R16G16_SNORM;
    case spv::ImageFormatRg8Snorm:
      return VK_FORMAT_R8G8_SNORM;
    case spv::ImageFormatR16Snorm:
      return VK_FORMAT_R16_SNORM;
    case spv::ImageFormatR8Snorm:
      return VK_FORMAT_R8_SNORM;
    case spv::ImageFormatRgba32i:
      return VK_FORMAT_R32G32B32A32_SINT;
    case spv::ImageFormatRgba16i:
      return VK_FORMAT_R16G16B16A16_SINT;
    case spv::ImageFormatRgba8i:
      return VK_FORMAT_R8G8B8A8_SINT;
    case spv::ImageFormatR32i:
      return VK_FORMAT_R32_SINT;
    case spv::ImageFormatRg32i:
      return VK_FORMAT_R32G32_SINT;
    case spv::ImageFormatRg16i:
      return VK_FORMAT_R16G16_SINT;
    case spv::ImageFormatRg8i:
      return VK_FORMAT_R8G8_SINT;
    case spv::ImageFormatR16i:
      return VK_FORMAT_R16_SINT;
    case spv::ImageFormatR8i:
      return VK_FORMAT_R8_SINT;
    case spv::ImageFormatRgba32ui:
      return VK_FORMAT_R32G32B32A32_UINT;
    case spv::ImageFormatRgba16ui:
      return VK_FORMAT_R16G16B16A16_UINT;
    case spv::ImageFormatRgba8ui:
      return VK_FORMAT_R8G8B8A8_UINT;
    case spv::ImageFormatR32ui:
      return VK_FORMAT_R32_UINT;
    case spv::ImageFormatRgb10a2ui:
      return VK_FORMAT_A2B10G10R10_UINT_PACK32;
    case spv::ImageFormatRg32ui:
      return VK_FORMAT_R32G32_UINT;
    case spv::ImageFormatRg16ui:
      return VK_FORMAT_R16G16_UINT;
    case spv::ImageFormatRg8ui:
      return VK_FORMAT_R8G8_UINT;
    case spv::ImageFormatR16ui:
      return VK_FORMAT_R16_UINT;
    case spv::ImageFormatR8ui:
      return VK_FORMAT_R8_UINT;
    case spv::ImageFormatR64ui:
      return VK_FORMAT_R64_UINT;
    case spv::ImageFormatR64i:
      return VK_FORMAT_R64_SINT;
    default:
      return VK_FORMAT_UNDEFINED;
  }
}

ShaderReflection reflectSpirv(std::span<const uint32_t> words) {
  return Reflector(words).run();
}

}  // namespace sky
