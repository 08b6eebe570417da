// The CI counterpart of tests/fuzz/scene_fuzz.cpp: deterministic mutations of every scene
// file in configs/ (byte flips, truncations, inserted YAML and JSON punctuation, numbers
// replaced by huge ones, NaN and infinities, lines dropped or doubled, `--set` overrides
// with odd values) through loadSceneText. Each must give a Scene or a BadInput sky::Error
// with a one-line message; a crash or any other exception fails the test. A Scene that
// loads is written out as YAML and as JSON, and each text must load to the same Scene.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/scene/scene_io.h"
#include "tests/scene/scene_compare.h"
#include "tests/scene/scene_test_util.h"

namespace sky {
namespace {

namespace fs = std::filesystem;

struct Base {
  std::string name;
  std::string text;
  ConfigFormat format;
};

// Every scene in configs/ (as SceneFiles finds them: schema/, ocio/ and datasets/ hold no
// scenes).
std::vector<Base> sceneBases() {
  std::vector<Base> bases;
  const fs::path root = test::sourceDir() / "configs";
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator();
       ++it) {
    if (it->is_directory() &&
        (it->path().filename() == "schema" || it->path().filename() == "ocio" ||
         it->path().filename() == "datasets")) {
      it.disable_recursion_pending();
      continue;
    }
    const std::string ext = it->path().extension().string();
    if (!it->is_regular_file() || (ext != ".yaml" && ext != ".yml" && ext != ".json")) continue;
    bases.push_back({fs::relative(it->path(), root).string(), readTextFile(it->path()),
                     formatForPath(it->path())});
  }
  std::sort(bases.begin(), bases.end(),
            [](const Base& a, const Base& b) { return a.name < b.name; });
  return bases;
}

// Punctuation that changes a YAML (or JSON) document's structure: anchors, aliases, merge
// keys, tags, flow collections, block scalars, document markers, tabs, quotes, NUL.
const std::vector<std::string> kTokens = {
    "&a ",   "*a",     "*b",   "<<: *a", "[",   "]",       "{",       "}",  ":",   ": ",
    "\t",    "- ",     "? ",   ",",      "#",   "'",       "\"",      "|",  ">-",  "!!str ",
    "!!binary ", "!<tag:x> ", "---\n", "...\n", "%YAML 1.2\n", "\n", "  ", std::string(1, '\0'),
    "\\u0000", "\xff\xfe", "~", "null", "true", "{}", "[]", "&a [*a]", "\r"};

// Values for a number in the text: past every range and every type's limits, not numbers.
const std::vector<std::string> kNumbers = {
    "1e999",      "-1e999",   "1e-999",     "99999999999999999999999999999999", ".nan",
    ".NaN",       "NaN",      ".inf",       "-.inf",  "Infinity", "-0",    "0x7fffffff",
    "0o777",      "4294967296", "-2147483649", "9223372036854775808", "1.7976931348623157e308",
    "4.9e-324",   "1_000",    "+1",         "1.",     ".5",       "1e",    "0.1e+1000000000",
    std::string(400, '9'), "1." + std::string(400, '1'), std::string(300, '0') + "1"};

// Overrides: the keys of the shipped scenes with values from kNumbers and odd text.
const std::vector<std::string> kOverrideKeys = {
    "camera.latitude", "camera.pitch",  "output.width", "output.name", "time",
    "sun.azimuth",     "sun.elevation", "sky.glow_size", "lighting.palette", "camera",
    "output..width",   "=",             "camera.latitude.x", "palette[0].sky_color", ""};

size_t pick(std::mt19937& rng, size_t n) {
  return n == 0 ? 0 : size_t(rng() % n);
}

std::string mutate(const std::string& base, std::mt19937& rng, int kind) {
  std::string m = base;
  if (m.empty()) return m;
  switch (kind) {
    case 0:  // one to three flipped bits
      for (int i = 0, n = 1 + int(rng() % 3); i < n; ++i)
        m[pick(rng, m.size())] ^= char(1 << (rng() % 8));
      break;
    case 1:  // cut short
      m.resize(pick(rng, m.size()));
      break;
    case 2:  // structural punctuation inserted, one to three times
      for (int i = 0, n = 1 + int(rng() % 3); i < n; ++i)
        m.insert(pick(rng, m.size() + 1), kTokens[pick(rng, kTokens.size())]);
      break;
    case 3: {  // a number replaced by a huge, tiny or non-finite one
      std::vector<size_t> starts;
      for (size_t i = 0; i < m.size(); ++i)
        if (std::isdigit(static_cast<unsigned char>(m[i])) &&
            (i == 0 || !std::isalnum(static_cast<unsigned char>(m[i - 1]))))
          starts.push_back(i);
      if (starts.empty()) break;
      size_t at = starts[pick(rng, starts.size())], end = at;
      while (end < m.size() && (std::isalnum(static_cast<unsigned char>(m[end])) ||
                                m[end] == '.' || m[end] == '-' || m[end] == '+'))
        ++end;
      m.replace(at, end - at, kNumbers[pick(rng, kNumbers.size())]);
      break;
    }
    case 4: {  // a line dropped or doubled
      std::vector<size_t> lines = {0};
      for (size_t i = 0; i < m.size(); ++i)
        if (m[i] == '\n') lines.push_back(i + 1);
      size_t l = pick(rng, lines.size());
      size_t start = lines[l], end = l + 1 < lines.size() ? lines[l + 1] : m.size();
      std::string line = m.substr(start, end - start);
      if (rng() % 2)
        m.erase(start, end - start);
      else
        m.insert(start, line);
      break;
    }
    default:  // one to four random bytes over the text
      for (int i = 0, n = 1 + int(rng() % 4); i < n; ++i) m[pick(rng, m.size())] = char(rng());
      break;
  }
  return m;
}

std::vector<std::string> overrides(std::mt19937& rng) {
  std::vector<std::string> out;
  for (int i = 0, n = 1 + int(rng() % 2); i < n; ++i) {
    std::string value = rng() % 2 ? kNumbers[pick(rng, kNumbers.size())]
                                  : kTokens[pick(rng, kTokens.size())] + "1";
    out.push_back(kOverrideKeys[pick(rng, kOverrideKeys.size())] + "=" + value);
  }
  return out;
}

TEST(SceneFuzz, MutatedConfigsEndInASceneOrABadInputError) {
  const std::vector<Base> bases = sceneBases();
  ASSERT_GE(bases.size(), 5u);
  // The unmutated files load (SceneFiles checks them in full).
  for (const Base& b : bases) EXPECT_NO_THROW(loadSceneText(b.text, b.format, b.name)) << b.name;

  std::mt19937 rng(20240621);
  int errors = 0, loads = 0;
  constexpr int kMutations = 2000;
  for (int i = 0; i < kMutations; ++i) {
    const Base& base = bases[size_t(i) % bases.size()];
    const std::string input = mutate(base.text, rng, (i / int(bases.size())) % 6);
    // Every fifth one also reads the other format's way (a YAML file as JSON and back).
    ConfigFormat format = base.format;
    if (i % 5 == 4) format = format == ConfigFormat::Yaml ? ConfigFormat::Json : ConfigFormat::Yaml;
    std::vector<std::string> sets;
    if (i % 7 == 3) sets = overrides(rng);
    SCOPED_TRACE("mutation " + std::to_string(i) + " of " + base.name);
    try {
      const Scene scene = loadSceneText(input, format, "fuzz", sets);
      ++loads;
      for (ConfigFormat f : {ConfigFormat::Yaml, ConfigFormat::Json}) {
        Scene again;
        ASSERT_NO_THROW(again = loadSceneText(writeScene(scene, f), f, "written"))
            << writeScene(scene, f);
        test::expectSameScene(again, scene);
      }
    } catch (const Error& e) {
      ++errors;
      EXPECT_EQ(e.kind(), ErrorKind::BadInput) << e.what();
      const std::string message = e.what();
      EXPECT_EQ(message.find_first_of("\n\r"), std::string::npos) << message;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not a sky::Error: " << e.what();
    }
    if (HasFatalFailure()) return;
  }
  // Both outcomes occur: the mutations neither all break the files nor all miss.
  EXPECT_GT(errors, kMutations / 10);
  EXPECT_GT(loads, kMutations / 10);
  RecordProperty("loads", loads);
  RecordProperty("errors", errors);
}

}  // namespace
}  // namespace sky
