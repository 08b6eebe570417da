#pragma once
// Shared by the io tests: a scratch folder per test, and helpers to check error kinds and
// that failed writes leave nothing behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "error_capture.h"

namespace sky::test {

class ScratchDirTest : public ::testing::Test {
protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    mDir = std::filesystem::temp_directory_path() / ("sky-io-" + std::to_string(::getpid()) + "-" +
                                                     info->test_suite_name() + "-" + info->name());
    std::filesystem::remove_all(mDir);
    std::filesystem::create_directories(mDir);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(mDir, ec);
  }
  const std::filesystem::path& dir() const { return mDir; }

  // Names in the scratch folder, sorted, to prove a failed write left no temporary behind.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(mDir))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

private:
  std::filesystem::path mDir;
};

inline bool mentions(const Error& e, const std::filesystem::path& p) {
  return std::string(e.what()).find(p.string()) != std::string::npos;
}

}  // namespace sky::test
