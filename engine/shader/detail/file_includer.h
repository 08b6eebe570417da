#pragma once
// glslang #include resolution for one compile (Debian's glslang ships no DirStackFileIncluder).
#include <deque>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <glslang/Public/ShaderLang.h>

namespace sky::detail {

// Resolves "" includes next to the including file first, then under the shader root; <>
// includes under the root only. Every file read is kept, so a second pass (preprocess, then
// parse) sees the same text even if the file changes on disk in between. One instance per
// compile; not shared between threads.
class FileIncluder final : public glslang::TShader::Includer {
public:
  FileIncluder(std::filesystem::path root, std::string rootDisplayName);

  // Registers the main file before the first pass; returns the name glslang reports it by.
  const std::string& addMainFile(const std::filesystem::path& path, std::string text);

  IncludeResult* includeLocal(const char* headerName, const char* includerName,
                              size_t inclusionDepth) override;
  IncludeResult* includeSystem(const char* headerName, const char* includerName,
                               size_t inclusionDepth) override;
  void releaseInclude(IncludeResult* result) override;

  // Name used in #line directives and messages: "<root folder>/<relative>" under the root,
  // else the absolute path. Valid any time.
  std::string displayName(const std::filesystem::path& path) const;
  // Main file then every included file in first-inclusion order; valid after a pass.
  const std::vector<std::filesystem::path>& dependencies() const { return mDependencies; }

private:
  struct File {
    std::filesystem::path path;
    std::string text;
  };
  IncludeResult* open(const std::filesystem::path& candidate);
  IncludeResult* failure(std::string message);

  static constexpr size_t kMaxDepth = 32;
  std::filesystem::path mRoot;
  std::string mRootName;
  std::map<std::string, File> mFiles;  // by display name, the key glslang hands back to us
  std::vector<std::filesystem::path> mDependencies;
  std::deque<std::string> mMessages;  // failure texts; IncludeResult points into them
};

}  // namespace sky::detail
