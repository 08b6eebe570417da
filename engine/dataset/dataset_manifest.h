#pragma once
// A dataset's manifest (docs/datasets.md): JSON Lines, one line per finished sample, appended
// only after the sample's files are in place, so a sample is complete exactly when its line
// exists. An unsharded run writes manifest.jsonl, shard I of N manifest.I-of-N.jsonl, each
// in the output folder; `skyrender merge` joins them.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sky {

// Which share of the work a process takes: the samples (or frames) with index % count ==
// index - 1, for `--shard I/N`; {1, 1} is all of it.
struct Shard {
  int index = 1, count = 1;
  bool all() const { return count == 1; }
  bool takes(int64_t item) const { return item % count == index - 1; }
  std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
};
// "I/N" with 1 <= I <= N <= 100000; anything else is BadInput naming `option`.
Shard parseShard(const std::string& text, const std::string& option);

// The manifest file a run writes into `dir`.
std::filesystem::path manifestPath(const std::filesystem::path& dir, const Shard& shard);

// One manifest's complete lines, in file order. A last line without its newline (the run was
// killed while appending it) is not a line: `torn` says where it starts so the next writer
// cuts it off. A complete line that is no JSON object with an integer "index" is BadInput
// naming file and line.
struct ManifestLines {
  std::vector<nlohmann::ordered_json> lines;
  std::vector<int> lineNumbers;  // of each, from 1
  std::uintmax_t torn = 0;       // byte offset of an unfinished last line; 0 none
  bool hasTorn = false;
};
ManifestLines readManifest(const std::filesystem::path& path);

// Appends one line to a manifest in one write, flushed to the disk, after cutting off an
// unfinished last line a killed run left. BadInput naming the file when it cannot.
class ManifestWriter {
public:
  explicit ManifestWriter(std::filesystem::path path);
  ~ManifestWriter();
  ManifestWriter(const ManifestWriter&) = delete;
  ManifestWriter& operator=(const ManifestWriter&) = delete;
  void append(const nlohmann::ordered_json& line);
  const std::filesystem::path& path() const { return mPath; }

private:
  std::filesystem::path mPath;
  int mFd = -1;
};

// What `skyrender merge` finds in shard folders: every sample's line once, by index.
struct MergeResult {
  std::map<int64_t, nlohmann::ordered_json> samples;  // the first line of each index
  int64_t expected = 0;                               // the spec's count (0: unknown)
  std::vector<int64_t> missing;                       // indices of 0 .. expected - 1 absent
  std::map<int64_t, int> duplicates;                  // index -> how many lines name it
  std::vector<std::filesystem::path> manifests;       // read, in order
};
// Reads the shard manifests (manifest.I-of-N.jsonl) of every folder, and the joined
// manifest.jsonl of every folder but the first (where the result goes). File names of a
// folder other than the first are made relative to the first. Lines of different specs
// (their "spec" checksums differ) are BadInput.
MergeResult mergeManifests(const std::vector<std::filesystem::path>& dirs);
// "0-3, 7, 9-12": indices as ranges, at most `maxItems` of them, then "...".
std::string indexRanges(const std::vector<int64_t>& indices, size_t maxItems = 12);

}  // namespace sky
