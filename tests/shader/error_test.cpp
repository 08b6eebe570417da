// Compile errors become one line naming the file and line where the first error is.
#include "engine/shader/shader_compiler.h"
#include "tests/shader/shader_test_util.h"

namespace sky {
namespace {
using test::ScratchDir;
using test::shaderTestData;
using test::writeText;

// Compiles and returns the error; fails the test if it compiled.
ShaderCompileError compileError(const std::filesystem::path& root, const std::string& file) {
  ShaderCompiler compiler(root, std::nullopt);
  try {
    compiler.compile(file);
  } catch (const ShaderCompileError& e) {
    return e;
  }
  ADD_FAILURE() << file << " compiled";
  return ShaderCompileError("", "");
}

TEST(ShaderErrors, SyntaxErrorInMainFileNamesFileAndLine) {
  ShaderCompileError e = compileError(shaderTestData(), "errors/syntax.comp");
  EXPECT_EQ(e.kind(), ErrorKind::Internal);
  EXPECT_EQ(e.exitCode(), 1);
  EXPECT_STREQ(e.what(),
               "shader/errors/syntax.comp:6: error: 'undeclaredThing' : undeclared identifier");
  // The full glslang log stays available for a debug view.
  EXPECT_NE(e.log().find("undeclaredThing"), std::string::npos) << e.log();
  EXPECT_NE(e.log().find("ERROR:"), std::string::npos) << e.log();
}

TEST(ShaderErrors, ErrorInIncludedFileNamesThatFileAndItsLine) {
  ShaderCompileError e = compileError(shaderTestData(), "errors/included_error.comp");
  // glslang's recovery adds a follow-on error in the main file; only the first one matters.
  const std::string first =
      "shader/errors/broken.glsl:4: error: 'missingVariable' : undeclared identifier";
  EXPECT_EQ(std::string(e.what()).rfind(first, 0), 0u) << e.what() << "\n" << e.log();
}

TEST(ShaderErrors, MainFileLinesAreRightAfterAnInclude) {
  ScratchDir dir("err-after");
  writeText(dir.path() / "three_lines.glsl", "// one\n// two\n// three\n");
  writeText(dir.path() / "main.comp",
            "#version 460\n"
            "#include \"three_lines.glsl\"\n"
            "layout(local_size_x = 1) in;\n"
            "void main() {\n"
            "  float x = notDeclaredHere;\n"  // line 5
            "}\n");
  ShaderCompileError e = compileError(dir.path(), "main.comp");
  EXPECT_EQ(std::string(e.what()),
            dir.path().filename().string() +
                "/main.comp:5: error: 'notDeclaredHere' : undeclared identifier")
      << e.log();
}

TEST(ShaderErrors, MissingIncludeNamesIncludingFileAndLine) {
  ShaderCompileError e = compileError(shaderTestData(), "errors/missing_include.comp");
  std::string what = e.what();
  EXPECT_EQ(what.rfind("shader/errors/missing_include.comp:5: error: '#include' : ", 0), 0u)
      << what;
  EXPECT_NE(what.find("common/does_not_exist.glsl"), std::string::npos) << what;
}

TEST(ShaderErrors, CountsTheOtherErrors) {
  ShaderCompileError e = compileError(shaderTestData(), "errors/many.comp");
  EXPECT_STREQ(e.what(),
               "shader/errors/many.comp:6: error: 'firstUndeclared' : undeclared identifier "
               "(and 2 more errors)")
      << e.log();
}

TEST(ShaderErrors, CountsEveryPreprocessorError) {
  ShaderCompileError e = compileError(shaderTestData(), "errors/many_preprocessor.comp");
  EXPECT_STREQ(e.what(),
               "shader/errors/many_preprocessor.comp:3: error: '#include' : file not found "
               "(searched the including file's folder, then shader/) for header name: "
               "missing_one.glsl (and 2 more errors)")
      << e.log();
}

TEST(ShaderErrors, MessagesAreOneLine) {
  for (const char* file :
       {"errors/syntax.comp", "errors/included_error.comp", "errors/missing_include.comp",
        "errors/many.comp", "errors/many_preprocessor.comp"}) {
    ShaderCompileError e = compileError(shaderTestData(), file);
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

TEST(ShaderErrors, FilesOutsideTheRootAreNamedByFullPath) {
  ScratchDir root("err-root"), other("err-other");
  writeText(other.path() / "outside.comp",
            "#version 460\nlayout(local_size_x = 1) in;\nvoid main() { nope(); }\n");
  ShaderCompileError e = compileError(root.path(), (other.path() / "outside.comp").string());
  std::string expected = (other.path() / "outside.comp").generic_string() + ":3: error: ";
  EXPECT_EQ(std::string(e.what()).rfind(expected, 0), 0u) << e.what();
}

}  // namespace
}  // namespace sky
