#pragma once
// File helpers shared by every module that touches the disk.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace sky {

// Refuses, as an input error naming the path, anything that exists but is not a regular file
// or a folder (after symlinks): opening a FIFO blocks until a writer comes, forever for a
// render, and a device such as /dev/zero reads until memory runs out. Call it before a
// library opens the path itself.
void refuseSpecialFile(const std::filesystem::path& path);

// Why `path` is no regular file to read: "file not found", "is a directory, not a file",
// "is a FIFO, not a regular file", ...; "" when it is one (after symlinks).
std::string notARegularFile(const std::filesystem::path& path);

// Reads a whole file; a missing, unreadable or special file is an input error naming the
// path, and so is one larger than `maxBytes`.
std::string readTextFile(const std::filesystem::path& path,
                         std::uintmax_t maxBytes = UINTMAX_MAX);
std::vector<uint8_t> readBinaryFile(const std::filesystem::path& path);

// Writes through a temporary file in the same folder and renames it over `path`, so a
// failure (exception in `write`, full disk) never leaves a partial file behind.
// `write` receives the temporary path and must create it.
void writeFileAtomic(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path& tmp)>& write);
void writeFileAtomic(const std::filesystem::path& path, std::string_view bytes);

// Several files that must appear together or not at all (a render's EXR, PNG and report):
// stage() writes each to a temporary beside its target, commit() renames them all, in the
// order staged (stage the file that marks the set whole last). Files
// staged but not committed are removed when the set goes away (an error on the way).
class AtomicFileSet {
public:
  AtomicFileSet() = default;
  ~AtomicFileSet();
  AtomicFileSet(const AtomicFileSet&) = delete;
  AtomicFileSet& operator=(const AtomicFileSet&) = delete;

  void stage(const std::filesystem::path& path,
             const std::function<void(const std::filesystem::path& tmp)>& write);
  void commit();

private:
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> mStaged;  // (tmp, final)
};

// Removes the temporaries (".tmp-HOST-PID-...") that processes of this host left in `folder`
// when they were killed before they could: those whose process is gone. Returns how many.
// Every output folder is swept when a run opens it (OutputFolder).
int removeStaleTemporaries(const std::filesystem::path& folder);

// An output folder created for a run: create() makes it and any missing parents; unless
// keep() is called (something was written), the folders it made are removed again when it
// goes away, if still empty, so a failed or interrupted run leaves nothing behind. It also
// removes what killed runs left there (removeStaleTemporaries).
class OutputFolder {
public:
  // BadInput "<what> <path>: cannot create folder: <reason>" when it cannot be made.
  OutputFolder(const std::filesystem::path& path, const std::string& what);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;
  const std::filesystem::path& path() const { return mPath; }
  void keep() { mCreated.clear(); }

private:
  std::filesystem::path mPath;
  std::vector<std::filesystem::path> mCreated;  // deepest first
};

// 64-bit FNV-1a, used for cache keys (not for security).
uint64_t hash64(std::string_view bytes, uint64_t seed = 0xcbf29ce484222325ull);
std::string hex64(uint64_t value);

}  // namespace sky
