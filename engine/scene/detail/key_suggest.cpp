#include "engine/scene/detail/key_suggest.h"

#include <algorithm>
#include <cctype>

namespace sky::detail {

size_t editDistance(std::string_view a, std::string_view b) {
  // Full table: keys are short, and OSA needs the row before the previous one.
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

std::string suggestKey(std::string_view unknown, const std::vector<std::string>& known) {
  // Case is ignored: "Width" and "verticalFov"-style spellings are common slips.
  auto lower = [](std::string_view s) {
    std::string r(s);
    for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return r;
  };
  std::string u = lower(unknown);
  std::string best;
  size_t bestDistance = 0;
  for (const std::string& k : known) {
    size_t dist = editDistance(u, lower(k));
    if (best.empty() || dist < bestDistance) {
      best = k;
      bestDistance = dist;
    }
  }
  // Up to a third of the key may be wrong (at least 2 edits, so camelCase -> snake_case
  // like "altitudeM" -> "altitude_m" is found), but never a wholesale different word.
  size_t allowed = std::max<size_t>(2, u.size() / 3);
  if (best.empty() || bestDistance > allowed || bestDistance >= u.size()) return {};
  return best;
}

}  // namespace sky::detail
