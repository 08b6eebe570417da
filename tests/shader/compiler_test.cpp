// Basic compilation, defines and thread safety, on shaders under tests/data/shader.
#include <thread>

#include "engine/shader/shader_compiler.h"
#include "tests/shader/shader_test_util.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::ScratchDir;
using test::shaderTestData;
using test::writeText;

constexpr uint32_t kSpirvMagic = 0x07230203u;

TEST(ShaderCompiler, CompilesSimpleShaderToSpirv16) {
  ShaderCompiler compiler(shaderTestData(), std::nullopt);
  CompiledShader s = compiler.compile("simple.comp");
  ASSERT_GE(s.spirv.size(), 5u);
  EXPECT_EQ(s.spirv[0], kSpirvMagic);
  EXPECT_EQ(s.spirv[1], 0x00010600u);  // SPIR-V 1.6
  EXPECT_FALSE(s.fromCache);
  EXPECT_NE(s.sourceHash, 0u);
  EXPECT_TRUE(s.path.is_absolute());
  EXPECT_EQ(s.path, (compiler.root() / "simple.comp").lexically_normal());
  EXPECT_EQ(s.dependencies, std::vector<fs::path>{s.path});
  EXPECT_EQ(s.reflection.localSize, (std::array<uint32_t, 3>{8, 4, 1}));
  ASSERT_EQ(s.reflection.bindings.size(), 1u);
  EXPECT_EQ(s.reflection.bindings[0].type, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  EXPECT_EQ(s.reflection.bindings[0].name, "data");
}

TEST(ShaderCompiler, AbsoluteAndRelativePathsGiveTheSameResult) {
  ShaderCompiler compiler(shaderTestData(), std::nullopt);
  CompiledShader rel = compiler.compile("simple.comp");
  CompiledShader abs = compiler.compile(shaderTestData() / "simple.comp");
  EXPECT_EQ(rel.spirv, abs.spirv);
  EXPECT_EQ(rel.sourceHash, abs.sourceHash);
}

TEST(ShaderCompiler, RootIsAbsoluteWithoutTrailingSlash) {
  ShaderCompiler compiler(shaderTestData() / "", std::nullopt);
  EXPECT_TRUE(compiler.root().is_absolute());
  EXPECT_EQ(compiler.root().filename(), "shader");
}

TEST(ShaderCompiler, MissingMainFileIsInternalErrorNamingIt) {
  ShaderCompiler compiler(shaderTestData(), std::nullopt);
  try {
    compiler.compile("no_such_shader.comp");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Internal);
    EXPECT_STREQ(e.what(), "shader/no_such_shader.comp: shader file not found");
  }
}

TEST(ShaderCompiler, RejectsNonComputeStages) {
  ShaderCompiler compiler(shaderTestData(), std::nullopt);
  EXPECT_THROW(compiler.compile("common/math.glsl"), Error);
}

TEST(ShaderCompiler, DefinesReachThePreprocessor) {
  ScratchDir dir("defines");
  writeText(dir.path() / "defined.comp",
            "#version 460\n"
            "#ifndef REQUIRED_FLAG\n#error REQUIRED_FLAG must be defined\n#endif\n"
            "layout(local_size_x = GROUP_X) in;\n"
            "void main() {}\n");
  ShaderCompiler compiler(dir.path(), std::nullopt);
  EXPECT_THROW(compiler.compile("defined.comp"), ShaderCompileError);
  CompiledShader s = compiler.compile("defined.comp", {{"REQUIRED_FLAG", ""}, {"GROUP_X", "16"}});
  EXPECT_EQ(s.reflection.localSize, (std::array<uint32_t, 3>{16, 1, 1}));
  CompiledShader t = compiler.compile("defined.comp", {{"REQUIRED_FLAG", "1"}, {"GROUP_X", "4"}});
  EXPECT_EQ(t.reflection.localSize, (std::array<uint32_t, 3>{4, 1, 1}));
  EXPECT_NE(s.sourceHash, t.sourceHash);
}

TEST(ShaderCompiler, BadDefineNamesAreRejected) {
  ShaderCompiler compiler(shaderTestData(), std::nullopt);
  for (const char* name : {"", "1ABC", "A B", "A;B"}) {
    try {
      compiler.compile("simple.comp", {{name, "1"}});
      ADD_FAILURE() << "accepted define name '" << name << "'";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Internal);
      EXPECT_NE(std::string(e.what()).find("not an identifier"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(compiler.compile("simple.comp", {{"VALUE", "1\n#define X"}}), Error);
}

TEST(ShaderCompiler, ConcurrentCompilesMatchSequentialOnes) {
  ShaderCompiler compiler(shaderTestData(), std::nullopt);
  const std::vector<fs::path> shaders = {"simple.comp", "includes/main.comp",
                                         "reflect/all_types.comp", "reflect/push_matrix.comp"};
  std::vector<std::vector<uint32_t>> expected;
  for (const fs::path& p : shaders) expected.push_back(compiler.compile(p).spirv);

  std::vector<std::string> failures(2);
  auto worker = [&](size_t t) {
    try {
      for (int round = 0; round < 3; ++round)
        for (size_t i = 0; i < shaders.size(); ++i)
          if (compiler.compile(shaders[(i + t) % shaders.size()]).spirv !=
              expected[(i + t) % shaders.size()])
            failures[t] = "different SPIR-V for " + shaders[(i + t) % shaders.size()].string();
    } catch (const std::exception& e) {
      failures[t] = e.what();
    }
  };
  std::thread a(worker, 0), b(worker, 1);
  a.join();
  b.join();
  EXPECT_EQ(failures[0], "");
  EXPECT_EQ(failures[1], "");
}

TEST(ShaderCompiler, CompilerVersionNamesGlslangAndTarget) {
  const std::string& v = ShaderCompiler::compilerVersion();
  EXPECT_NE(v.find("glslang"), std::string::npos) << v;
  EXPECT_NE(v.find("spv1.6"), std::string::npos) << v;
}

}  // namespace
}  // namespace sky
