#pragma once
// Shared helpers for the scene tests.
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "error_capture.h"

namespace sky::test {

// Runs `f`, expects a sky::Error of `kind` and returns its message ("" if none was thrown).
inline std::string errorOf(const std::function<void()>& f, ErrorKind kind = ErrorKind::BadInput) {
  Error e = catchError(f);
  EXPECT_EQ(e.kind(), kind) << e.what();
  return e.what();
}

inline std::filesystem::path sourceDir() {
  const char* v = std::getenv("SKY_DATA_DIR");
  return (v && *v) ? std::filesystem::path(v) : std::filesystem::path(SKY_SOURCE_DIR_DEFAULT);
}

inline std::filesystem::path testDataDir() {
  const char* v = std::getenv("SKY_TEST_DATA");
  return (v && *v) ? std::filesystem::path(v) : sourceDir() / "tests" / "data";
}

}  // namespace sky::test
