#pragma once
// The star catalogue: the Yale Bright Star Catalogue (configs/stars/, see its README) as unit
// directions in the J2000 equatorial frame with visual magnitudes. Loaded once at start-up.
#include <filesystem>
#include <vector>

#include <glm/vec3.hpp>

namespace sky {

struct Star {
  // Unit vector, J2000 equatorial: x toward RA 0h / Dec 0, y toward RA 6h, z the north pole.
  glm::vec3 directionJ2000;
  float vmag;  // Johnson V magnitude
};

// Reads "dec_deg ra_h vmag" lines ('#' comments and blank lines skipped), strictly: any
// malformed line, a value out of range or a file without stars throws sky::Error
// (BadInput) "path:line: what". Stars keep the file's order.
std::vector<Star> loadStarCatalog(const std::filesystem::path& path);

// Unit J2000 direction of right ascension `raHours` and declination `decDeg`.
glm::vec3 starDirectionJ2000(double raHours, double decDeg);

}  // namespace sky
