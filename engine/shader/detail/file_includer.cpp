#include "engine/shader/detail/file_includer.h"

#include <algorithm>
#include <system_error>

#include "engine/core/files.h"

namespace sky::detail {
namespace fs = std::filesystem;

FileIncluder::FileIncluder(fs::path root, std::string rootDisplayName)
    : mRoot(std::move(root)), mRootName(std::move(rootDisplayName)) {}

std::string FileIncluder::displayName(const fs::path& path) const {
  fs::path rel = path.lexically_relative(mRoot);
  if (!rel.empty() && *rel.begin() != "..") return (fs::path(mRootName) / rel).generic_string();
  return path.generic_string();
}

const std::string& FileIncluder::addMainFile(const fs::path& path, std::string text) {
  auto it = mFiles.insert_or_assign(displayName(path), File{path, std::move(text)}).first;
  if (std::find(mDependencies.begin(), mDependencies.end(), path) == mDependencies.end())
    mDependencies.insert(mDependencies.begin(), path);
  return it->first;
}

glslang::TShader::Includer::IncludeResult* FileIncluder::open(const fs::path& candidate) {
  fs::path path = candidate.lexically_normal();
  std::string name = displayName(path);
  auto it = mFiles.find(name);
  if (it == mFiles.end()) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return nullptr;
    try {
      it = mFiles.emplace(name, File{path, readTextFile(path)}).first;
    } catch (const std::exception&) {
      return nullptr;  // unreadable: reported by glslang as an include it cannot process
    }
  }
  if (std::find(mDependencies.begin(), mDependencies.end(), path) == mDependencies.end())
    mDependencies.push_back(path);
  const std::string& text = it->second.text;
  return new IncludeResult(it->first, text.data(), text.size(), nullptr);
}

glslang::TShader::Includer::IncludeResult* FileIncluder::failure(std::string message) {
  const std::string& text = mMessages.emplace_back(std::move(message));
  return new IncludeResult("", text.data(), text.size(), nullptr);
}

glslang::TShader::Includer::IncludeResult* FileIncluder::includeLocal(const char* headerName,
                                                                      const char* includerName,
                                                                      size_t inclusionDepth) {
  if (inclusionDepth > kMaxDepth) return nullptr;  // includeSystem reports it
  auto it = mFiles.find(includerName ? includerName : "");
  if (it == mFiles.end()) return nullptr;  // unknown includer (a user #line): root only
  return open(it->second.path.parent_path() / headerName);
}

glslang::TShader::Includer::IncludeResult* FileIncluder::includeSystem(const char* headerName,
                                                                       const char*,
                                                                       size_t inclusionDepth) {
  if (inclusionDepth > kMaxDepth)
    return failure("include nesting deeper than " + std::to_string(kMaxDepth) +
                   " (recursive include without a guard?)");
  if (IncludeResult* r = open(mRoot / headerName)) return r;
  // glslang appends " for header name: <name>" to this text.
  return failure("file not found (searched the including file's folder, then " + mRootName + "/)");
}

void FileIncluder::releaseInclude(IncludeResult* result) {
  delete result;
}

}  // namespace sky::detail
