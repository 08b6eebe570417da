#include "engine/core/files.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <csignal>
#include <signal.h>
#include <cstdlib>
#include <unistd.h>

#include "engine/core/error.h"
#include "engine/core/fault_injection.h"

namespace sky {
namespace fs = std::filesystem;

namespace {
// What a special file is ("a FIFO"), or nullptr for a regular file, a folder or nothing.
const char* specialKind(const fs::file_status& st) {
  switch (st.type()) {
    case fs::file_type::fifo:
      return "a FIFO";
    case fs::file_type::socket:
      return "a socket";
    case fs::file_type::character:
      return "a character device";
    case fs::file_type::block:
      return "a block device";
    case fs::file_type::regular:
    case fs::file_type::directory:
    case fs::file_type::not_found:
      return nullptr;
    default:
      return "something";
  }
}
}  // namespace

void refuseSpecialFile(const fs::path& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // follows symlinks
  if (ec) return;  // missing or unreadable: the open that follows says so
  if (const char* kind = specialKind(st))
    inputError(path.string() + ": is " + kind + ", not a regular file");
}

std::string notARegularFile(const fs::path& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // follows symlinks
  if (st.type() == fs::file_type::regular) return "";
  if (st.type() == fs::file_type::directory) return "is a directory, not a file";
  if (const char* kind = specialKind(st)) return std::string("is ") + kind + ", not a regular file";
  if (ec && ec != std::errc::no_such_file_or_directory) return "cannot be read: " + ec.message();
  return "file not found";
}

namespace {

// The whole of `path` into a container of bytes: one allocation of the file's size and one
// read into it (a cache file of megabytes is read at start-up), then whatever the file grew
// by since its size was taken.
template <class Bytes>
Bytes readWholeFile(const fs::path& path, std::uintmax_t maxBytes) {
  // An ifstream opens a folder and reads it as empty: say what it is instead.
  std::error_code ec;
  if (fs::is_directory(path, ec)) inputError(path.string() + ": is a directory, not a file");
  refuseSpecialFile(path);
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > maxBytes)
    inputError(path.string() + ": is " + std::to_string(size) + " bytes, more than the " +
               std::to_string(maxBytes) + " read from it");
  std::ifstream in(path, std::ios::binary);
  if (!in) inputError(path.string() + ": cannot open file: " + std::strerror(errno));
  Bytes out(ec ? 0 : static_cast<size_t>(size), 0);
  in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(out.size()));
  out.resize(static_cast<size_t>(in.gcount()));
  if (in.bad()) inputError(path.string() + ": read error");
  if (!in.eof()) {
    in.clear();
    char chunk[65536];
    while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
      out.insert(out.end(), chunk, chunk + in.gcount());
      if (out.size() > maxBytes)
        inputError(path.string() + ": grew past the " + std::to_string(maxBytes) +
                   " bytes read from it");
    }
    if (in.bad()) inputError(path.string() + ": read error");
  }
  return out;
}

}  // namespace

std::string readTextFile(const fs::path& path, std::uintmax_t maxBytes) {
  return readWholeFile<std::string>(path, maxBytes);
}

std::vector<uint8_t> readBinaryFile(const fs::path& path) {
  return readWholeFile<std::vector<uint8_t>>(path, std::numeric_limits<std::uintmax_t>::max());
}

namespace {
// ".tmp-HOST-": the start of this host's temporaries. The host is in the name because an
// output folder may be shared by the nodes of a cluster, where a process id says nothing
// about another machine's processes.
std::string temporaryPrefix() {
  static const std::string prefix = [] {
    char host[256] = {};
    if (::gethostname(host, sizeof host - 1) != 0 || !host[0]) std::strcpy(host, "localhost");
    return ".tmp-" + std::string(host) + "-";
  }();
  return prefix;
}

// A unique temporary beside `path`, ".tmp-HOST-PID-N-NAME": it keeps the final extension so
// format libraries that look at it still work, and names the process that owns it
// (removeStaleTemporaries).
fs::path temporaryFor(const fs::path& path) {
  static std::atomic<unsigned> counter{0};
  fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  return dir / (temporaryPrefix() + std::to_string(::getpid()) + "-" + std::to_string(counter++) +
                "-" + path.filename().string());
}

// Runs write(tmp); an error it throws names the file the caller asked for, not the
// temporary (a user never sees .tmp-... names).
void writeNaming(const fs::path& tmp, const fs::path& path,
                 const std::function<void(const fs::path&)>& write) {
  try {
    write(tmp);
  } catch (const Error& e) {
    std::string what = e.what();
    const std::string from = tmp.string(), to = path.string();
    for (size_t at = what.find(from); at != std::string::npos; at = what.find(from, at + to.size()))
      what.replace(at, from.size(), to);
    const std::string name = tmp.filename().string(), finalName = path.filename().string();
    for (size_t at = what.find(name); at != std::string::npos;
         at = what.find(name, at + finalName.size()))
      what.replace(at, name.size(), finalName);
    throw Error(e.kind(), what);
  }
}

}  // namespace

void writeFileAtomic(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  fs::path tmp = temporaryFor(path);
  try {
    writeNaming(tmp, path, write);
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) inputError(path.string() + ": cannot write file: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

void writeFileAtomic(const fs::path& path, std::string_view bytes) {
  writeFileAtomic(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) inputError(path.string() + ": cannot write file: " + std::strerror(errno));
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) inputError(path.string() + ": write failed (disk full?)");
  });
}

AtomicFileSet::~AtomicFileSet() {
  std::error_code ignored;
  for (const auto& [tmp, final] : mStaged) fs::remove(tmp, ignored);
}

void AtomicFileSet::stage(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  fs::path tmp = temporaryFor(path);
  mStaged.emplace_back(tmp, path);  // registered first so a throwing writer is cleaned up
  writeNaming(tmp, path, write);
  if (!fs::exists(tmp)) internalError(path.string() + ": writer produced no file");
}

void AtomicFileSet::commit() {
  // A rename that would fail (a folder in the file's place) is found before any is made, so
  // the set is not left half in place.
  for (const auto& [tmp, final] : mStaged) {
    std::error_code ec;
    if (fs::is_directory(final, ec))
      inputError(final.string() + ": cannot write file: a folder of that name exists");
  }
  for (const auto& [tmp, final] : mStaged) {
    std::error_code ec;
    fs::rename(tmp, final, ec);
    if (ec) inputError(final.string() + ": cannot write file: " + ec.message());
    if (faultAt(FaultPoint::KillAfterRename)) ::raise(SIGKILL);  // a crash mid-commit, for tests
  }
  mStaged.clear();
}

int removeStaleTemporaries(const fs::path& folder) {
  const std::string prefix = temporaryPrefix();
  int removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const size_t digits = name.find_first_not_of("0123456789", prefix.size());
    if (digits == prefix.size() || digits == std::string::npos || name[digits] != '-') continue;
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    // Only a process that is gone: kill(pid, 0) fails with ESRCH. A live one (or one this
    // user may not signal, EPERM) may still be writing.
    if (pid <= 0 || pid == ::getpid() || ::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;
    std::error_code removeError;
    if (it->is_regular_file(removeError) && fs::remove(it->path(), removeError)) ++removed;
  }
  return removed;
}

OutputFolder::OutputFolder(const fs::path& path, const std::string& what) : mPath(path) {
  std::error_code ec;
  // The folders that do not exist yet, deepest first: those are ours to remove again.
  fs::path p = fs::absolute(path, ec).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();  // written with a trailing '/'
  while (!p.empty() && !fs::exists(p, ec)) {
    mCreated.push_back(p);
    if (p == p.parent_path()) break;
    p = p.parent_path();
  }
  fs::create_directories(path, ec);
  if (ec || !fs::is_directory(path)) {
    const std::string reason = ec ? ec.message()
                                  : (fs::exists(path) ? std::string("a file of that name exists")
                                                      : std::string("unknown"));
    mCreated.clear();
    inputError(what + " " + path.string() + ": cannot create folder: " + reason);
  }
  removeStaleTemporaries(path);
}

OutputFolder::~OutputFolder() {
  std::error_code ec;
  for (const fs::path& p : mCreated)
    if (!fs::remove(p, ec)) break;  // not empty (or gone): leave it and what holds it
}

uint64_t hash64(std::string_view bytes, uint64_t seed) {
  uint64_t h = seed;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

std::string hex64(uint64_t value) {
  static const char* kDigits = "0123456789abcdef";
  std::string s(16, '0');
  for (int i = 15; i >= 0; --i, value >>= 4) s[static_cast<size_t>(i)] = kDigits[value & 0xf];
  return s;
}

}  // namespace sky
