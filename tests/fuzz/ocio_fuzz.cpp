// libFuzzer entry for the OCIO config path (engine/color/ocio_output): the input is a config
// file, loaded with OcioOutput::load as `--ocio FILE` does; when it loads, the first view of
// its first display is checked (checkDisplayView builds its processor) and applied to a few
// pixels. Only sky::Error may escape: OCIO's exceptions must come out wrapped, and a crash,
// a leak, a hang or any other exception is a finding.
//
// The file lies alone in a folder of this process's own, so the relative search paths a
// config names resolve there and find nothing, whatever else is in the temp folder.
// OCIO keeps process-wide caches (file lookups, keyed by path, kept for the life of the
// process: a run of fuzzed LUT names grew by about 0.5 KB an input and slowed down), so they
// are cleared after every input; skyrender loads one config a process and is not affected.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <OpenColorIO/OpenColorIO.h>

#include "engine/color/ocio_output.h"
#include "engine/core/error.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // OCIO logs warnings about odd configs to stderr; thousands of them a second drown the
  // fuzzer's own output. An explicit OCIO_LOGGING_LEVEL still wins.
  setenv("OCIO_LOGGING_LEVEL", "none", 0);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path file = [] {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("sky_ocio_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir / "config.ocio";
  }();
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  try {
    const sky::OcioOutput ocio = sky::OcioOutput::load(file);
    const std::vector<std::string> displays = ocio.displays();
    const std::vector<std::string> views =
        displays.empty() ? std::vector<std::string>() : ocio.views(displays.front());
    if (!views.empty()) {
      ocio.checkDisplayView(displays.front(), views.front());
      std::vector<float> rgba = {0.18f, 0.18f, 0.18f, 1.0f, 0.0f,  0.0f,     0.0f, 0.5f,
                                 1e4f,  -1.0f, NAN,   1.0f, 1e-6f, INFINITY, 2.0f, 0.0f};
      ocio.toDisplay(rgba, displays.front(), views.front(), 1.5);
    }
  } catch (const sky::Error&) {
    // Bad input is expected; anything else escapes and libFuzzer reports it.
  }
  OCIO_NAMESPACE::ClearAllCaches();
  return 0;
}
