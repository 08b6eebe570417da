// #include resolution: next to the including file first, then the shader root; guards;
// dependency lists for hot reload.
#include "engine/shader/shader_compiler.h"
#include "tests/shader/shader_test_util.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::ScratchDir;
using test::shaderTestData;
using test::writeText;

const char* kMain =
    "layout(local_size_x = 1) in;\n"
    "layout(std430, binding = 0) buffer Out { float result[]; };\n";

TEST(ShaderIncludes, RelativeRootRelativeNestedAndGuarded) {
  ShaderCompiler compiler(shaderTestData(), std::nullopt);
  CompiledShader s = compiler.compile("includes/main.comp");
  const fs::path root = compiler.root();
  // First-inclusion order; math.glsl is reached three ways but listed once.
  std::vector<fs::path> expected = {root / "includes/main.comp", root / "includes/local.glsl",
                                    root / "common/math.glsl", root / "common/nested.glsl"};
  EXPECT_EQ(s.dependencies, expected);
}

TEST(ShaderIncludes, QuotedPrefersIncludingFolderAngleUsesRootOnly) {
  ScratchDir dir("inc-order");
  // Same relative name twice: sub/common/pick.glsl (local to sub/) and common/pick.glsl (root).
  writeText(dir.path() / "common/pick.glsl", "const float kRootPick = 1.0;\n");
  writeText(dir.path() / "sub/common/pick.glsl", "const float kLocalPick = 2.0;\n");
  writeText(
      dir.path() / "sub/main.comp",
      std::string("#version 460\n#include \"common/pick.glsl\"\n#include <common/pick.glsl>\n") +
          kMain + "void main() { result[0] = kLocalPick + kRootPick; }\n");
  ShaderCompiler compiler(dir.path(), std::nullopt);
  CompiledShader s = compiler.compile("sub/main.comp");
  const fs::path root = compiler.root();
  std::vector<fs::path> expected = {root / "sub/main.comp", root / "sub/common/pick.glsl",
                                    root / "common/pick.glsl"};
  EXPECT_EQ(s.dependencies, expected);
}

TEST(ShaderIncludes, QuotedFallsBackToRoot) {
  ScratchDir dir("inc-fallback");
  writeText(dir.path() / "lib/helper.glsl", "float helper() { return 3.0; }\n");
  writeText(dir.path() / "passes/deep/main.comp",
            std::string("#version 460\n#include \"lib/helper.glsl\"\n") + kMain +
                "void main() { result[0] = helper(); }\n");
  ShaderCompiler compiler(dir.path(), std::nullopt);
  CompiledShader s = compiler.compile("passes/deep/main.comp");
  ASSERT_EQ(s.dependencies.size(), 2u);
  EXPECT_EQ(s.dependencies[1], compiler.root() / "lib/helper.glsl");
}

TEST(ShaderIncludes, GuardsAreWhatMakesDoubleInclusionWork) {
  ScratchDir dir("inc-guard");
  writeText(dir.path() / "unguarded.glsl", "float twice() { return 1.0; }\n");
  writeText(dir.path() / "guarded.glsl",
            "#ifndef GUARDED\n#define GUARDED\nfloat once() { return 1.0; }\n#endif\n");
  writeText(dir.path() / "good.comp",
            std::string("#version 460\n#include \"guarded.glsl\"\n#include \"guarded.glsl\"\n") +
                kMain + "void main() { result[0] = once(); }\n");
  writeText(
      dir.path() / "bad.comp",
      std::string("#version 460\n#include \"unguarded.glsl\"\n#include \"unguarded.glsl\"\n") +
          kMain + "void main() { result[0] = twice(); }\n");
  ShaderCompiler compiler(dir.path(), std::nullopt);
  EXPECT_NO_THROW(compiler.compile("good.comp"));
  try {
    compiler.compile("bad.comp");
    FAIL() << "double definition was accepted";
  } catch (const ShaderCompileError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(dir.path().filename().string() + "/unguarded.glsl:1:", 0),
              0u)
        << e.what();
  }
}

TEST(ShaderIncludes, RecursiveIncludeIsAnErrorNotAHang) {
  ScratchDir dir("inc-recursive");
  writeText(dir.path() / "loop.glsl", "#include \"loop.glsl\"\n");
  writeText(dir.path() / "main.comp",
            std::string("#version 460\n#include \"loop.glsl\"\n") + kMain + "void main() {}\n");
  ShaderCompiler compiler(dir.path(), std::nullopt);
  try {
    compiler.compile("main.comp");
    FAIL() << "a recursive include compiled";
  } catch (const ShaderCompileError& e) {
    EXPECT_EQ(
        std::string(e.what()).rfind(dir.path().filename().string() + "/loop.glsl:1: error:", 0), 0u)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("recursive include"), std::string::npos) << e.what();
  }
}

TEST(ShaderIncludes, ShadersMayStillEnableTheExtensionThemselves) {
  ScratchDir dir("inc-ext");
  writeText(dir.path() / "lib.glsl", "float lib() { return 1.0; }\n");
  writeText(dir.path() / "main.comp",
            std::string("#version 460\n#extension GL_GOOGLE_include_directive : require\n"
                        "#include \"lib.glsl\"\n") +
                kMain + "void main() { result[0] = lib(); }\n");
  ShaderCompiler compiler(dir.path(), std::nullopt);
  EXPECT_EQ(compiler.compile("main.comp").dependencies.size(), 2u);
}

TEST(ShaderIncludes, IncludesInDisabledBranchesAreNotResolved) {
  ScratchDir dir("inc-disabled");
  writeText(dir.path() / "main.comp",
            std::string("#version 460\n#if 0\n#include \"nowhere.glsl\"\n#endif\n") + kMain +
                "void main() {}\n");
  ShaderCompiler compiler(dir.path(), std::nullopt);
  CompiledShader s = compiler.compile("main.comp");
  EXPECT_EQ(s.dependencies.size(), 1u);
}

}  // namespace
}  // namespace sky
