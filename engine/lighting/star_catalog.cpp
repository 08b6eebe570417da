#include "engine/lighting/star_catalog.h"

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace sky {
namespace {
constexpr double kPi = 3.14159265358979323846;

// Magnitudes a catalogue star can have: Sirius is -1.46, and anything fainter than 15 is far
// below what a render can show, so a value outside is a broken column, not a star.
constexpr double kMinVmag = -2.0;
constexpr double kMaxVmag = 15.0;

bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

// Splits on blanks; the caller checks the count.
std::vector<std::string_view> fields(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isSpace(line[i])) ++i;
    size_t start = i;
    while (i < line.size() && !isSpace(line[i])) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

}  // namespace

glm::vec3 starDirectionJ2000(double raHours, double decDeg) {
  const double ra = raHours * (kPi / 12.0), dec = decDeg * (kPi / 180.0);
  return glm::vec3(static_cast<float>(std::cos(dec) * std::cos(ra)),
                   static_cast<float>(std::cos(dec) * std::sin(ra)),
                   static_cast<float>(std::sin(dec)));
}

std::vector<Star> loadStarCatalog(const std::filesystem::path& path) {
  const std::string text = readTextFile(path);
  std::vector<Star> stars;
  size_t lineNo = 0;
  auto fail = [&](const std::string& what) {
    inputError(path.string() + ":" + std::to_string(lineNo) + ": " + what);
  };
  auto number = [&](std::string_view field, const char* column) {
    double v = 0;
    auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
    if (ec != std::errc() || end != field.data() + field.size() || !std::isfinite(v))
      fail(std::string(column) + ": '" + std::string(field) + "' is not a number");
    return v;
  };

  size_t pos = 0;
  while (pos < text.size()) {
    size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) eol = text.size();
    const std::string_view line(text.data() + pos, eol - pos);
    pos = eol + 1;
    ++lineNo;
    const std::vector<std::string_view> f = fields(line);
    if (f.empty() || f[0].front() == '#') continue;
    if (f.size() != 3)
      fail("expected 3 columns (dec_deg ra_h vmag), found " + std::to_string(f.size()));
    const double dec = number(f[0], "dec_deg");
    const double ra = number(f[1], "ra_h");
    const double vmag = number(f[2], "vmag");
    if (dec < -90.0 || dec > 90.0)
      fail("dec_deg: " + std::string(f[0]) + " is out of range [-90, 90]");
    if (ra < 0.0 || ra >= 24.0) fail("ra_h: " + std::string(f[1]) + " is out of range [0, 24)");
    if (vmag < kMinVmag || vmag > kMaxVmag)
      fail("vmag: " + std::string(f[2]) + " is out of range [" + std::to_string(int(kMinVmag)) +
           ", " + std::to_string(int(kMaxVmag)) + "]");
    stars.push_back({starDirectionJ2000(ra, dec), static_cast<float>(vmag)});
  }
  if (stars.empty()) {
    lineNo = 1;  // the file as a whole
    fail("no stars in the catalogue (expected lines 'dec_deg ra_h vmag')");
  }
  return stars;
}

}  // namespace sky
