// SPIR-V reflection: on shaders compiled from tests/data/shader/reflect and on hand-built
// modules for what glslang's SPIR-V 1.6 output never contains (BufferBlock, WorkgroupSize).
#include <cstring>
#include <random>

#include <glslang/SPIRV/spirv.hpp>

#include "engine/shader/shader_compiler.h"
#include "tests/shader/shader_test_util.h"

namespace sky {
namespace {
using test::shaderTestData;

ShaderReflection reflectFile(const char* file) {
  return ShaderCompiler(shaderTestData(), std::nullopt).compile(file).reflection;
}

struct Expected {
  uint32_t set, binding;
  VkDescriptorType type;
  uint32_t count;
  const char* name;
  VkImageViewType viewType;
  VkFormat format;
};

TEST(SpirvReflect, EveryDescriptorTypeArrayDimensionAndFormat) {
  ShaderReflection r = reflectFile("reflect/all_types.comp");
  EXPECT_EQ(r.localSize, (std::array<uint32_t, 3>{8, 4, 1}));
  EXPECT_EQ(r.pushConstantSize, 0u);
  const VkImageViewType k2D = VK_IMAGE_VIEW_TYPE_2D, k3D = VK_IMAGE_VIEW_TYPE_3D;
  const VkFormat kNone = VK_FORMAT_UNDEFINED;
  const Expected expected[] = {
      {0, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, "params", k2D, kNone},
      {0, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, "values", k2D, kNone},
      {0, 2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, "colorTex", k2D, kNone},
      {0, 3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, "noiseTex", k3D, kNone},
      {0, 4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, "outImage", k2D, VK_FORMAT_R16G16B16A16_SFLOAT},
      {0, 5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, "densityImage", k3D, VK_FORMAT_R32_SFLOAT},
      {1, 0, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 1, "separateTex", k2D, kNone},
      {1, 1, VK_DESCRIPTOR_TYPE_SAMPLER, 1, "linearSampler", k2D, kNone},
      {1, 2, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 3, "volumes", k3D, kNone},
      {1, 3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2, "layers", k2D, VK_FORMAT_R32G32B32A32_SFLOAT},
      {2, 0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, "ldrOut", k2D, VK_FORMAT_R8G8B8A8_UNORM},
      {2, 1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, "mask", k2D, VK_FORMAT_R8_UNORM},
      {2, 2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, "halfImage", k2D, VK_FORMAT_R16_SFLOAT},
      {2, 3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, "noFormat", k2D, kNone},
      {2, 4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, "AnonBlock", k2D, kNone},
      {2, 5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4, "textures", k2D, kNone},
  };
  ASSERT_EQ(r.bindings.size(), std::size(expected));
  for (size_t i = 0; i < std::size(expected); ++i) {
    const Expected& e = expected[i];
    const DescriptorBinding& b = r.bindings[i];  // also checks the (set, binding) order
    SCOPED_TRACE(e.name);
    EXPECT_EQ(b.set, e.set);
    EXPECT_EQ(b.binding, e.binding);
    EXPECT_EQ(b.type, e.type);
    EXPECT_EQ(b.count, e.count);
    EXPECT_EQ(b.name, e.name);
    EXPECT_EQ(b.viewType, e.viewType);
    EXPECT_EQ(b.storageFormat, e.format);
  }
}

TEST(SpirvReflect, PushConstantBlockSize) {
  ShaderReflection r = reflectFile("reflect/push_constants.comp");
  EXPECT_EQ(r.pushConstantSize, 24u);  // vec4 + uint + float
  EXPECT_EQ(r.localSize, (std::array<uint32_t, 3>{16, 16, 1}));
  EXPECT_EQ(reflectFile("reflect/push_matrix.comp").pushConstantSize, 84u);
  EXPECT_EQ(reflectFile("simple.comp").pushConstantSize, 0u);
}

TEST(SpirvReflect, LocalSizeFromSpecializationConstantDefault) {
  EXPECT_EQ(reflectFile("reflect/spec_local_size.comp").localSize,
            (std::array<uint32_t, 3>{32, 2, 1}));
}

// Just enough of an assembler to write modules by hand.
class SpirvBuilder {
public:
  SpirvBuilder() : mWords{spv::MagicNumber, 0x00010000u, 0, 100, 0} {}
  SpirvBuilder& op(spv::Op code, std::vector<uint32_t> operands) {
    mWords.push_back(static_cast<uint32_t>((operands.size() + 1) << 16) | code);
    mWords.insert(mWords.end(), operands.begin(), operands.end());
    return *this;
  }
  SpirvBuilder& name(uint32_t id, const std::string& s) {
    std::vector<uint32_t> operands{id};
    std::vector<uint32_t> packed((s.size() + 4) / 4, 0);
    std::memcpy(packed.data(), s.data(), s.size());
    operands.insert(operands.end(), packed.begin(), packed.end());
    return op(spv::OpName, operands);
  }
  std::vector<uint32_t>& words() { return mWords; }

private:
  std::vector<uint32_t> mWords;
};

// A Vulkan 1.0-style module: an SSBO as Uniform + BufferBlock, a UBO array without a set
// decoration, a push block with a row-major matrix, a WorkgroupSize built-in overriding
// LocalSize.
enum : uint32_t {
  kMain = 1,
  kUint,
  kFloat,
  kRuntimeArray,
  kSsboType,
  kUboType,
  kC16,
  kC2,
  kC1,
  kV3,
  kWg,
  kUboArray,
  kPtrSsbo,
  kPtrUbo,
  kSsbo,
  kUbo,
  kV4,
  kMat3x4,
  kPushType,
  kPtrPush,
  kPush,
  kBound
};

SpirvBuilder legacyModule() {
  SpirvBuilder b;
  b.words()[3] = kBound;
  b.op(spv::OpCapability, {spv::CapabilityShader})
      .op(spv::OpMemoryModel, {spv::AddressingModelLogical, spv::MemoryModelGLSL450})
      .op(spv::OpEntryPoint, {spv::ExecutionModelGLCompute, kMain, 0x6e69616d, 0})  // "main"
      .op(spv::OpExecutionMode, {kMain, spv::ExecutionModeLocalSize, 4, 4, 4})
      .name(kSsbo, "legacySsbo")
      .name(kUbo, "")
      .name(kUboType, "UboBlock")
      .op(spv::OpDecorate, {kSsboType, spv::DecorationBufferBlock})
      .op(spv::OpDecorate, {kUboType, spv::DecorationBlock})
      .op(spv::OpDecorate, {kPushType, spv::DecorationBlock})
      .op(spv::OpDecorate, {kSsbo, spv::DecorationDescriptorSet, 1})
      .op(spv::OpDecorate, {kSsbo, spv::DecorationBinding, 3})
      .op(spv::OpDecorate, {kUbo, spv::DecorationBinding, 2})
      .op(spv::OpDecorate, {kWg, spv::DecorationBuiltIn, spv::BuiltInWorkgroupSize})
      .op(spv::OpDecorate, {kRuntimeArray, spv::DecorationArrayStride, 4})
      .op(spv::OpMemberDecorate, {kSsboType, 0, spv::DecorationOffset, 0})
      .op(spv::OpMemberDecorate, {kUboType, 0, spv::DecorationOffset, 0})
      .op(spv::OpMemberDecorate, {kPushType, 0, spv::DecorationOffset, 0})
      .op(spv::OpMemberDecorate, {kPushType, 1, spv::DecorationOffset, 16})
      .op(spv::OpMemberDecorate, {kPushType, 1, spv::DecorationRowMajor})
      .op(spv::OpMemberDecorate, {kPushType, 1, spv::DecorationMatrixStride, 16})
      .op(spv::OpTypeInt, {kUint, 32, 0})
      .op(spv::OpTypeFloat, {kFloat, 32})
      .op(spv::OpTypeRuntimeArray, {kRuntimeArray, kFloat})
      .op(spv::OpTypeStruct, {kSsboType, kRuntimeArray})
      .op(spv::OpTypeStruct, {kUboType, kUint})
      .op(spv::OpConstant, {kUint, kC16, 16})
      .op(spv::OpConstant, {kUint, kC2, 2})
      .op(spv::OpConstant, {kUint, kC1, 1})
      .op(spv::OpTypeVector, {kV3, kUint, 3})
      .op(spv::OpSpecConstantComposite, {kV3, kWg, kC16, kC2, kC1})
      .op(spv::OpTypeArray, {kUboArray, kUboType, kC2})
      .op(spv::OpTypePointer, {kPtrSsbo, spv::StorageClassUniform, kSsboType})
      .op(spv::OpTypePointer, {kPtrUbo, spv::StorageClassUniform, kUboArray})
      .op(spv::OpVariable, {kPtrSsbo, kSsbo, spv::StorageClassUniform})
      .op(spv::OpVariable, {kPtrUbo, kUbo, spv::StorageClassUniform})
      // Row-major mat3x4 (3 columns of vec4 = 4 rows): 4 rows x stride 16 = 64 bytes,
      // where column-major would be 3 x 16 = 48.
      .op(spv::OpTypeVector, {kV4, kFloat, 4})
      .op(spv::OpTypeMatrix, {kMat3x4, kV4, 3})
      .op(spv::OpTypeStruct, {kPushType, kUint, kMat3x4})
      .op(spv::OpTypePointer, {kPtrPush, spv::StorageClassPushConstant, kPushType})
      .op(spv::OpVariable, {kPtrPush, kPush, spv::StorageClassPushConstant});
  return b;
}

TEST(SpirvReflect, LegacyBufferBlockAndWorkgroupSizeBuiltIn) {
  SpirvBuilder b = legacyModule();
  ShaderReflection r = reflectSpirv(b.words());
  EXPECT_EQ(r.localSize, (std::array<uint32_t, 3>{16, 2, 1}));
  ASSERT_EQ(r.bindings.size(), 2u);
  EXPECT_EQ(r.bindings[0].set, 0u);
  EXPECT_EQ(r.bindings[0].binding, 2u);
  EXPECT_EQ(r.bindings[0].type, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  EXPECT_EQ(r.bindings[0].count, 2u);
  EXPECT_EQ(r.bindings[0].name, "UboBlock");
  EXPECT_EQ(r.bindings[1].set, 1u);
  EXPECT_EQ(r.bindings[1].binding, 3u);
  EXPECT_EQ(r.bindings[1].type, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  EXPECT_EQ(r.bindings[1].name, "legacySsbo");
  EXPECT_EQ(r.pushConstantSize, 80u);  // matrix at 16 + 64
}

TEST(SpirvReflect, PushConstantSizeIsRoundedToFourBytes) {
  // { uint at 0; uint16_t at 4 }: ends at byte 6, Vulkan needs a multiple of 4.
  enum : uint32_t { kU32 = 1, kU16, kBlock, kPtr, kVar, kIds };
  SpirvBuilder b;
  b.words()[3] = kIds;
  b.op(spv::OpMemberDecorate, {kBlock, 0, spv::DecorationOffset, 0})
      .op(spv::OpMemberDecorate, {kBlock, 1, spv::DecorationOffset, 4})
      .op(spv::OpTypeInt, {kU32, 32, 0})
      .op(spv::OpTypeInt, {kU16, 16, 0})
      .op(spv::OpTypeStruct, {kBlock, kU32, kU16})
      .op(spv::OpTypePointer, {kPtr, spv::StorageClassPushConstant, kBlock})
      .op(spv::OpVariable, {kPtr, kVar, spv::StorageClassPushConstant});
  EXPECT_EQ(reflectSpirv(b.words()).pushConstantSize, 8u);
}

void expectInternalError(std::span<const uint32_t> words, const char* what) {
  try {
    reflectSpirv(words);
    ADD_FAILURE() << "accepted " << what;
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Internal) << what;
    EXPECT_EQ(std::string(e.what()).rfind("SPIR-V reflection: ", 0), 0u) << e.what();
  }
}

TEST(SpirvReflect, MalformedModulesAreInternalErrors) {
  expectInternalError({}, "an empty module");
  std::vector<uint32_t> words = legacyModule().words();
  std::vector<uint32_t> badMagic = words;
  badMagic[0] = 0x03022307u;
  expectInternalError(badMagic, "a byte-swapped magic");
  std::vector<uint32_t> zeroCount = words;
  zeroCount[5] = spv::OpCapability;  // word count 0
  expectInternalError(zeroCount, "a zero word count");
  std::vector<uint32_t> overrun = words;
  overrun.back() = 0;
  overrun[overrun.size() - 4] = (40u << 16) | spv::OpVariable;
  expectInternalError(overrun, "an instruction running past the end");
  std::vector<uint32_t> shortOp = words;
  shortOp.insert(shortOp.end(), {(2u << 16) | spv::OpMemberDecorate, kSsboType});
  expectInternalError(shortOp, "an instruction missing operands");
  // Drop the SSBO's struct type: the variable's pointer then points at nothing.
  SpirvBuilder dangling;
  dangling.words()[3] = kBound;
  dangling.op(spv::OpTypePointer, {kPtrSsbo, spv::StorageClassUniform, kSsboType})
      .op(spv::OpVariable, {kPtrSsbo, kSsbo, spv::StorageClassUniform});
  expectInternalError(dangling.words(), "a dangling type id");
  SpirvBuilder outOfBound;
  outOfBound.words()[3] = 5;
  outOfBound.op(spv::OpTypeInt, {7, 32, 0});
  expectInternalError(outOfBound.words(), "an id past the bound");
}

TEST(SpirvReflect, TruncatedOrScrambledRealModulesNeverCrash) {
  std::vector<uint32_t> spirv =
      ShaderCompiler(shaderTestData(), std::nullopt).compile("reflect/all_types.comp").spirv;
  auto attempt = [](std::span<const uint32_t> w) {
    try {
      reflectSpirv(w);
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Internal);
    }
  };
  for (size_t n = 0; n < spirv.size(); n += 7) attempt(std::span(spirv).first(n));
  std::mt19937 rng(1234);
  for (int round = 0; round < 200; ++round) {
    std::vector<uint32_t> scrambled = spirv;
    for (int k = 0; k < 3; ++k) {
      size_t at = 5 + rng() % (scrambled.size() - 5);
      scrambled[at] = (rng() % 4 == 0) ? rng() : scrambled[at] ^ (1u << (rng() % 32));
    }
    attempt(scrambled);
  }
}

TEST(SpirvReflect, FormatMapping) {
  EXPECT_EQ(vkFormatFromSpirv(spv::ImageFormatUnknown), VK_FORMAT_UNDEFINED);
  EXPECT_EQ(vkFormatFromSpirv(spv::ImageFormatRgba32f), VK_FORMAT_R32G32B32A32_SFLOAT);
  EXPECT_EQ(vkFormatFromSpirv(spv::ImageFormatRgba16f), VK_FORMAT_R16G16B16A16_SFLOAT);
  EXPECT_EQ(vkFormatFromSpirv(spv::ImageFormatR32f), VK_FORMAT_R32_SFLOAT);
  EXPECT_EQ(vkFormatFromSpirv(spv::ImageFormatR16f), VK_FORMAT_R16_SFLOAT);
  EXPECT_EQ(vkFormatFromSpirv(spv::ImageFormatRgba8), VK_FORMAT_R8G8B8A8_UNORM);
  EXPECT_EQ(vkFormatFromSpirv(spv::ImageFormatR8), VK_FORMAT_R8_UNORM);
  EXPECT_EQ(vkFormatFromSpirv(spv::ImageFormatR32ui), VK_FORMAT_R32_UINT);
  EXPECT_EQ(vkFormatFromSpirv(spv::ImageFormatR11fG11fB10f), VK_FORMAT_B10G11R11_UFLOAT_PACK32);
  EXPECT_EQ(vkFormatFromSpirv(9999), VK_FORMAT_UNDEFINED);
}

}  // namespace
}  // namespace sky
