#pragma once
// Shared by the colour tests: a scratch folder per test and an $OCIO guard, so a developer's
// own $OCIO never leaks into the results.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "engine/core/error.h"
#include "error_capture.h"

namespace sky::test {

class OcioEnvTest : public ::testing::Test {
protected:
  void SetUp() override {
    if (const char* v = std::getenv("OCIO")) mSavedOcio = v;
    ::unsetenv("OCIO");
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    mDir =
        std::filesystem::temp_directory_path() / ("sky-color-" + std::to_string(::getpid()) + "-" +
                                                  info->test_suite_name() + "-" + info->name());
    std::filesystem::remove_all(mDir);
    std::filesystem::create_directories(mDir);
  }
  void TearDown() override {
    if (mSavedOcio)
      ::setenv("OCIO", mSavedOcio->c_str(), 1);
    else
      ::unsetenv("OCIO");
    std::error_code ec;
    std::filesystem::remove_all(mDir, ec);
  }
  const std::filesystem::path& dir() const { return mDir; }

private:
  std::optional<std::string> mSavedOcio;
  std::filesystem::path mDir;
};

}  // namespace sky::test
