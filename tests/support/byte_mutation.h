#pragma once
// Deterministic mutations of a binary file for the CI fuzz counterparts (GribFuzz, ImageFuzz):
// flipped bits, a cut, a zeroed run, or a run of 0xff or random bytes, half of them landing in
// the file's first `header` bytes, where the sizes, counts and offsets are.
#include <algorithm>
#include <cstddef>
#include <random>
#include <string>

namespace sky::test {

struct ByteMutation {
  size_t header;      // half the edits land in the first this many bytes
  size_t zeroRunMax;  // the longest zeroed run
  size_t minLength;   // a cut keeps at least this many bytes
};

// Mutation `kind` (0 bit flips, 1 a cut, 2 a zeroed run, otherwise a run of 0xff or random
// bytes) of `base`, drawing from `rng`.
inline std::string mutateBytes(const std::string& base, std::mt19937& rng, int kind,
                               const ByteMutation& how) {
  std::string m = base;
  auto offset = [&](size_t limit) {
    const size_t span = (rng() % 2) ? std::min(limit, how.header) : limit;
    return size_t(rng() % span);
  };
  switch (kind) {
    case 0:  // one to three flipped bits
      for (int i = 0, n = 1 + int(rng() % 3); i < n; ++i)
        m[offset(m.size())] ^= char(1 << (rng() % 8));
      break;
    case 1:  // cut short
      m.resize(how.minLength + offset(m.size() - how.minLength));
      break;
    case 2: {  // a zeroed run
      const size_t at = offset(m.size()), len = 1 + rng() % how.zeroRunMax;
      for (size_t i = at; i < std::min(m.size(), at + len); ++i) m[i] = 0;
      break;
    }
    default: {  // a run of 0xff or random bytes (huge sizes, counts, offsets, scale factors)
      const size_t at = offset(m.size()), len = 1 + rng() % 8;
      const bool ones = rng() % 2;
      for (size_t i = at; i < std::min(m.size(), at + len); ++i) m[i] = char(ones ? 0xff : rng());
      break;
    }
  }
  return m;
}

}  // namespace sky::test
