// The SPIR-V cache: keyed by the preprocessed source, defines and compiler version.
#include "engine/core/files.h"
#include "engine/shader/shader_compiler.h"
#include "tests/shader/shader_test_util.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::readAll;
using test::ScratchDir;
using test::shaderTestData;
using test::writeText;

// A private copy of tests/data/shader plus an empty cache folder, so edits stay local.
struct CacheFixture : ::testing::Test {
  ScratchDir work{"cache"};
  fs::path root = work.path() / "shaders";
  fs::path cache = work.path() / "cache" / "spirv";
  void SetUp() override { fs::copy(shaderTestData(), root, fs::copy_options::recursive); }
  ShaderCompiler compiler() { return ShaderCompiler(root, cache); }
  fs::path cacheFile(uint64_t key) { return cache / (hex64(key) + ".spv"); }
};

TEST_F(CacheFixture, SecondCompileComesFromCacheWithIdenticalResult) {
  ShaderCompiler c = compiler();
  CompiledShader first = c.compile("includes/main.comp");
  EXPECT_FALSE(first.fromCache);
  EXPECT_TRUE(fs::is_regular_file(cacheFile(first.sourceHash)));
  CompiledShader second = c.compile("includes/main.comp");
  EXPECT_TRUE(second.fromCache);
  EXPECT_EQ(second.spirv, first.spirv);
  EXPECT_EQ(second.sourceHash, first.sourceHash);
  EXPECT_EQ(second.dependencies, first.dependencies);
  EXPECT_EQ(second.reflection.localSize, first.reflection.localSize);
  EXPECT_EQ(second.reflection.bindings.size(), first.reflection.bindings.size());
  // A second compiler instance (another run of the program) shares the cache.
  EXPECT_TRUE(compiler().compile("includes/main.comp").fromCache);
}

TEST_F(CacheFixture, ChangingAnIncludedFileMisses) {
  CompiledShader before = compiler().compile("includes/main.comp");
  writeText(root / "common/math.glsl",
            "#ifndef TEST_MATH_GLSL\n#define TEST_MATH_GLSL\n"
            "float testSquare(float x) { return x * x * 1.5; }\n#endif\n");
  CompiledShader after = compiler().compile("includes/main.comp");
  EXPECT_FALSE(after.fromCache);
  EXPECT_NE(after.sourceHash, before.sourceHash);
  EXPECT_NE(after.spirv, before.spirv);
}

TEST_F(CacheFixture, CommentOnlyEditStillHits) {
  CompiledShader before = compiler().compile("includes/main.comp");
  std::string text = readAll(root / "includes/local.glsl");
  writeText(root / "includes/local.glsl",
            "// a new comment on line 1 of the old text\n" + text.substr(text.find('\n') + 1));
  CompiledShader after = compiler().compile("includes/main.comp");
  EXPECT_TRUE(after.fromCache);
  EXPECT_EQ(after.sourceHash, before.sourceHash);
}

TEST_F(CacheFixture, ChangingADefineMisses) {
  ShaderCompiler c = compiler();
  CompiledShader a = c.compile("simple.comp", {{"UNUSED_FLAG", "1"}});
  CompiledShader b = c.compile("simple.comp", {{"UNUSED_FLAG", "2"}});
  CompiledShader none = c.compile("simple.comp");
  EXPECT_FALSE(a.fromCache);
  EXPECT_FALSE(b.fromCache);
  EXPECT_FALSE(none.fromCache);
  EXPECT_NE(a.sourceHash, b.sourceHash);
  EXPECT_NE(a.sourceHash, none.sourceHash);
  EXPECT_TRUE(c.compile("simple.comp", {{"UNUSED_FLAG", "1"}}).fromCache);
}

TEST_F(CacheFixture, CorruptOrShortCacheFilesAreRecompiledAndReplaced) {
  ShaderCompiler c = compiler();
  CompiledShader good = c.compile("simple.comp");
  const fs::path file = cacheFile(good.sourceHash);
  const std::string valid = readAll(file);
  ASSERT_GT(valid.size(), 64u);

  std::string flipped = valid;
  flipped[valid.size() - 9] ^= 0x5a;  // inside the SPIR-V payload
  std::string badMagic = valid;
  badMagic[0] = 'X';
  std::string spirvOnly = valid.substr(32);  // bare SPIR-V without our header
  for (const std::string& corrupt :
       {std::string(), std::string("garbage"), valid.substr(0, 40),
        valid.substr(0, valid.size() - 4), flipped, badMagic, spirvOnly, valid + "trailing"}) {
    writeText(file, corrupt);
    CompiledShader again = c.compile("simple.comp");
    EXPECT_FALSE(again.fromCache) << "accepted a corrupt file of " << corrupt.size() << " bytes";
    EXPECT_EQ(again.spirv, good.spirv);
    EXPECT_EQ(readAll(file), valid) << "the cache file was not rewritten";
    EXPECT_TRUE(c.compile("simple.comp").fromCache);
  }
}

// A process that finds a shader's files unchanged takes the SPIR-V's key from an index of
// their raw text, without starting glslang's preprocessor (~180 ms the first time).
TEST_F(CacheFixture, UnchangedFilesFindTheirSpirvThroughTheSourceIndex) {
  CompiledShader first = compiler().compile("includes/main.comp");
  std::vector<fs::path> indexes;
  for (const auto& e : fs::directory_iterator(cache))
    if (e.path().extension() == ".idx") indexes.push_back(e.path());
  ASSERT_EQ(indexes.size(), 1u);
  CompiledShader second = compiler().compile("includes/main.comp");
  EXPECT_TRUE(second.fromCache);
  EXPECT_EQ(second.sourceHash, first.sourceHash);
  EXPECT_EQ(second.spirv, first.spirv);
  // A torn index is a miss: the preprocessed key still finds the SPIR-V, and the index is
  // written again.
  writeText(indexes[0], "torn");
  EXPECT_TRUE(compiler().compile("includes/main.comp").fromCache);
  EXPECT_EQ(fs::file_size(indexes[0]), 32u);
  // An index whose SPIR-V is gone compiles again.
  fs::remove(cacheFile(first.sourceHash));
  CompiledShader third = compiler().compile("includes/main.comp");
  EXPECT_FALSE(third.fromCache);
  EXPECT_EQ(third.spirv, first.spirv);
  // A changed included file changes the index's key too.
  writeText(root / "common/math.glsl",
            "#ifndef TEST_MATH_GLSL\n#define TEST_MATH_GLSL\n"
            "float testSquare(float x) { return x * x * 2.5; }\n#endif\n");
  EXPECT_NE(compiler().compile("includes/main.comp").spirv, first.spirv);
}

TEST_F(CacheFixture, NoCacheDirectoryMeansNoCache) {
  ShaderCompiler c(root, std::nullopt);
  EXPECT_FALSE(c.compile("simple.comp").fromCache);
  EXPECT_FALSE(c.compile("simple.comp").fromCache);
  EXPECT_FALSE(fs::exists(cache));
}

TEST_F(CacheFixture, UnwritableCacheIsOnlySlower) {
  // A regular file where the cache folder should be: every store fails.
  writeText(work.path() / "blocked", "not a folder");
  ShaderCompiler c(root, work.path() / "blocked" / "spirv");
  CompiledShader s = c.compile("simple.comp");
  EXPECT_FALSE(s.fromCache);
  EXPECT_FALSE(s.spirv.empty());
  EXPECT_FALSE(c.compile("simple.comp").fromCache);
}

TEST_F(CacheFixture, CompileErrorsAreNeverCached) {
  ShaderCompiler c = compiler();
  EXPECT_THROW(c.compile("errors/syntax.comp"), ShaderCompileError);
  EXPECT_THROW(c.compile("errors/syntax.comp"), ShaderCompileError);
  EXPECT_TRUE(!fs::exists(cache) || fs::is_empty(cache));
}

}  // namespace
}  // namespace sky
