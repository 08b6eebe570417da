#include "file_watcher.h"

#include <algorithm>
#include <system_error>

namespace sky::view {
namespace fs = std::filesystem;

FileWatcher::FileWatcher(fs::path path, std::chrono::milliseconds interval)
    : mPath(std::move(path)), mInterval(interval), mLastPoll(std::chrono::steady_clock::now()) {
  mLast = snapshot();
}

std::vector<FileWatcher::Entry> FileWatcher::snapshot() const {
  std::vector<Entry> entries;
  std::error_code ec;
  auto add = [&](const fs::path& p) {
    std::error_code e1, e2;
    Entry entry{p.string(), fs::last_write_time(p, e1), fs::file_size(p, e2)};
    if (e1 || e2) entry = {p.string(), {}, static_cast<uintmax_t>(-1)};
    entries.push_back(std::move(entry));
  };
  if (fs::is_directory(mPath, ec)) {
    for (fs::recursive_directory_iterator it(mPath, ec), end; !ec && it != end; it.increment(ec))
      if (it->is_regular_file(ec)) add(it->path());
    std::sort(entries.begin(), entries.end(),
              [](const Entry& a, const Entry& b) { return a.path < b.path; });
  } else if (!mPath.empty()) {
    add(mPath);
  }
  return entries;
}

bool FileWatcher::poll() {
  if (mPath.empty()) return false;
  const auto now = std::chrono::steady_clock::now();
  if (now - mLastPoll < mInterval) return false;
  mLastPoll = now;
  std::vector<Entry> current = snapshot();
  if (current == mLast) return false;
  mLast = std::move(current);
  return true;
}

}  // namespace sky::view
