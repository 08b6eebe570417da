#include <cstdlib>

#include <gtest/gtest.h>

#include "gpu_test.h"

int main(int argc, char** argv) {
  // Set here rather than by ctest so a test binary run by hand behaves the same.
  setenv("SKY_VALIDATION", "1", 1);
  setenv("SKY_DATA_DIR", SKY_TEST_SOURCE_DIR, 0);
  setenv("SKY_TEST_DATA", SKY_TEST_SOURCE_DIR "/tests/data", 0);
  setenv("SKY_CACHE_DIR", SKY_TEST_CACHE_DIR, 0);
  setenv("SKY_SKYRENDER", SKY_TEST_SKYRENDER, 0);
  testing::InitGoogleTest(&argc, argv);
  int rc = RUN_ALL_TESTS();
  // Objects leaked past the tests show up as validation messages on device destruction.
  return rc | sky::test::shutdownSharedContext();
}
