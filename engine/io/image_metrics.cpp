#include "engine/io/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "engine/core/error.h"

namespace sky {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

void checkSizes(const char* what, std::span<const float> a, std::span<const float> b) {
  if (a.size() != b.size())
    internalError(std::string(what) + ": arrays differ in size (" + std::to_string(a.size()) +
                  " vs " + std::to_string(b.size()) + ")");
  if (a.empty()) internalError(std::string(what) + ": arrays are empty");
}

// Equal values (equal infinities too) differ by 0; any NaN is an infinite difference.
double absDiff(float x, float y) {
  if (x == y) return 0.0;
  const double d = std::abs(double(x) - double(y));
  return std::isnan(d) ? kInf : d;
}

}  // namespace

double psnr(std::span<const float> a, std::span<const float> b, double peak) {
  checkSizes("psnr", a, b);
  if (!(peak > 0.0) || !std::isfinite(peak))
    internalError("psnr: peak " + std::to_string(peak) + " must be a positive finite number");
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double d = absDiff(a[i], b[i]);
    sum += d * d;
  }
  if (sum == 0.0) return kInf;
  const double mse = sum / double(a.size());
  return 10.0 * std::log10(peak * peak / mse);  // -inf when mse is infinite
}

double maxAbsError(std::span<const float> a, std::span<const float> b) {
  checkSizes("maxAbsError", a, b);
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, absDiff(a[i], b[i]));
  return worst;
}

double meanAbsError(std::span<const float> a, std::span<const float> b) {
  checkSizes("meanAbsError", a, b);
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) sum += absDiff(a[i], b[i]);
  return sum / double(a.size());
}

}  // namespace sky
