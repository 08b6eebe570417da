// The CI counterpart of tests/fuzz/grib_fuzz.cpp: deterministic mutations (bit flips,
// truncations, zeroed and overwritten ranges) of three small GRIB2 messages of different
// packings through readGrib2. Each must give consistent WeatherFields or a sky::Error; a crash,
// an abort inside ecCodes or any other exception fails the test.
#include <eccodes.h>

#include <cstdio>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/weather/grib_reader.h"
#include "byte_mutation.h"
#include "grib_writer.h"

namespace sky {
namespace {

std::string readAll(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The fixture's low cloud-layer cover: complex packing with spatial differencing.
std::string gfsLowCloudMessage() {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(test::gfsFixture().c_str(), "rb"),
                                          std::fclose);
  if (!f) return {};
  int err = 0;
  while (codes_handle* h = codes_handle_new_from_file(nullptr, f.get(), PRODUCT_GRIB, &err)) {
    std::unique_ptr<codes_handle, int (*)(codes_handle*)> owner(h, codes_handle_delete);
    char level[64] = {};
    size_t len = sizeof level;
    if (codes_get_string(h, "typeOfLevel", level, &len) == 0 &&
        std::string(level) == "lowCloudLayer") {
      const void* data = nullptr;
      size_t size = 0;
      if (codes_get_message(h, &data, &size) != 0) break;
      std::string bytes(static_cast<const char*>(data), size);
      codes_grib_multi_support_reset_file(codes_context_get_default(), f.get());
      return bytes;
    }
  }
  codes_grib_multi_support_reset_file(codes_context_get_default(), f.get());
  return {};
}

TEST(GribFuzz, MutatedFixturesNeverCrash) {
  std::vector<std::string> bases;
  {
    std::vector<double> v(48);
    for (size_t i = 0; i < v.size(); ++i) v[i] = (i % 7 == 3) ? 9999.0 : double(i * 2);
    test::GribWriter w("regular_ll_pl_grib2");
    w.set("Ni", 8L).set("Nj", 6L).set("numberOfDataPoints", 48L);
    w.set("latitudeOfFirstGridPointInDegrees", 50.0).set("latitudeOfLastGridPointInDegrees", 25.0);
    w.set("longitudeOfFirstGridPointInDegrees", 0.0).set("longitudeOfLastGridPointInDegrees", 35.0);
    w.set("iDirectionIncrementInDegrees", 5.0).set("jDirectionIncrementInDegrees", 5.0);
    w.set("shortName", "r").set("level", 850L).set("missingValue", 9999.0).set("bitmapPresent", 1L);
    w.values(v);
    bases.push_back(w.bytes());  // simple packing with a bitmap
  }
  bases.push_back(gfsLowCloudMessage());
  // The fixture ends with GFS's u/v message at 500 hPa: two fields after one grid section.
  std::string fixture = readAll(test::gfsFixture());
  ASSERT_GT(fixture.size(), 28565u);
  bases.push_back(fixture.substr(fixture.size() - 28565));
  for (const std::string& b : bases) {
    ASSERT_GT(b.size(), 16u);
    ASSERT_EQ(b.substr(0, 4), "GRIB");
    ASSERT_EQ(b.substr(b.size() - 4), "7777");
  }
  // The unmutated messages read (the multi-field one has no humidity: an error by design).
  for (size_t b = 0; b < 2; ++b) {
    std::filesystem::path p = test::tempFile("fuzz_base.grib2");
    std::ofstream(p, std::ios::binary) << bases[b];
    EXPECT_NO_THROW(readGrib2(p)) << b;
  }

  std::mt19937 rng(20110115);
  std::filesystem::path file = test::tempFile("fuzz.grib2");
  int errors = 0, reads = 0;
  for (int i = 0; i < 200; ++i) {
    const std::string& base = bases[size_t(i) % bases.size()];
    std::string input = test::mutateBytes(base, rng, (i / 3) % 4, {200, 32, 1});
    if (i % 5 == 0) input = bases[0] + input;  // a good message first: errors name message 2
    std::ofstream(file, std::ios::binary | std::ios::trunc) << input;
    try {
      WeatherFields f = readGrib2(file);
      ++reads;
      for (const WeatherStep& s : f.steps)
        for (const LevelField& l : s.fields) ASSERT_EQ(l.values.size(), f.grid.size()) << i;
      ASSERT_EQ(f.grid.latDeg.size(), size_t(f.grid.nx) * f.grid.ny) << i;
    } catch (const Error& e) {
      ++errors;
      EXPECT_EQ(e.kind(), ErrorKind::BadInput) << i << ": " << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << i << ": " << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "mutation " << i << ": " << e.what();
    }
  }
  // Both outcomes occur: the mutations neither all break the file nor all miss.
  EXPECT_GT(errors, 20);
  EXPECT_GT(reads, 20);
}

}  // namespace
}  // namespace sky
