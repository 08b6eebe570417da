#pragma once
// Error metrics over two equally sized float arrays, used by golden-image tests.
// Sizes that differ, or empty inputs, are internal errors (a test comparing nothing must
// not pass). Equal values (including equal infinities) differ by 0; a NaN on either side
// counts as an infinite error so a NaN in a render always fails a comparison.
#include <span>

namespace sky {

// 10 log10(peak^2 / MSE) in dB; +infinity when the arrays are identical. peak must be > 0.
double psnr(std::span<const float> a, std::span<const float> b, double peak);
// Largest |a[i] - b[i]|.
double maxAbsError(std::span<const float> a, std::span<const float> b);
// Mean of |a[i] - b[i]|.
double meanAbsError(std::span<const float> a, std::span<const float> b);

}  // namespace sky
