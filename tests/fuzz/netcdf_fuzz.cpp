// libFuzzer entry for engine/weather/netcdf_reader: any input must end in a WeatherFields or
// a sky::Error, never a crash, a leak or another exception. readNetcdf takes a path (libnetcdf
// opens files by name), so the bytes go through a file of this process's own.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/core/error.h"
#include "engine/weather/netcdf_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      ("sky_netcdf_fuzz_" + std::to_string(::getpid()) + ".nc");
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  try {
    sky::readNetcdf(file);
  } catch (const sky::Error&) {
    // Bad input is expected; anything else escapes and libFuzzer reports it.
  }
  return 0;
}
