#pragma once
// Hot reload by polling: the modification times (and sizes) of one file, or of every file under
// a folder. Polling, not inotify, because editors replace files in ways (rename over, delete and
// create) that a watch on the old inode misses, and a stat of ~50 shader files twice a second
// costs nothing next to a frame.
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace sky::view {

class FileWatcher {
public:
  FileWatcher() = default;
  // Takes the first snapshot now. `path` may be a file or a folder (searched recursively).
  explicit FileWatcher(std::filesystem::path path,
                       std::chrono::milliseconds interval = std::chrono::milliseconds(500));

  // At most once per interval: whether anything changed since the last snapshot (a file
  // edited, added or removed). A path that cannot be read counts as a state of its own, so
  // removing and restoring a file both register.
  bool poll();
  const std::filesystem::path& path() const { return mPath; }

private:
  struct Entry {
    std::string path;
    std::filesystem::file_time_type mtime;
    uintmax_t size = 0;
    bool operator==(const Entry&) const = default;
  };
  std::vector<Entry> snapshot() const;

  std::filesystem::path mPath;
  std::chrono::milliseconds mInterval{500};
  std::chrono::steady_clock::time_point mLastPoll;
  std::vector<Entry> mLast;
};

}  // namespace sky::view
