#include "engine/dataset/dataset_manifest.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <regex>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace sky {
namespace fs = std::filesystem;

namespace {

// A manifest line is a few hundred bytes; a million samples' manifest stays far below this.
constexpr std::uintmax_t kMaxManifestBytes = std::uintmax_t(2) << 30;

bool isShardManifest(const std::string& name) {
  static const std::regex pattern(R"(^manifest\.[0-9]+-of-[0-9]+\.jsonl$)");
  return std::regex_match(name, pattern);
}

}  // namespace

Shard parseShard(const std::string& text, const std::string& option) {
  const std::string expected =
      option + " '" + text + "': expected I/N, shard I of N (1 <= I <= N), e.g. 2/4";
  const size_t slash = text.find('/');
  if (slash == std::string::npos) inputError(expected);
  Shard s;
  const auto parse = [&](std::string_view part, int& out) {
    auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), out);
    if (ec != std::errc() || end != part.data() + part.size()) inputError(expected);
  };
  parse(std::string_view(text).substr(0, slash), s.index);
  parse(std::string_view(text).substr(slash + 1), s.count);
  if (s.count < 1 || s.count > 100000 || s.index < 1 || s.index > s.count) inputError(expected);
  return s;
}

fs::path manifestPath(const fs::path& dir, const Shard& shard) {
  if (shard.all()) return dir / "manifest.jsonl";
  return dir / ("manifest." + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) +
                ".jsonl");
}

ManifestLines readManifest(const fs::path& path) {
  ManifestLines out;
  std::error_code ec;
  if (!fs::exists(path, ec)) return out;
  const std::string text = readTextFile(path, kMaxManifestBytes);
  size_t start = 0;
  int number = 0;
  while (start < text.size()) {
    const size_t end = text.find('\n', start);
    ++number;
    if (end == std::string::npos) {  // killed while appending: not a line
      out.torn = start;
      out.hasTorn = true;
      break;
    }
    const std::string_view line(text.data() + start, end - start);
    start = end + 1;
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    nlohmann::ordered_json j;
    try {
      j = nlohmann::ordered_json::parse(line);
    } catch (const std::exception& e) {
      inputError(path.string() + ":" + std::to_string(number) + ": not a JSON line: " +
                 std::string(e.what()).substr(0, 120));
    }
    if (!j.is_object() || !j.contains("index") || !j["index"].is_number_integer() ||
        j["index"].get<int64_t>() < 0)
      inputError(path.string() + ":" + std::to_string(number) +
                 ": a manifest line is a JSON object with a whole \"index\" >= 0");
    out.lines.push_back(std::move(j));
    out.lineNumbers.push_back(number);
  }
  return out;
}

ManifestWriter::ManifestWriter(fs::path path) : mPath(std::move(path)) {
  refuseSpecialFile(mPath);
  const ManifestLines existing = readManifest(mPath);
  mFd = ::open(mPath.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (mFd < 0) inputError(mPath.string() + ": cannot open the manifest: " + std::strerror(errno));
  // A line a killed run left half-written: cut off, so the next line starts on its own.
  if (existing.hasTorn && ::ftruncate(mFd, static_cast<off_t>(existing.torn)) != 0)
    inputError(mPath.string() + ": cannot cut off an unfinished line: " + std::strerror(errno));
}

ManifestWriter::~ManifestWriter() {
  if (mFd >= 0) ::close(mFd);
}

void ManifestWriter::append(const nlohmann::ordered_json& line) {
  const std::string text = line.dump() + "\n";
  // One write: O_APPEND places it whole at the end; a short write (a full disk) is an error
  // and the line is cut off again, so no partial line is left for a reader to trip on.
  const off_t before = ::lseek(mFd, 0, SEEK_END);
  const ssize_t n = ::write(mFd, text.data(), text.size());
  if (n != static_cast<ssize_t>(text.size()) || ::fsync(mFd) != 0) {
    const int err = n < 0 ? errno : ENOSPC;
    if (before >= 0 && ::ftruncate(mFd, before) != 0) {
      // Nothing more to do: the torn line is cut off by the next writer.
    }
    inputError(mPath.string() + ": cannot append to the manifest: " + std::strerror(err));
  }
}

MergeResult mergeManifests(const std::vector<fs::path>& dirs) {
  if (dirs.empty()) inputError("merge: no folder given");
  MergeResult r;
  std::string spec;
  fs::path specFrom;
  for (size_t d = 0; d < dirs.size(); ++d) {
    std::error_code ec;
    if (!fs::is_directory(dirs[d], ec)) inputError(dirs[d].string() + ": not a folder");
    std::vector<fs::path> files;
    for (const fs::directory_entry& e : fs::directory_iterator(dirs[d], ec)) {
      const std::string name = e.path().filename().string();
      if (isShardManifest(name) || (d > 0 && name == "manifest.jsonl")) files.push_back(e.path());
    }
    if (ec) inputError(dirs[d].string() + ": cannot list the folder: " + ec.message());
    std::sort(files.begin(), files.end());
    // Names of files in another folder, as seen from the first.
    const fs::path prefix = d == 0 ? fs::path() : fs::relative(dirs[d], dirs[0], ec);
    for (const fs::path& file : files) {
      r.manifests.push_back(file);
      ManifestLines m = readManifest(file);
      for (size_t i = 0; i < m.lines.size(); ++i) {
        nlohmann::ordered_json& line = m.lines[i];
        const std::string where = file.string() + ":" + std::to_string(m.lineNumbers[i]);
        const std::string lineSpec = line.value("spec", std::string());
        if (spec.empty()) {
          spec = lineSpec;
          specFrom = where;
        } else if (lineSpec != spec) {
          inputError(where + ": a sample of another dataset spec than " + specFrom.string() +
                     "'s (their \"spec\" checksums differ)");
        }
        if (line.contains("count") && line["count"].is_number_integer())
          r.expected = std::max<int64_t>(r.expected, line["count"].get<int64_t>());
        if (!prefix.empty() && line.contains("files") && line["files"].is_object())
          for (auto& [kind, f] : line["files"].items())
            if (f.is_object() && f.contains("name") && f["name"].is_string())
              f["name"] = (prefix / f["name"].get<std::string>()).string();
        const int64_t index = line["index"].get<int64_t>();
        if (r.samples.count(index))
          r.duplicates[index] = std::max(r.duplicates[index], 1) + 1;
        else
          r.samples.emplace(index, std::move(line));
      }
    }
  }
  for (int64_t i = 0; i < r.expected; ++i)
    if (!r.samples.count(i)) r.missing.push_back(i);
  return r;
}

std::string indexRanges(const std::vector<int64_t>& indices, size_t maxItems) {
  std::string out;
  size_t items = 0;
  for (size_t i = 0; i < indices.size();) {
    size_t j = i;
    while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) ++j;
    if (items == maxItems) {
      out += ", ...";
      break;
    }
    if (!out.empty()) out += ", ";
    out += std::to_string(indices[i]);
    if (j > i) out += "-" + std::to_string(indices[j]);
    ++items;
    i = j + 1;
  }
  return out;
}

}  // namespace sky
