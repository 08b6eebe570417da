// libFuzzer entry for the scene loader (engine/scene/scene_io.h): any input must end in a
// Scene or a sky::Error, never a crash, a leak, a hang or another exception. A loaded Scene
// is written back as YAML and as JSON; each text must load again without error, to the same
// Scene field by field (writeScene promises "loading it gives an identical Scene": checked
// with the tests' expectSameScene, whose gtest failures land in the ad hoc test result),
// and write the same text a second time.
//
// Input layout, so the seed folders (plain scene files) work as they are:
//   [selector] SCENE-TEXT [ "\n--set\n" OVERRIDE-LINE ( "\n" OVERRIDE-LINE )* ]
// A first byte of 0x01 or 0x02 is a selector (YAML or JSON) and is dropped; any other first
// byte is text, and the format is JSON when the first non-blank character is '{' or '['
// (a .json file) and YAML otherwise. Text after the first "\n--set\n" is split into lines,
// each one a `--set key.path=value` override (empty lines are skipped).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/scene/scene_io.h"
#include "tests/scene/scene_compare.h"

namespace {

[[noreturn]] void finding(const char* what, const std::string& detail, const std::string& text) {
  std::fprintf(stderr, "scene_fuzz: %s: %s\n--- text ---\n%s\n--- end ---\n", what,
               detail.c_str(), text.c_str());
  std::abort();
}

// The written text must load again (a sky::Error here is a finding, not bad input) and
// write identically: the writer and the reader agree on every field.
void roundTrip(const sky::Scene& scene, sky::ConfigFormat format) {
  const char* name = format == sky::ConfigFormat::Yaml ? "roundtrip.yaml" : "roundtrip.json";
  const std::string text = sky::writeScene(scene, format);
  sky::Scene reloaded;
  try {
    reloaded = sky::loadSceneText(text, format, name);
  } catch (const sky::Error& e) {
    finding("written scene does not load again", e.what(), text);
  }
  sky::test::expectSameScene(reloaded, scene);  // prints what differs
  if (::testing::UnitTest::GetInstance()->ad_hoc_test_result().Failed())
    finding("written scene loads to a different Scene", "see the gtest failures above", text);
  const std::string again = sky::writeScene(reloaded, format);
  if (again != text) finding("written scene changes on a second round trip", again, text);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string_view input(reinterpret_cast<const char*>(data), size);
  sky::ConfigFormat format = sky::ConfigFormat::Yaml;
  if (!input.empty() && (input[0] == '\x01' || input[0] == '\x02')) {
    format = input[0] == '\x02' ? sky::ConfigFormat::Json : sky::ConfigFormat::Yaml;
    input.remove_prefix(1);
  } else {
    const size_t first = input.find_first_not_of(" \t\r\n");
    if (first != std::string_view::npos && (input[first] == '{' || input[first] == '['))
      format = sky::ConfigFormat::Json;
  }

  std::vector<std::string> overrides;
  constexpr std::string_view kSeparator = "\n--set\n";
  if (const size_t at = input.find(kSeparator); at != std::string_view::npos) {
    std::string_view rest = input.substr(at + kSeparator.size());
    input = input.substr(0, at);
    while (!rest.empty()) {
      const size_t nl = rest.find('\n');
      std::string_view line = rest.substr(0, nl);
      if (!line.empty()) overrides.emplace_back(line);
      rest = nl == std::string_view::npos ? std::string_view() : rest.substr(nl + 1);
    }
  }

  sky::Scene scene;
  try {
    scene = sky::loadSceneText(input,
                               format, format == sky::ConfigFormat::Yaml ? "fuzz.yaml" : "fuzz.json",
                               overrides);
  } catch (const sky::Error& e) {
    // Bad input is expected; anything else escapes and libFuzzer reports it. Messages are
    // one line (engine/core/error.h).
    const std::string message = e.what();
    if (message.find_first_of("\n\r") != std::string::npos)
      finding("error message spans lines", message, std::string(input));
    return 0;
  }
  roundTrip(scene, sky::ConfigFormat::Yaml);
  roundTrip(scene, sky::ConfigFormat::Json);
  return 0;
}
