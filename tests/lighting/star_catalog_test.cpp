// engine/lighting/star_catalog: the shipped Yale Bright Star Catalogue loads with the right
// stars in the right places, and malformed files fail with "path:line: what" (BadInput).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine/core/paths.h"
#include "engine/lighting/star_catalog.h"
#include "error_capture.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr double kPi = 3.14159265358979323846;

fs::path shippedCatalog() {
  return configDir() / "stars" / "bright_star_catalogue.txt";
}

TEST(StarCatalog, ShippedFileHasTheWholeBrightStarCatalogue) {
  const std::vector<Star> stars = loadStarCatalog(shippedCatalog());
  // BSC5 has 9110 entries; 14 are novae or non-stellar objects without positions.
  EXPECT_GE(stars.size(), 9000u);
  EXPECT_LE(stars.size(), 9110u);
  for (const Star& s : stars) ASSERT_NEAR(glm::length(s.directionJ2000), 1.0f, 1e-6f);
}

TEST(StarCatalog, SiriusIsTheBrightestAndWhereItShouldBe) {
  const std::vector<Star> stars = loadStarCatalog(shippedCatalog());
  const auto brightest = std::min_element(
      stars.begin(), stars.end(), [](const Star& a, const Star& b) { return a.vmag < b.vmag; });
  EXPECT_FLOAT_EQ(brightest->vmag, -1.46f);
  // Sirius, J2000: RA 6h 45m 09s = 6.7525 h, Dec -16 deg 42' 58" = -16.7161 deg. Written out
  // here in spherical coordinates, independently of starDirectionJ2000.
  const double ra = 6.7525 * 15.0 * kPi / 180.0, dec = -16.7161 * kPi / 180.0;
  const glm::dvec3 expected(std::cos(dec) * std::cos(ra), std::cos(dec) * std::sin(ra),
                            std::sin(dec));
  const glm::dvec3 got(brightest->directionJ2000);
  EXPECT_LT(glm::length(got - expected), 1e-6) << "Sirius's direction";
  // Sanity of the axes: RA 6.75 h is just past +y, a southern star has z < 0.
  EXPECT_GT(got.y, 0.9);
  EXPECT_LT(got.x, 0.0);
  EXPECT_LT(got.z, -0.28);
  // The axes themselves: RA 0h Dec 0 is +x, RA 6h is +y, Dec +90 is +z.
  EXPECT_LT(glm::length(glm::dvec3(starDirectionJ2000(0.0, 0.0)) - glm::dvec3(1, 0, 0)), 1e-7);
  EXPECT_LT(glm::length(glm::dvec3(starDirectionJ2000(6.0, 0.0)) - glm::dvec3(0, 1, 0)), 1e-7);
  EXPECT_LT(glm::length(glm::dvec3(starDirectionJ2000(3.0, 90.0)) - glm::dvec3(0, 0, 1)), 1e-7);
}

TEST(StarCatalog, MagnitudeHistogramGrowsAboutThreefoldPerMagnitude) {
  const std::vector<Star> stars = loadStarCatalog(shippedCatalog());
  // Stars per whole magnitude [m, m + 1). Stars spread evenly through space would give
  // 10^0.6 = 4 times more per magnitude; the real sky gives about 3 (the galactic disc is
  // thin, interstellar dust). The catalogue is complete to V = 6.5, so the bins up to [5, 6)
  // follow that rule and [6, 7) holds fewer than a full bin would.
  int bins[10] = {};
  for (const Star& s : stars) {
    const int b = static_cast<int>(std::floor(s.vmag)) + 2;  // V -2 -> bin 0
    ASSERT_GE(b, 0);
    ASSERT_LT(b, 10);
    ++bins[b];
  }
  auto count = [&](int m) { return bins[m + 2]; };
  EXPECT_EQ(count(-2), 1) << "only Sirius is brighter than V = -1";
  for (int m = 1; m <= 4; ++m) {
    const double ratio = double(count(m + 1)) / count(m);
    EXPECT_GT(ratio, 2.2) << "stars in [" << m + 1 << ", " << m + 2 << ") vs [" << m << ", "
                          << m + 1 << ")";
    EXPECT_LT(ratio, 4.5) << "stars in [" << m + 1 << ", " << m + 2 << ") vs [" << m << ", "
                          << m + 1 << ")";
  }
  EXPECT_GT(count(6), count(5)) << "V 6..6.5 is still complete";
  EXPECT_LT(count(6), 3 * count(5)) << "the catalogue stops near V = 6.5";
  EXPECT_LT(count(7), count(6) / 10) << "only a few stars fainter than V = 7";
}

class StarCatalogErrors : public ::testing::Test {
protected:
  void SetUp() override {
    mDir = fs::temp_directory_path() /
           ("sky-stars-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(mDir);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(mDir, ec);
  }
  // Writes `text` to a file and returns the error loading it raises.
  Error load(const std::string& text) {
    mPath = mDir / "catalogue.txt";
    std::ofstream(mPath) << text;
    Error e = test::catchError([&] { loadStarCatalog(mPath); });
    EXPECT_EQ(e.kind(), ErrorKind::BadInput) << e.what();
    return e;
  }
  std::string at(int line) const { return mPath.string() + ":" + std::to_string(line) + ": "; }

  fs::path mDir, mPath;
};

TEST_F(StarCatalogErrors, BadNumberNamesLineAndColumn) {
  Error e = load("# header\n-16.7161 6.7525 -1.46\n-52.6958 6.39x2 -0.72\n");
  EXPECT_THAT(e.what(), StartsWith(at(3)));
  EXPECT_THAT(e.what(), HasSubstr("ra_h: '6.39x2' is not a number"));
  e = load("1 2 nan\n");
  EXPECT_THAT(e.what(), StartsWith(at(1)));
  EXPECT_THAT(e.what(), HasSubstr("vmag"));
}

TEST_F(StarCatalogErrors, MissingOrExtraColumn) {
  Error e = load("-16.7161 6.7525 -1.46\n\n-52.6958 6.3992\n");
  EXPECT_THAT(e.what(), StartsWith(at(3)));
  EXPECT_THAT(e.what(), HasSubstr("expected 3 columns"));
  e = load("-16.7161 6.7525 -1.46 2491\n");  // xplanet's BSC number column
  EXPECT_THAT(e.what(), StartsWith(at(1)));
  EXPECT_THAT(e.what(), HasSubstr("found 4"));
}

TEST_F(StarCatalogErrors, ValuesOutOfRange) {
  Error e = load("-16.7161 6.7525 -1.46\n-90.5 6.3992 -0.72\n");
  EXPECT_THAT(e.what(), StartsWith(at(2)));
  EXPECT_THAT(e.what(), HasSubstr("dec_deg: -90.5 is out of range [-90, 90]"));
  e = load("10 24 1\n");
  EXPECT_THAT(e.what(), StartsWith(at(1)));
  EXPECT_THAT(e.what(), HasSubstr("ra_h: 24 is out of range [0, 24)"));
  e = load("10 12 -27\n");
  EXPECT_THAT(e.what(), HasSubstr("vmag: -27 is out of range"));
}

TEST_F(StarCatalogErrors, EmptyFileOrOnlyComments) {
  Error e = load("");
  EXPECT_THAT(e.what(), StartsWith(at(1)));
  EXPECT_THAT(e.what(), HasSubstr("no stars"));
  e = load("# dec_deg ra_h vmag\n\n");
  EXPECT_THAT(e.what(), StartsWith(at(1)));
  EXPECT_THAT(e.what(), HasSubstr("no stars"));
}

TEST_F(StarCatalogErrors, MissingFileIsBadInput) {
  Error e = test::catchError([&] { loadStarCatalog(mDir / "absent.txt"); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_THAT(e.what(), HasSubstr("absent.txt"));
}

TEST_F(StarCatalogErrors, CommentsBlankLinesAndCrlfAreAccepted) {
  mPath = mDir / "ok.txt";
  std::ofstream(mPath) << "# comment\r\n\r\n  -16.7161\t6.7525 -1.46\r\n# another\n0 0 0\n";
  const std::vector<Star> stars = loadStarCatalog(mPath);
  ASSERT_EQ(stars.size(), 2u);
  EXPECT_FLOAT_EQ(stars[0].vmag, -1.46f);
  EXPECT_LT(glm::length(stars[1].directionJ2000 - glm::vec3(1, 0, 0)), 1e-7f);
}

}  // namespace
}  // namespace sky
