#include "engine/shader/shader_compiler.h"

#include <cctype>
#include <functional>
#include <mutex>
#include <regex>
#include <set>
#include <sstream>
#include <string_view>
#include <system_error>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <glslang/build_info.h>

#include "engine/core/files.h"
#include "engine/shader/detail/file_includer.h"
#include "engine/shader/detail/spirv_cache.h"

namespace sky {
namespace fs = std::filesystem;

namespace {

constexpr int kDefaultGlslVersion = 460;  // only used by a shader without #version
// Cascading errors: without them glslang stops at the first error, and a shader author fixing
// a file wants every error in one go. glslang's own test suite runs in this mode; the first
// error, the one in the one-line message, is the same either way.
constexpr auto kMessages =
    static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules | EShMsgCascadingErrors);
// Bump when anything that changes the SPIR-V without changing the source does (options,
// the cache file layout): old cache entries then simply stop matching.
constexpr int kCacheFormat = 1;

// glslang keeps process-wide tables; InitializeProcess must run once before any TShader and
// FinalizeProcess would pull them from under other threads, so it is never called.
void ensureGlslangInitialized() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (!glslang::InitializeProcess()) internalError("glslang: InitializeProcess failed");
  });
}

void configure(glslang::TShader& shader, const char* const* text, const int* length,
               const char* const* name, const std::string& preamble) {
  shader.setStringsWithLengthsAndNames(text, length, name, 1);
  shader.setPreamble(preamble.c_str());
  shader.setEntryPoint("main");
  shader.setEnvInput(glslang::EShSourceGlsl, EShLangCompute, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_6);
}

bool isIdentifier(const std::string& s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
  for (char c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  return true;
}

// The preamble goes in front of the main file without moving its line numbers, and is
// allowed before #version (glslang treats it as a separate string).
std::string makePreamble(const std::vector<ShaderDefine>& defines, const std::string& where) {
  std::string preamble = "#extension GL_GOOGLE_include_directive : require\n";
  for (const ShaderDefine& d : defines) {
    if (!isIdentifier(d.name))
      internalError(where + ": shader define name '" + d.name + "' is not an identifier");
    if (d.value.find_first_of("\r\n") != std::string::npos)
      internalError(where + ": shader define " + d.name + " has a value spanning lines");
    preamble += "#define " + d.name + (d.value.empty() ? "" : " " + d.value) + "\n";
  }
  return preamble;
}

std::string trim(std::string s) {
  size_t b = s.find_first_not_of(" \t\r\n");
  size_t e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// Turns glslang's log ("ERROR: name:line: 'tok' : message" lines and a summary) into one
// line naming the first error, so callers and tests see "file:line: error: ...".
[[noreturn]] void throwCompileError(const std::string& log, const std::string& mainName) {
  static const std::regex kSummary(R"(^\d+ compilation errors?\..*)");
  static const std::regex kLocated(R"(^(.*?):(\d+): (.*)$)");
  std::vector<std::string> errors;
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("ERROR: ", 0) != 0) continue;
    std::string body = trim(line.substr(7));
    // Summary and "compilation terminated" lines repeat an error already counted.
    if (std::regex_match(body, kSummary)) continue;
    if (body.size() >= 22 && body.compare(body.size() - 22, 22, "compilation terminated") == 0)
      continue;
    errors.push_back(body);
  }
  std::string message;
  std::smatch m;
  if (errors.empty()) {
    message = mainName + ": error: " + (trim(log).empty() ? "compilation failed" : trim(log));
  } else if (std::regex_match(errors[0], m, kLocated)) {
    message = m[1].str() + ":" + m[2].str() + ": error: " + trim(m[3].str());
  } else {
    message = mainName + ": error: " + errors[0];
  }
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  if (errors.size() > 1) {
    size_t more = errors.size() - 1;
    message += " (and " + std::to_string(more) + (more == 1 ? " more error)" : " more errors)");
  }
  throw ShaderCompileError(message, log);
}

}  // namespace

const std::string& ShaderCompiler::compilerVersion() {
  static const std::string version = [] {
    glslang::Version v = glslang::GetVersion();
    std::string spirv;
    glslang::GetSpirvVersion(spirv);
    return "glslang " + std::to_string(v.major) + "." + std::to_string(v.minor) + "." +
           std::to_string(v.patch) + v.flavor + " (generator " +
           std::to_string(glslang::GetSpirvGeneratorVersion()) + ", " + spirv +
           "), vulkan1.3/spv1.6, cache format " + std::to_string(kCacheFormat);
  }();
  return version;
}

ShaderCompiler::ShaderCompiler(fs::path shaderRoot, std::optional<fs::path> cacheDirectory)
    : mCacheDir(std::move(cacheDirectory)) {
  mRoot = fs::absolute(shaderRoot).lexically_normal();
  if (mRoot.has_parent_path() && mRoot.filename().empty()) mRoot = mRoot.parent_path();
  mRootName = mRoot.filename().string();
  if (mRootName.empty()) mRootName = mRoot.generic_string();
}

namespace {

// A shader's files as they are on disk: the main file's text and that of every file an
// #include line of it names, recursively, resolved as detail::FileIncluder does (the
// including file's folder, then the root), whatever conditions surround the line. Nothing
// is preprocessed: a comment changes the key. None when a named file is missing (the
// include may sit in a branch the preprocessor drops): such a shader always preprocesses.
struct RawSource {
  uint64_t key = 0;
  std::vector<fs::path> files;
};

std::optional<RawSource> rawSource(const fs::path& mainPath, const std::string& mainText,
                                   const fs::path& root, const std::string& settings) {
  RawSource raw;
  std::string all = "raw1\n" + settings;
  std::set<fs::path> seen;
  std::function<bool(const fs::path&, const std::string&, int)> scan =
      [&](const fs::path& path, const std::string& text, int depth) {
        if (depth > 64 || !seen.insert(path).second) return depth <= 64;
        raw.files.push_back(path);
        all += "\n\x01" + path.string() + "\n" + text;
        size_t line = 0;
        while (line < text.size()) {
          size_t end = text.find('\n', line);
          if (end == std::string::npos) end = text.size();
          std::string_view l(text.data() + line, end - line);
          line = end + 1;
          size_t i = l.find_first_not_of(" \t");
          if (i == std::string_view::npos || l[i] != '#') continue;
          i = l.find_first_not_of(" \t", i + 1);
          if (i == std::string_view::npos || l.substr(i, 7) != "include") continue;
          const size_t open = l.find_first_of("\"<", i + 7);
          if (open == std::string_view::npos) return false;
          const size_t close = l.find_first_of("\">", open + 1);
          if (close == std::string_view::npos) return false;
          const std::string name(l.substr(open + 1, close - open - 1));
          std::error_code ec;
          fs::path next = (path.parent_path() / name).lexically_normal();
          if (!fs::is_regular_file(next, ec)) next = (root / name).lexically_normal();
          if (!fs::is_regular_file(next, ec)) return false;
          std::string nextText;
          try {
            nextText = readTextFile(next);
          } catch (const Error&) {
            return false;
          }
          if (!scan(next, nextText, depth + 1)) return false;
        }
        return true;
      };
  if (!scan(mainPath, mainText, 0)) return std::nullopt;
  raw.key = hash64(all);
  return raw;
}

}  // namespace

CompiledShader ShaderCompiler::compile(const fs::path& relativePath,
                                       const std::vector<ShaderDefine>& defines) {
  ensureGlslangInitialized();

  CompiledShader out;
  out.path = (relativePath.is_absolute() ? relativePath : mRoot / relativePath).lexically_normal();
  detail::FileIncluder includer(mRoot, mRootName);
  const std::string where = includer.displayName(out.path);

  std::error_code ec;
  if (!fs::is_regular_file(out.path, ec)) internalError(where + ": shader file not found");
  if (out.path.extension() != ".comp")
    internalError(where + ": only compute shaders (.comp) are supported");
  const std::string preamble = makePreamble(defines, where);

  // Read once: both passes below must see the same text (the includer keeps a copy so the
  // main file resolves like any other if it includes itself).
  const std::string mainText = readTextFile(out.path);
  const std::string& mainName = includer.addMainFile(out.path, mainText);
  const char* text = mainText.c_str();
  const int length = static_cast<int>(mainText.size());
  const char* name = mainName.c_str();
  const TBuiltInResource* resources = GetDefaultResources();

  // Pass 0: the files as they are. Unchanged since a compile that cached them, they give the
  // SPIR-V's key without glslang (detail::loadSourceIndex).
  const std::optional<RawSource> raw =
      mCacheDir ? rawSource(out.path, mainText, mRoot, compilerVersion() + "\n" + preamble)
                : std::nullopt;
  if (raw) {
    if (const auto key = detail::loadSourceIndex(*mCacheDir, raw->key)) {
      if (auto cached = detail::loadCachedSpirv(*mCacheDir, *key)) {
        try {
          out.reflection = reflectSpirv(*cached);
          out.spirv = std::move(*cached);
          out.sourceHash = *key;
          out.dependencies = raw->files;
          out.fromCache = true;
          return out;
        } catch (const Error&) {
          // Stale: compile as below.
        }
      }
    }
  }

  // Pass 1: preprocess only. Its output (every include expanded, macros applied) is what the
  // cache key hashes, so an edit to any included file or define changes the key.
  std::string preprocessed;
  {
    glslang::TShader shader(EShLangCompute);
    configure(shader, &text, &length, &name, preamble);
    if (!shader.preprocess(resources, kDefaultGlslVersion, ENoProfile, false, false, kMessages,
                           &preprocessed, includer))
      throwCompileError(shader.getInfoLog(), mainName);
  }
  out.dependencies = includer.dependencies();
  std::string keyInput = compilerVersion() + "\n" + preamble;
  out.sourceHash = hash64(preprocessed, hash64(keyInput));

  if (mCacheDir) {
    if (auto cached = detail::loadCachedSpirv(*mCacheDir, out.sourceHash)) {
      try {
        out.reflection = reflectSpirv(*cached);
        out.spirv = std::move(*cached);
        out.fromCache = true;
        if (raw) detail::storeSourceIndex(*mCacheDir, raw->key, out.sourceHash);
        return out;
      } catch (const Error&) {
        // A checksum-valid file that still does not reflect is stale garbage: recompile.
      }
    }
  }

  // Pass 2: the real compile, from the original sources (not the preprocessed text, which
  // glslang documents as not fully supported input) through the same includer snapshot.
  glslang::TShader shader(EShLangCompute);
  configure(shader, &text, &length, &name, preamble);
  if (!shader.parse(resources, kDefaultGlslVersion, ENoProfile, false, false, kMessages, includer))
    throwCompileError(shader.getInfoLog(), mainName);

  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(kMessages)) throwCompileError(program.getInfoLog(), mainName);

  spv::SpvBuildLogger logger;
  glslang::SpvOptions options;
  glslang::GlslangToSpv(*program.getIntermediate(EShLangCompute), out.spirv, &logger, &options);
  // The logger also collects warnings and "TBD functionality" notes; only errors are fatal.
  const std::string spvLog = logger.getAllMessages();
  if (out.spirv.empty() || spvLog.find("error: ") != std::string::npos)
    throwCompileError("ERROR: SPIR-V generation: " + spvLog, mainName);

  out.reflection = reflectSpirv(out.spirv);
  if (mCacheDir) {
    detail::storeCachedSpirv(*mCacheDir, out.sourceHash, out.spirv);
    if (raw) detail::storeSourceIndex(*mCacheDir, raw->key, out.sourceHash);
  }
  return out;
}

}  // namespace sky
