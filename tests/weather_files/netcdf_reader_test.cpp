// engine/weather/netcdf_reader: the ERA5-style fixture (GFS fields converted by ecCodes'
// grib_to_netcdf), small files written here through the netCDF C API (WRF-like 2D
// coordinates, Pa levels, fill values, two times), one-line errors, agreement with the GRIB2
// reader on the same fields, and a deterministic mutation run that must never crash.
#include <netcdf.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/weather/detail/cf_time.h"
#include "engine/weather/grib_reader.h"
#include "engine/weather/netcdf_reader.h"
#include "tests/support/error_capture.h"

namespace sky {
namespace {

namespace fs = std::filesystem;

fs::path dataDir() {
  const char* d = std::getenv("SKY_TEST_DATA");
  return fs::path(d ? d : "tests/data") / "weather";
}

// A fresh folder per test under the system temp dir, removed afterwards.
class NetcdfTest : public ::testing::Test {
protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    mDir =
        fs::temp_directory_path() / ("sky_netcdf_" + std::to_string(getpid()) + "_" + info->name());
    fs::create_directories(mDir);
  }
  void TearDown() override { fs::remove_all(mDir); }
  fs::path path(const std::string& name) const { return mDir / name; }

private:
  fs::path mDir;
};

// Writes a NetCDF file with the C API, failing the test on any error.
class NcWriter {
public:
  explicit NcWriter(const fs::path& file) {
    EXPECT_EQ(nc_create(file.c_str(), NC_CLOBBER, &mId), NC_NOERR) << file;
  }
  ~NcWriter() { close(); }
  void close() {
    if (mId >= 0) {
      EXPECT_EQ(nc_close(mId), NC_NOERR);
    }
    mId = -1;
  }
  int dim(const char* name, size_t len) {
    int d = -1;
    EXPECT_EQ(nc_def_dim(mId, name, len, &d), NC_NOERR) << name;
    return d;
  }
  int var(const char* name, nc_type type, const std::vector<int>& dims) {
    int v = -1;
    EXPECT_EQ(nc_def_var(mId, name, type, int(dims.size()), dims.data(), &v), NC_NOERR) << name;
    return v;
  }
  void text(int var, const char* name, const std::string& value) {
    EXPECT_EQ(nc_put_att_text(mId, var, name, value.size(), value.c_str()), NC_NOERR) << name;
  }
  void number(int var, const char* name, nc_type type, double value) {
    EXPECT_EQ(nc_put_att_double(mId, var, name, type, 1, &value), NC_NOERR) << name;
  }
  void endDef() { EXPECT_EQ(nc_enddef(mId), NC_NOERR); }
  // Writes the whole variable; an unlimited (record) dimension gets as many records as the
  // values fill.
  void put(int var, const std::vector<double>& v) {
    EXPECT_EQ(nc_put_vara_double(mId, var, std::vector<size_t>(8, 0).data(),
                                 counts(var, v.size()).data(), v.data()),
              NC_NOERR);
  }
  void putText(int var, const std::string& s) {
    EXPECT_EQ(nc_put_vara_text(mId, var, std::vector<size_t>(8, 0).data(),
                               counts(var, s.size()).data(), s.c_str()),
              NC_NOERR);
  }

private:
  std::vector<size_t> counts(int var, size_t values) const {
    int nd = 0, unlimited = -1;
    EXPECT_EQ(nc_inq_varndims(mId, var, &nd), NC_NOERR);
    EXPECT_EQ(nc_inq_unlimdim(mId, &unlimited), NC_NOERR);
    std::vector<int> dims(size_t(nd), 0);
    if (nd > 0) {
      EXPECT_EQ(nc_inq_vardimid(mId, var, dims.data()), NC_NOERR);
    }
    std::vector<size_t> count(size_t(nd), 1);
    size_t fixed = 1;
    for (size_t i = 0; i < dims.size(); ++i) {
      if (dims[i] == unlimited) continue;
      EXPECT_EQ(nc_inq_dimlen(mId, dims[i], &count[i]), NC_NOERR);
      fixed *= count[i];
    }
    for (size_t i = 0; i < dims.size(); ++i)
      if (dims[i] == unlimited) count[i] = values / fixed;
    count.resize(8, 1);
    return count;
  }

  int mId = -1;
};

double meanOf(const std::vector<float>& v) {
  double s = 0.0;
  for (float x : v) s += x;
  return s / double(v.size());
}

// A small ERA5/CDS-style file: longitude 4 (350..365 E), latitude 3 (north first), level 2
// (hPa, ascending), time 1; r (short, packed, percent), t, z (geopotential) and lcc.
void writeEra5Style(const fs::path& file, const std::string& rUnits = "%", bool rWithLevel = true,
                    const char* rName = "r") {
  NcWriter w(file);
  const int lon = w.dim("longitude", 4), lat = w.dim("latitude", 3), lev = w.dim("level", 2),
            time = w.dim("time", 1);
  const int vlon = w.var("longitude", NC_FLOAT, {lon});
  w.text(vlon, "units", "degrees_east");
  const int vlat = w.var("latitude", NC_FLOAT, {lat});
  w.text(vlat, "units", "degrees_north");
  const int vlev = w.var("level", NC_INT, {lev});
  w.text(vlev, "units", "millibars");
  const int vtime = w.var("time", NC_INT, {time});
  w.text(vtime, "units", "hours since 1900-01-01 00:00:00.0");
  w.text(vtime, "calendar", "gregorian");
  const int vr =
      w.var(rName, NC_SHORT,
            rWithLevel ? std::vector<int>{time, lev, lat, lon} : std::vector<int>{time, lat, lon});
  w.number(vr, "scale_factor", NC_DOUBLE, 0.01);
  w.number(vr, "add_offset", NC_DOUBLE, 50.0);
  w.number(vr, "_FillValue", NC_SHORT, -32767);
  w.text(vr, "units", rUnits);
  const int vt = w.var("t", NC_FLOAT, {time, lev, lat, lon});
  w.text(vt, "units", "K");
  const int vz = w.var("z", NC_FLOAT, {time, lev, lat, lon});
  w.text(vz, "units", "m**2 s**-2");
  const int vlcc = w.var("lcc", NC_FLOAT, {time, lat, lon});
  w.text(vlcc, "units", "(0 - 1)");
  w.endDef();
  w.put(vlon, {350, 355, 360, 365});
  w.put(vlat, {50, 47.5, 45});
  w.put(vlev, {500, 850});
  w.put(vtime, {973356});  // 2011-01-15T12Z
  std::vector<double> r(rWithLevel ? 24 : 12), t(24), z(24), lcc(12);
  for (size_t i = 0; i < r.size(); ++i) r[i] = (10.0 + 3.0 * double(i) - 50.0) / 0.01;  // %
  r[5] = -32767;                                                                        // hole
  for (size_t i = 0; i < 24; ++i) {
    t[i] = 250.0 + double(i);
    z[i] = 9.80665 * (5000.0 + 10.0 * double(i));
  }
  for (size_t i = 0; i < 12; ++i) lcc[i] = 0.05 * double(i);
  lcc[11] = 1.2;  // outside [0, 1] by more than 1 %: clamped with a warning
  w.put(vr, r);
  w.put(vt, t);
  w.put(vz, z);
  w.put(vlcc, lcc);
}

void expectOneLineBadInput(const Error& e, const fs::path& file, const std::string& var) {
  const std::string msg = e.what();
  EXPECT_EQ(e.kind(), ErrorKind::BadInput) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  EXPECT_NE(msg.find(file.string()), std::string::npos) << msg;
  if (!var.empty()) {
    EXPECT_NE(msg.find(var), std::string::npos) << msg;
  }
}

TEST(NetcdfReader, Era5StyleFixture) {
  const WeatherFields f = readNetcdf(dataDir() / "gfs_trop_r_t_gh_era5style.nc");
  EXPECT_EQ(f.grid.nx, 144u);
  EXPECT_EQ(f.grid.ny, 73u);
  EXPECT_TRUE(f.grid.regularLatLon);
  EXPECT_DOUBLE_EQ(f.grid.latDeg[0], 90.0);
  EXPECT_DOUBLE_EQ(f.grid.latDeg[72 * 144], -90.0);
  EXPECT_DOUBLE_EQ(f.grid.lonDeg[0], 0.0);
  EXPECT_DOUBLE_EQ(f.grid.lonDeg[143], 357.5);
  ASSERT_EQ(f.steps.size(), 1u);
  EXPECT_DOUBLE_EQ(f.steps[0].validTimeUnix, 1295092800.0);  // 2011-01-15T12:00Z
  const WeatherStep& s = f.steps[0];
  for (FieldKind kind :
       {FieldKind::RelativeHumidity, FieldKind::Temperature, FieldKind::GeopotentialHeight}) {
    const std::vector<double> levels = s.levels(kind);
    ASSERT_EQ(levels.size(), 21u) << fieldName(kind);
    EXPECT_DOUBLE_EQ(levels.front(), 1000.0);
    EXPECT_DOUBLE_EQ(levels.back(), 100.0);
  }
  EXPECT_EQ(s.fields.size(), 63u);
  const LevelField* r850 = s.find(FieldKind::RelativeHumidity, 850);
  ASSERT_NE(r850, nullptr);
  ASSERT_EQ(r850->values.size(), 144u * 73u);
  EXPECT_NEAR(meanOf(r850->values), 0.685, 0.0015);  // ecCodes: mean 68.5 %
  for (float x : r850->values) ASSERT_TRUE(x >= 0.0f && x <= 1.0f) << x;
  const LevelField* gh500 = s.find(FieldKind::GeopotentialHeight, 500);
  ASSERT_NE(gh500, nullptr);
  const auto [lo, hi] = std::minmax_element(gh500->values.begin(), gh500->values.end());
  EXPECT_NEAR(*lo, 4893.0, 1.0);  // ecCodes: 4893..5902 gpm
  EXPECT_NEAR(*hi, 5902.0, 1.0);
  const LevelField* t1000 = s.find(FieldKind::Temperature, 1000);
  ASSERT_NE(t1000, nullptr);
  const auto [tlo, thi] = std::minmax_element(t1000->values.begin(), t1000->values.end());
  EXPECT_GT(*tlo, 200.0f);
  EXPECT_LT(*thi, 330.0f);
}

TEST_F(NetcdfTest, Era5StyleGeopotentialCoverAndLongitudes) {
  const fs::path file = path("era5.nc");
  writeEra5Style(file);
  testing::internal::CaptureStderr();
  const WeatherFields f = readNetcdf(file);
  const std::string err = testing::internal::GetCapturedStderr();
  // One warning line, for lcc's 1.2 (r's 1..97 % lie inside).
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_NE(err.find("lcc"), std::string::npos) << err;

  ASSERT_EQ(f.grid.nx, 4u);
  ASSERT_EQ(f.grid.ny, 3u);
  EXPECT_TRUE(f.grid.regularLatLon);
  // 350..365 E moved as one axis to -10..5: monotonic and within [-180, 360).
  EXPECT_EQ(f.grid.lonDeg[0], -10.0);
  EXPECT_EQ(f.grid.lonDeg[3], 5.0);
  EXPECT_EQ(f.grid.latDeg[0], 50.0);
  EXPECT_EQ(f.grid.latDeg[11], 45.0);
  ASSERT_EQ(f.steps.size(), 1u);
  const WeatherStep& s = f.steps[0];
  const LevelField* r500 = s.find(FieldKind::RelativeHumidity, 500);
  const LevelField* r850 = s.find(FieldKind::RelativeHumidity, 850);
  ASSERT_TRUE(r500 && r850);
  EXPECT_NEAR(r500->values[0], 0.10, 1e-6);  // 10 % packed as short
  EXPECT_NEAR(r500->values[4], 0.22, 1e-6);
  EXPECT_TRUE(std::isnan(r500->values[5]));  // the _FillValue hole
  EXPECT_NEAR(r850->values[0], 0.46, 1e-6);
  const LevelField* gh = s.find(FieldKind::GeopotentialHeight, 850);  // z / 9.80665
  ASSERT_NE(gh, nullptr);
  EXPECT_NEAR(gh->values[1], 5000.0 + 10.0 * 13.0, 1e-3);
  const LevelField* t = s.find(FieldKind::Temperature, 500);
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->values[2], 252.0f);
  const LevelField* low = s.find(FieldKind::CloudCoverLow);
  ASSERT_NE(low, nullptr);
  EXPECT_NEAR(low->values[3], 0.15, 1e-6);  // a fraction by units and by its maximum
  EXPECT_EQ(low->values[11], 1.0f);         // 1.2 clamped
}

// WRF pressure-level output: Times strings, XLAT/XLONG(Time, south_north, west_east), levels
// in Pa descending in P_PL, RH_PL as a fraction with a fill hole, two times.
TEST_F(NetcdfTest, WrfLikeFile) {
  const fs::path file = path("wrf.nc");
  const size_t nt = 2, np = 3, ny = 2, nx = 3;
  {
    NcWriter w(file);
    const int time = w.dim("Time", NC_UNLIMITED), strLen = w.dim("DateStrLen", 19),
              lev = w.dim("num_press_levels_stag", np), sn = w.dim("south_north", ny),
              we = w.dim("west_east", nx);
    const int vTimes = w.var("Times", NC_CHAR, {time, strLen});
    const int vlat = w.var("XLAT", NC_FLOAT, {time, sn, we});
    w.text(vlat, "units", "degree_north");
    const int vlon = w.var("XLONG", NC_FLOAT, {time, sn, we});
    w.text(vlon, "units", "degree_east");
    const int vp = w.var("P_PL", NC_FLOAT, {time, lev});
    w.text(vp, "units", "Pa");
    const int vrh = w.var("RH_PL", NC_FLOAT, {time, lev, sn, we});
    w.text(vrh, "units", "1");
    w.number(vrh, "_FillValue", NC_FLOAT, -999.0);
    const int vt = w.var("T_PL", NC_FLOAT, {time, lev, sn, we});
    w.text(vt, "units", "K");
    const int vgh = w.var("GHT_PL", NC_FLOAT, {time, lev, sn, we});
    w.text(vgh, "units", "m");
    w.endDef();
    // Two times, written in reverse order: the reader sorts steps by valid time.
    w.putText(vTimes, "2024-06-21_15:00:002024-06-21_12:00:00");
    // A rotated, curved grid: latitude varies along rows and columns.
    std::vector<double> lat, lon;
    for (size_t t = 0; t < nt; ++t)
      for (size_t j = 0; j < ny; ++j)
        for (size_t i = 0; i < nx; ++i) {
          lat.push_back(45.0 + double(j) + 0.1 * double(i));
          lon.push_back(-179.5 + double(i) - 0.2 * double(j) + (i == 0 && j == 1 ? -1.0 : 0.0));
        }
    w.put(vlat, lat);
    w.put(vlon, lon);
    w.put(vp, {100000, 85000, 50000, 100000, 85000, 50000});
    std::vector<double> rh, t, gh;
    for (size_t s = 0; s < nt; ++s)
      for (size_t k = 0; k < np; ++k)
        for (size_t p = 0; p < ny * nx; ++p) {
          rh.push_back(0.1 * double(s) + 0.2 * double(k) + 0.01 * double(p));
          t.push_back(280.0 - 20.0 * double(k) + double(s));
          gh.push_back(100.0 + 1000.0 * double(k) + double(p));
        }
    rh[1 * np * ny * nx + 2 * ny * nx + 4] = -999.0;  // time 1, level 2 (500 hPa), point 4
    w.put(vrh, rh);
    w.put(vt, t);
    w.put(vgh, gh);
  }
  const WeatherFields f = readNetcdf(file);
  EXPECT_EQ(f.grid.nx, nx);
  EXPECT_EQ(f.grid.ny, ny);
  EXPECT_FALSE(f.grid.regularLatLon);
  EXPECT_NEAR(f.grid.latDeg[1 * nx + 2], 46.2, 1e-5);
  EXPECT_NEAR(f.grid.lonDeg[2], -177.5, 1e-5);
  EXPECT_NEAR(f.grid.lonDeg[1 * nx + 0], 179.3, 1e-4);  // -180.7 wrapped into range
  ASSERT_EQ(f.steps.size(), 2u);
  EXPECT_DOUBLE_EQ(f.steps[0].validTimeUnix, 1718971200.0);  // 2024-06-21T12Z
  EXPECT_DOUBLE_EQ(f.steps[1].validTimeUnix, 1718982000.0);  // 15Z
  // Steps were sorted: file time 1 (12Z) is step 0.
  const WeatherStep& s0 = f.steps[0];
  EXPECT_EQ(s0.levels(FieldKind::RelativeHumidity), (std::vector<double>{1000.0, 850.0, 500.0}));
  const LevelField* r500 = s0.find(FieldKind::RelativeHumidity, 500);
  ASSERT_NE(r500, nullptr);
  EXPECT_TRUE(std::isnan(r500->values[4]));
  EXPECT_NEAR(r500->values[3], 0.1 + 0.4 + 0.03, 1e-6);  // a fraction stays a fraction
  const LevelField* t850 = f.steps[1].find(FieldKind::Temperature, 850);
  ASSERT_NE(t850, nullptr);
  EXPECT_EQ(t850->values[0], 260.0f);  // file time 0
  const LevelField* gh1000 = s0.find(FieldKind::GeopotentialHeight, 1000);
  ASSERT_NE(gh1000, nullptr);
  EXPECT_EQ(gh1000->values[5], 105.0f);
}

TEST(NetcdfReader, CfTimeUnits) {
  EXPECT_DOUBLE_EQ(detail::cfTimeToUnix(973356, "hours since 1900-01-01 00:00:00.0"), 1295092800.0);
  EXPECT_DOUBLE_EQ(detail::cfTimeToUnix(1718971200, "seconds since 1970-01-01"), 1718971200.0);
  EXPECT_DOUBLE_EQ(detail::cfTimeToUnix(1.5, "days since 2000-1-1T06:00:00Z"),
                   946684800.0 + 1.75 * 86400);
  EXPECT_DOUBLE_EQ(detail::cfTimeToUnix(30, "minutes since 2011-01-15 12:00:00"), 1295094600.0);
  EXPECT_DOUBLE_EQ(detail::cfTimeToUnix(0, "hours since 2024-06-21 14:00:00 +02:00"), 1718971200.0);
  EXPECT_EQ(test::catchError([] { detail::cfTimeToUnix(0, "fortnights since 2000-01-01"); }).kind(),
            ErrorKind::BadInput);
  EXPECT_EQ(test::catchError([] { detail::cfTimeToUnix(0, "hours"); }).kind(), ErrorKind::BadInput);
  EXPECT_EQ(test::catchError([] { detail::cfTimeToUnix(0, "hours since 2000-13-01"); }).kind(),
            ErrorKind::BadInput);
}

TEST_F(NetcdfTest, PercentByMaximumWhateverTheUnitsSay) {
  const fs::path file = path("percent.nc");
  writeEra5Style(file, "1");           // r holds 1..97 but claims a fraction
  testing::internal::CaptureStderr();  // lcc's warning, checked above
  const WeatherFields f = readNetcdf(file);
  testing::internal::GetCapturedStderr();
  EXPECT_NEAR(f.steps[0].find(FieldKind::RelativeHumidity, 500)->values[4], 0.22, 1e-6);
}

TEST_F(NetcdfTest, MissingOrNotNetcdf) {
  const fs::path missing = path("nothing.nc");
  expectOneLineBadInput(test::catchError([&] { readNetcdf(missing); }), missing, "");
  const fs::path text = path("text.nc");
  std::ofstream(text) << "this is not a NetCDF file\n";
  const Error e = test::catchError([&] { readNetcdf(text); });
  expectOneLineBadInput(e, text, "");
  EXPECT_NE(std::string(e.what()).find("not a NetCDF file"), std::string::npos) << e.what();
}

TEST_F(NetcdfTest, TruncatedFixture) {
  std::ifstream in(dataDir() / "gfs_trop_r_t_gh_era5style.nc", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 1000000u);
  // Halfway (r's data cut), a few bytes short of the end (the last values of the last
  // variable), and inside the header.
  for (size_t size : {bytes.size() / 2, bytes.size() - 100, size_t(200)}) {
    const fs::path file = path("truncated_" + std::to_string(size) + ".nc");
    std::ofstream(file, std::ios::binary).write(bytes.data(), std::streamsize(size));
    const Error e = test::catchError([&] { readNetcdf(file); });
    expectOneLineBadInput(e, file, "");
  }
  const fs::path file = path("truncated_end.nc");
  std::ofstream(file, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() - 100));
  const Error e = test::catchError([&] { readNetcdf(file); });
  EXPECT_NE(std::string(e.what()).find(": r: "), std::string::npos) << e.what();  // the last one
}

// The mutation that crashed libnetcdf 4.9's nc_open before the header check: the variable
// count of a 1 kB file raised to 2^30 + 8.
TEST_F(NetcdfTest, CorruptHeaderCountRefused) {
  const fs::path file = path("counts.nc");
  writeEra5Style(file);
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::string varList("\0\0\0\x0b\0\0\0\x08", 8);  // NC_VARIABLE, 8 variables
  const size_t at = bytes.find(varList);
  ASSERT_NE(at, std::string::npos);
  bytes[at + 4] = 0x40;
  std::ofstream(file, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  const Error e = test::catchError([&] { readNetcdf(file); });
  expectOneLineBadInput(e, file, "not a valid NetCDF file: variable count 1073741832");
}

TEST_F(NetcdfTest, NoUsableVariable) {
  const fs::path file = path("q_only.nc");
  {
    NcWriter w(file);
    const int x = w.dim("x", 2);
    const int q = w.var("q", NC_FLOAT, {x});
    w.text(q, "units", "kg kg**-1");
    w.endDef();
    w.put(q, {1e-3, 2e-3});
  }
  const Error e = test::catchError([&] { readNetcdf(file); });
  expectOneLineBadInput(e, file, "no usable variable");
  EXPECT_NE(std::string(e.what()).find("q"), std::string::npos) << e.what();
}

TEST_F(NetcdfTest, WrongUnitsAndDimensions) {
  const fs::path kelvin = path("rh_in_kelvin.nc");
  writeEra5Style(kelvin, "K");
  const Error e = test::catchError([&] { readNetcdf(kelvin); });
  expectOneLineBadInput(e, kelvin, ": r: units \"K\"");

  const fs::path flat = path("rh_without_level.nc");
  writeEra5Style(flat, "%", false);
  const Error d = test::catchError([&] { readNetcdf(flat); });
  expectOneLineBadInput(d, flat, ": r: dimensions (time, latitude, longitude)");
}

// The same GFS fields through both readers. The NetCDF stores each variable as short with
// scale_factor = range / 65534, so it differs from the GRIB2 decode by at most half a step:
// r 0.00076 % (7.6e-6 as a fraction), gh 0.13 m, t 0.00097 K (plus float rounding).
TEST(NetcdfReader, GribAndNetcdfAgree) {
  const WeatherFields nc = readNetcdf(dataDir() / "gfs_trop_r_t_gh_era5style.nc");
  const WeatherFields grib = readGrib2(dataDir() / "gfs_2p5deg_r_gh_t_tcc_uv500.grib2");
  ASSERT_EQ(grib.grid.size(), nc.grid.size());
  for (size_t p = 0; p < nc.grid.size(); ++p) {
    ASSERT_NEAR(grib.grid.latDeg[p], nc.grid.latDeg[p], 1e-6) << p;
    ASSERT_NEAR(grib.grid.lonDeg[p], nc.grid.lonDeg[p], 1e-6) << p;
  }
  ASSERT_EQ(grib.steps.size(), 1u);
  EXPECT_DOUBLE_EQ(grib.steps[0].validTimeUnix, nc.steps[0].validTimeUnix);
  struct Tolerance {
    FieldKind kind;
    double tol;
  };
  int compared = 0;
  for (const Tolerance& t : {Tolerance{FieldKind::RelativeHumidity, 8e-6}, Tolerance{FieldKind::GeopotentialHeight, 0.14}, Tolerance{FieldKind::Temperature, 1e-3}})
    for (double level : nc.steps[0].levels(t.kind)) {
      const LevelField* a = nc.steps[0].find(t.kind, level);
      const LevelField* b = grib.steps[0].find(t.kind, level);
      ASSERT_TRUE(a && b) << fieldName(t.kind) << " " << level;
      double worst = 0.0;
      for (size_t p = 0; p < a->values.size(); ++p)
        worst = std::max(worst, std::fabs(double(a->values[p]) - double(b->values[p])));
      EXPECT_LE(worst, t.tol + 1e-7 * std::fabs(b->values[0])) << fieldName(t.kind) << " at " << level;
      ++compared;
    }
  EXPECT_EQ(compared, 63);
}

// ~100 deterministic mutations of a small classic NetCDF: every one is read or refused with
// a sky::Error; none crashes, hangs or throws anything else.
class NetcdfFuzz : public NetcdfTest {};

TEST_F(NetcdfFuzz, MutatedFixturesNeverCrash) {
  const fs::path original = path("original.nc");
  writeEra5Style(original);
  std::ifstream in(original, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 400u);
  testing::internal::CaptureStderr();  // the clamping warnings (lcc's 1.2, mutated values)
  EXPECT_NO_THROW(readNetcdf(original));

  std::mt19937 rng(20240621);
  auto below = [&](size_t n) { return size_t(rng() % n); };
  // The header (dimension lengths, types, offsets, attribute sizes) is where a mutation
  // reaches the parser; half the mutations aim there.
  const size_t header = std::min<size_t>(bytes.size(), 700);
  int read = 0, refused = 0;
  for (int m = 0; m < 100; ++m) {
    std::string b = bytes;
    switch (m % 5) {
      case 0:  // a few flipped bits anywhere
        for (int k = 0; k < 1 + m % 4; ++k) b[below(b.size())] ^= char(1u << below(8));
        break;
      case 1:  // random bytes in the header
        for (int k = 0; k < 1 + m % 6; ++k) b[below(header)] = char(rng());
        break;
      case 2:  // a 32-bit big-endian count or offset in the header set to an extreme
      {
        const uint32_t extremes[] = {0u, 1u, 0x7fffffffu, 0xffffffffu, 0x10000u, 3u};
        const uint32_t v = extremes[below(6)];
        const size_t at = 4 * below(header / 4);
        for (int k = 0; k < 4; ++k) b[at + size_t(k)] = char(v >> (24 - 8 * k));
        break;
      }
      case 3:  // truncated anywhere
        b.resize(below(b.size()));
        break;
      case 4:  // a slice of the file repeated or removed
      {
        const size_t at = below(b.size()), len = 1 + below(64);
        if (m % 2)
          b.insert(at, b.substr(at, len));
        else
          b.erase(at, len);
        break;
      }
    }
    const fs::path file = path("mutant_" + std::to_string(m) + ".nc");
    std::ofstream(file, std::ios::binary).write(b.data(), std::streamsize(b.size()));
    try {
      const WeatherFields f = readNetcdf(file);
      for (const WeatherStep& s : f.steps)
        for (const LevelField& field : s.fields) EXPECT_EQ(field.values.size(), f.grid.size());
      ++read;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::BadInput) << "mutation " << m << ": " << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      ++refused;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "mutation " << m << " threw " << e.what();
    }
    fs::remove(file);
  }
  testing::internal::GetCapturedStderr();
  // Both outcomes occur: the mutations are neither all harmless nor all fatal.
  EXPECT_GT(read, 0);
  EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace sky
