#include "engine/io/image_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "tests/io/io_test_util.h"

namespace sky {
namespace {
using test::catchError;

const double kInf = std::numeric_limits<double>::infinity();

TEST(ImageMetrics, IdenticalArrays) {
  const std::vector<float> a{0.0f, 0.5f, 1.0f, 100.0f, std::numeric_limits<float>::infinity()};
  EXPECT_EQ(psnr(a, a, 1.0), kInf);
  EXPECT_EQ(maxAbsError(a, a), 0.0);
  EXPECT_EQ(meanAbsError(a, a), 0.0);
}

TEST(ImageMetrics, KnownValues) {
  // MSE 0.25 with peak 1: 10 log10(1 / 0.25) = 6.0206 dB.
  const std::vector<float> a{0.0f, 0.0f, 0.0f, 0.0f};
  const std::vector<float> b{0.5f, -0.5f, 0.5f, -0.5f};
  EXPECT_NEAR(psnr(a, b, 1.0), 10.0 * std::log10(4.0), 1e-12);
  // One 8-bit code off in one of four values, peak 255: MSE 0.25 -> 20 log10(255) + 6.0206.
  const std::vector<float> c{10.0f, 20.0f, 30.0f, 40.0f};
  const std::vector<float> d{10.0f, 21.0f, 30.0f, 40.0f};
  EXPECT_NEAR(psnr(c, d, 255.0), 20.0 * std::log10(255.0) + 10.0 * std::log10(4.0), 1e-9);

  const std::vector<float> e{0.0f, 1.0f, 2.0f, 3.0f};
  const std::vector<float> f{0.0f, 1.5f, 1.0f, 3.0f};
  EXPECT_DOUBLE_EQ(maxAbsError(e, f), 1.0);
  EXPECT_DOUBLE_EQ(meanAbsError(e, f), 0.375);
  EXPECT_DOUBLE_EQ(maxAbsError(f, e), 1.0);  // symmetric
}

TEST(ImageMetrics, NanCountsAsInfiniteError) {
  const std::vector<float> a{0.0f, 1.0f};
  const std::vector<float> b{0.0f, std::nanf("")};
  EXPECT_EQ(maxAbsError(a, b), kInf);
  EXPECT_EQ(meanAbsError(a, b), kInf);
  EXPECT_EQ(psnr(a, b, 1.0), -kInf);
  EXPECT_EQ(maxAbsError(b, b), kInf);  // NaN never equals itself: a NaN render always fails
}

TEST(ImageMetrics, MisuseIsAnInternalError) {
  const std::vector<float> a{0.0f, 1.0f}, b{0.0f}, empty;
  EXPECT_EQ(catchError([&] { psnr(a, b, 1.0); }).kind(), ErrorKind::Internal);
  EXPECT_EQ(catchError([&] { maxAbsError(a, b); }).kind(), ErrorKind::Internal);
  EXPECT_EQ(catchError([&] { meanAbsError(a, b); }).kind(), ErrorKind::Internal);
  EXPECT_EQ(catchError([&] { meanAbsError(empty, empty); }).kind(), ErrorKind::Internal);
  EXPECT_EQ(catchError([&] { psnr(a, a, 0.0); }).kind(), ErrorKind::Internal);
}

}  // namespace
}  // namespace sky
