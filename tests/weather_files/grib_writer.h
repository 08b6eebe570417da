#pragma once
// Writing small GRIB2 messages from ecCodes' samples, for the reader's tests.
#include <eccodes.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace sky::test {

class GribWriter {
public:
  // Starts from one of ecCodes' samples ("regular_ll_pl_grib2", "reduced_gg_pl_32_grib2").
  explicit GribWriter(const char* sample)
      : mHandle(codes_grib_handle_new_from_samples(nullptr, sample)) {
    EXPECT_NE(mHandle.get(), nullptr) << "no ecCodes sample " << sample;
  }
  GribWriter& set(const char* key, long v) {
    EXPECT_EQ(codes_set_long(mHandle.get(), key, v), 0) << key;
    return *this;
  }
  GribWriter& set(const char* key, double v) {
    EXPECT_EQ(codes_set_double(mHandle.get(), key, v), 0) << key;
    return *this;
  }
  GribWriter& set(const char* key, const char* v) {
    size_t len = std::string(v).size();
    EXPECT_EQ(codes_set_string(mHandle.get(), key, v, &len), 0) << key;
    return *this;
  }
  GribWriter& values(const std::vector<double>& v) {
    EXPECT_EQ(codes_set_double_array(mHandle.get(), "values", v.data(), v.size()), 0);
    return *this;
  }
  // The encoded message.
  std::string bytes() const {
    const void* data = nullptr;
    size_t size = 0;
    EXPECT_EQ(codes_get_message(mHandle.get(), &data, &size), 0);
    return std::string(static_cast<const char*>(data), size);
  }
  // Appends the message to `path` (creating it).
  void appendTo(const std::filesystem::path& path) const {
    std::string b = bytes();
    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "ab"), std::fclose);
    ASSERT_TRUE(f);
    ASSERT_EQ(std::fwrite(b.data(), 1, b.size(), f.get()), b.size());
  }

private:
  struct Deleter {
    void operator()(codes_handle* h) const { codes_handle_delete(h); }
  };
  std::unique_ptr<codes_handle, Deleter> mHandle;
};

// This process's scratch directory, removed when the process exits.
inline const std::filesystem::path& tempDir() {
  struct Dir {
    std::filesystem::path path = std::filesystem::path(testing::TempDir()) /
                                 ("sky_weather_files_" + std::to_string(::getpid()));
    Dir() { std::filesystem::create_directories(path); }
    ~Dir() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static Dir dir;
  return dir.path;
}

// A fresh path in the scratch directory.
inline std::filesystem::path tempFile(const std::string& name) {
  const std::filesystem::path& dir = tempDir();
  std::filesystem::path p = dir / name;
  std::filesystem::remove(p);
  return p;
}

// The GFS subset in tests/data/weather (see its README.md).
inline std::filesystem::path gfsFixture() {
  return std::filesystem::path(std::getenv("SKY_TEST_DATA")) / "weather" /
         "gfs_2p5deg_r_gh_t_tcc_uv500.grib2";
}

}  // namespace sky::test
