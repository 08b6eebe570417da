#include "engine/scene/detail/number_text.h"

#include <charconv>
#include <cmath>
#include <limits>

namespace sky::detail {
namespace {

// YAML 1.2 core schema spells infinity and NaN with a leading dot; from_chars knows only
// "inf"/"nan", which it accepts too. Either way the value is non-finite and the range
// check rejects it with the text as written.
std::optional<double> yamlSpecial(std::string_view t) {
  bool negative = false;
  if (!t.empty() && (t[0] == '+' || t[0] == '-')) {
    negative = t[0] == '-';
    t.remove_prefix(1);
  }
  if (t == ".inf" || t == ".Inf" || t == ".INF")
    return negative ? -std::numeric_limits<double>::infinity()
                    : std::numeric_limits<double>::infinity();
  if (!negative && (t == ".nan" || t == ".NaN" || t == ".NAN"))
    return std::numeric_limits<double>::quiet_NaN();
  return std::nullopt;
}

template <class T>
std::optional<T> parseAs(std::string_view text) {
  if (auto special = yamlSpecial(text)) return static_cast<T>(*special);
  // from_chars rejects a leading '+', which YAML and humans both write.
  if (text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+') text.remove_prefix(1);
  if (text.empty()) return std::nullopt;
  T value{};
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (end != text.data() + text.size()) return std::nullopt;
  if (ec == std::errc::result_out_of_range) {
    // Too large or too small for T: long double has the range to tell overflow (then out
    // of range like infinity) from underflow (a real, tiny number that rounds to 0).
    long double wide = 0;
    auto [wideEnd, wideEc] = std::from_chars(text.data(), text.data() + text.size(), wide);
    if (wideEc != std::errc() || wideEnd != text.data() + text.size())
      return text[0] == '-' ? -std::numeric_limits<T>::infinity()
                            : std::numeric_limits<T>::infinity();
    if (std::fabs(wide) > static_cast<long double>(std::numeric_limits<T>::max()))
      return wide < 0 ? -std::numeric_limits<T>::infinity() : std::numeric_limits<T>::infinity();
    return static_cast<T>(wide);
  }
  if (ec != std::errc()) return std::nullopt;
  return value;
}

template <class T>
std::string format(T value) {
  char buf[64];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, value);
  return ec == std::errc() ? std::string(buf, end) : std::string("nan");
}

}  // namespace

std::optional<double> parseNumber(std::string_view text) {
  return parseAs<double>(text);
}
std::optional<float> parseFloat(std::string_view text) {
  return parseAs<float>(text);
}
std::string formatDouble(double value) {
  return format(value);
}
std::string formatFloat(float value) {
  return format(value);
}

}  // namespace sky::detail
