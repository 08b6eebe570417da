#pragma once
// Helpers shared by the shader tests: where the test shaders live, and scratch folders.
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

namespace sky::test {

// tests/data/shader: the root for every test that does not build its own tree.
inline std::filesystem::path shaderTestData() {
  const char* v = std::getenv("SKY_TEST_DATA");
  return std::filesystem::path(v && *v ? v : SKY_TEST_DATA_DEFAULT) / "shader";
}

inline void writeText(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  ASSERT_TRUE(out.good()) << path;
}

inline std::string readAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A fresh folder removed again at scope exit; unique per process and per instance so tests
// (and parallel ctest runs) never share one.
class ScratchDir {
public:
  explicit ScratchDir(const std::string& tag) {
    static std::atomic<int> counter{0};
    mPath =
        std::filesystem::temp_directory_path() /
        ("sky-shader-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(mPath);
    std::filesystem::create_directories(mPath);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(mPath, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return mPath; }

private:
  std::filesystem::path mPath;
};

}  // namespace sky::test
