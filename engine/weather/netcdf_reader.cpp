#include "engine/weather/netcdf_reader.h"

#include <netcdf.h>
#include <netcdf_mem.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "engine/core/error.h"
#include "engine/weather/field_checks.h"
#include "engine/weather/detail/text.h"
#include "engine/weather/detail/cf_time.h"
#include "engine/weather/detail/netcdf_classic_header.h"

namespace sky {
namespace {

namespace fs = std::filesystem;
using detail::cfTimeToUnix;
using detail::lower;
using detail::parseDateTime;
using detail::printable;
using detail::trim;

// WMO standard gravity: ERA5's z (geopotential, m2 s-2) / g0 = geopotential height (gpm).
constexpr double kStandardGravity = 9.80665;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Units compared without case, blanks, '*' and '^': "m s**-1" == "m s-1" == "M S^-1".
std::string unitKey(std::string_view units) {
  std::string out;
  for (char c : lower(units))
    if (!std::isspace(static_cast<unsigned char>(c)) && c != '*' && c != '^') out += c;
  return out;
}

bool oneOf(const std::string& s, std::initializer_list<const char*> list) {
  return std::any_of(list.begin(), list.end(), [&](const char* x) { return s == x; });
}

// ---- libnetcdf access -------------------------------------------------------------------

class NcFile {
public:
  explicit NcFile(const fs::path& path) { mStatus = nc_open(path.c_str(), NC_NOWRITE, &mId); }
  // A file image in memory; `bytes` must outlive this object.
  NcFile(const fs::path& path, std::string& bytes) {
    mStatus = nc_open_mem(path.c_str(), NC_NOWRITE, bytes.size(), bytes.data(), &mId);
  }
  ~NcFile() {
    if (mStatus == NC_NOERR) nc_close(mId);
  }
  NcFile(const NcFile&) = delete;
  NcFile& operator=(const NcFile&) = delete;
  int status() const { return mStatus; }
  int id() const { return mId; }

private:
  int mId = -1;
  int mStatus = NC_NOERR;
};

struct Var {
  int id = -1;
  std::string name;
  nc_type type = NC_NAT;
  std::vector<int> dims;
  std::string units;
  std::string standardName;
};

bool isNumeric(nc_type t) {
  return t == NC_BYTE || t == NC_UBYTE || t == NC_SHORT || t == NC_USHORT || t == NC_INT ||
         t == NC_UINT || t == NC_INT64 || t == NC_UINT64 || t == NC_FLOAT || t == NC_DOUBLE;
}

// The file, its variables and dimensions, and one-line errors that name the file.
class Reader {
public:
  Reader(const fs::path& path, int ncid, bool classic)
      : mPath(path), mFile(path.string()), mNc(ncid), mClassic(classic) {
    std::error_code ec;
    mFileSize = fs::file_size(path, ec);
    int ndims = 0, nvars = 0, unlimited = -1;
    check(nc_inq(mNc, &ndims, &nvars, nullptr, &unlimited), "", "reading the header");
    // Dimension ids are 0..n-1 in classic files but need not be in NetCDF-4 ones: variables
    // refer to dimensions by index into mDimNames here.
    std::vector<int> dimIds(size_t(std::max(ndims, 0)));
    check(nc_inq_dimids(mNc, &ndims, dimIds.data(), 0), "", "reading the dimensions");
    dimIds.resize(size_t(std::max(ndims, 0)));
    for (int id : dimIds) {
      char name[NC_MAX_NAME + 1] = {};
      size_t len = 0;
      check(nc_inq_dim(mNc, id, name, &len), "", "reading dimension " + std::to_string(id));
      mDimNames.push_back(name);
      mDimLens.push_back(len);
    }
    for (int v = 0; v < nvars; ++v) {
      Var var;
      var.id = v;
      char name[NC_MAX_NAME + 1] = {};
      int nd = 0;
      check(nc_inq_var(mNc, v, name, &var.type, &nd, nullptr, nullptr), "",
            "reading variable " + std::to_string(v));
      var.name = name;
      if (nd < 0 || nd > NC_MAX_VAR_DIMS) fail(var.name, "corrupt dimension count");
      var.dims.resize(size_t(nd));
      if (nd > 0) check(nc_inq_vardimid(mNc, v, var.dims.data()), var.name, "reading dimensions");
      for (int& d : var.dims) {
        const auto it = std::find(dimIds.begin(), dimIds.end(), d);
        if (it == dimIds.end()) fail(var.name, "uses a dimension of another group");
        d = int(it - dimIds.begin());
      }
      var.units = textAttribute(v, "units").value_or("");
      var.standardName = textAttribute(v, "standard_name").value_or("");
      mVars.push_back(std::move(var));
    }
  }

  [[noreturn]] void fail(const std::string& var, const std::string& what) const {
    inputError(printable(mFile + ": " + (var.empty() ? "" : var + ": ") + what));
  }
  void check(int status, const std::string& var, const std::string& doing) const {
    if (status != NC_NOERR) fail(var, doing + " failed: " + nc_strerror(status));
  }

  const fs::path& path() const { return mPath; }
  const std::vector<Var>& vars() const { return mVars; }
  const Var* var(const std::string& name) const {
    for (const Var& v : mVars)
      if (v.name == name) return &v;
    return nullptr;
  }
  const std::string& dimName(int d) const { return mDimNames[size_t(d)]; }
  size_t dimLen(int d) const { return mDimLens[size_t(d)]; }

  std::optional<std::string> textAttribute(int varid, const char* name) const {
    nc_type type = NC_NAT;
    size_t len = 0;
    if (nc_inq_att(mNc, varid, name, &type, &len) != NC_NOERR) return std::nullopt;
    if (type == NC_CHAR) {
      std::string s(len, '\0');
      if (len > 0 && nc_get_att_text(mNc, varid, name, s.data()) != NC_NOERR) return std::nullopt;
      return trim(s);
    }
    if (type == NC_STRING && len == 1) {
      char* str = nullptr;
      if (nc_get_att_string(mNc, varid, name, &str) != NC_NOERR) return std::nullopt;
      std::string s = str ? str : "";
      nc_free_string(1, &str);
      return trim(s);
    }
    return std::nullopt;
  }

  std::vector<double> numberAttribute(const Var& v, const char* name) const {
    nc_type type = NC_NAT;
    size_t len = 0;
    if (nc_inq_att(mNc, v.id, name, &type, &len) != NC_NOERR || !isNumeric(type) || len == 0 ||
        len > 1024)
      return {};
    std::vector<double> out(len);
    check(nc_get_att_double(mNc, v.id, name, out.data()), v.name,
          std::string("reading attribute ") + name);
    return out;
  }

  // Guards every read: a corrupt or truncated classic file can declare far more data than
  // it holds (and libnetcdf reads a short file's missing tail as zeros unless diskless).
  void checkSize(const Var& v) const {
    size_t typeSize = 0;
    check(nc_inq_type(mNc, v.type, nullptr, &typeSize), v.name, "reading the type");
    double bytes = double(typeSize);
    for (int d : v.dims) bytes *= double(dimLen(d));
    if (mClassic && bytes > double(mFileSize))
      fail(v.name, "its dimensions need " + std::to_string(uint64_t(bytes)) +
                       " bytes but the file has " + std::to_string(mFileSize) + " (truncated?)");
    if (bytes > double(uint64_t(1) << 36)) fail(v.name, "too large to read");
  }

  // Reads the hyperslab start/count as doubles with scale_factor / add_offset applied and
  // _FillValue / missing_value (and NaN) turned into NaN.
  std::vector<double> read(const Var& v, const std::vector<size_t>& start,
                           const std::vector<size_t>& count) const {
    if (!isNumeric(v.type)) fail(v.name, "is not numeric");
    checkSize(v);
    size_t n = 1;
    for (size_t c : count) n *= c;
    std::vector<double> out(n);
    if (n == 0) return out;
    const int status = nc_get_vara_double(mNc, v.id, start.data(), count.data(), out.data());
    // From a memory image, libnetcdf reports a read past its end as EPERM (it may not grow
    // the image): the file is shorter than its header says.
    if (mClassic && status == EPERM) fail(v.name, "the file ends before this variable's data");
    check(status, v.name, "reading data");
    std::vector<double> fills = numberAttribute(v, "_FillValue");
    if (fills.empty()) {
      // The netCDF default fill for floating types marks never-written data.
      if (v.type == NC_FLOAT) fills.push_back(double(NC_FILL_FLOAT));
      if (v.type == NC_DOUBLE) fills.push_back(NC_FILL_DOUBLE);
    }
    for (double m : numberAttribute(v, "missing_value")) fills.push_back(m);
    // Fill values are in the stored type: compare them as that type would hold them.
    for (double& f : fills)
      if (v.type == NC_FLOAT) f = double(float(f));
    const std::vector<double> scale = numberAttribute(v, "scale_factor");
    const std::vector<double> offset = numberAttribute(v, "add_offset");
    const double s = scale.empty() ? 1.0 : scale[0];
    const double o = offset.empty() ? 0.0 : offset[0];
    // A NaN scale made every value NaN and the cover zero everywhere without a word (issue
    // 31, 9): the whole variable is unusable.
    if (!std::isfinite(s) || !std::isfinite(o))
      fail(v.name, std::string(!std::isfinite(s) ? "scale_factor" : "add_offset") + " is " +
                       std::to_string(!std::isfinite(s) ? s : o) +
                       ", not a finite number: the variable is unusable");
    for (double& x : out) {
      const bool missing = std::isnan(x) || std::any_of(fills.begin(), fills.end(),
                                                        [&](double f) { return x == f; });
      x = missing ? std::numeric_limits<double>::quiet_NaN() : x * s + o;
    }
    return out;
  }

  std::vector<double> readAll(const Var& v) const {
    std::vector<size_t> start(v.dims.size(), 0), count;
    for (int d : v.dims) count.push_back(dimLen(d));
    return read(v, start, count);
  }

  // Character variable Times(Time, DateStrLen) (WRF): row `row` as text.
  std::string readChars(const Var& v, size_t row) const {
    checkSize(v);
    const size_t len = dimLen(v.dims[1]);
    std::string s(len, '\0');
    const size_t start[2] = {row, 0};
    const size_t count[2] = {1, len};
    check(nc_get_vara_text(mNc, v.id, start, count, s.data()), v.name, "reading text");
    return trim(s);
  }

private:
  fs::path mPath;
  std::string mFile;
  int mNc;
  bool mClassic;
  uintmax_t mFileSize = 0;
  std::vector<std::string> mDimNames;
  std::vector<size_t> mDimLens;
  std::vector<Var> mVars;
};

// ---- what the variables mean ------------------------------------------------------------

enum class Quantity { Fraction, Temperature, Height, Geopotential, Wind };

struct Kind {
  FieldKind field;
  Quantity quantity;
  bool onLevels;
  std::array<const char*, 6> names;  // ERA5/CF first, then WRF (p_interp, auxhist *_PL), CMIP
  const char* standardName;
};

// clang-format off
constexpr Kind kKinds[] = {
    {FieldKind::RelativeHumidity,   Quantity::Fraction,     true, {"r", "rh", "RH", "RH_PL", "hur", "relhum"},   "relative_humidity"},
    {FieldKind::Temperature,        Quantity::Temperature,  true, {"t", "TT", "T_PL", "TK", "ta", "temp"},        "air_temperature"},
    {FieldKind::GeopotentialHeight, Quantity::Height,       true, {"gh", "GHT", "GHT_PL", "Z_PL", "zg", "hgt"},   "geopotential_height"},
    {FieldKind::GeopotentialHeight, Quantity::Geopotential, true, {"z", "Z", "geopotential", "", "", ""},         "geopotential"},
    {FieldKind::WindU,              Quantity::Wind,         true, {"u", "U_PL", "ua", "", "", ""},                "eastward_wind"},
    {FieldKind::WindV,              Quantity::Wind,         true, {"v", "V_PL", "va", "", "", ""},                "northward_wind"},
    {FieldKind::CloudCoverLow,      Quantity::Fraction, false, {"lcc", "LCC", "tcc_low", "", "", ""},  "low_type_cloud_area_fraction"},
    {FieldKind::CloudCoverMid,      Quantity::Fraction, false, {"mcc", "MCC", "tcc_mid", "", "", ""},  "medium_type_cloud_area_fraction"},
    {FieldKind::CloudCoverHigh,     Quantity::Fraction, false, {"hcc", "HCC", "tcc_high", "", "", ""}, "high_type_cloud_area_fraction"},
};
// clang-format on

// Multiplier to hPa for a vertical coordinate's units; nullopt when they are not a pressure.
std::optional<double> pressureScale(const std::string& units) {
  const std::string u = unitKey(units);
  if (oneOf(u, {"hpa", "mb", "mbar", "millibar", "millibars", "hectopascal", "hectopascals"}))
    return 1.0;
  if (oneOf(u, {"pa", "pascal", "pascals"})) return 0.01;
  if (oneOf(u, {"kpa"})) return 10.0;
  return std::nullopt;
}

bool isLatitudeVar(const Var& v) {
  return oneOf(v.name, {"latitude", "lat", "XLAT", "XLAT_M", "nav_lat", "LAT"}) ||
         v.standardName == "latitude" ||
         oneOf(unitKey(v.units),
               {"degrees_north", "degree_north", "degrees_n", "degree_n", "degreesn", "degreen"});
}
bool isLongitudeVar(const Var& v) {
  return oneOf(v.name, {"longitude", "lon", "XLONG", "XLONG_M", "nav_lon", "LON"}) ||
         v.standardName == "longitude" ||
         oneOf(unitKey(v.units),
               {"degrees_east", "degree_east", "degrees_e", "degree_e", "degreese", "degreee"});
}

struct FieldVar {
  const Kind* kind = nullptr;
  const Var* var = nullptr;
  int timeDim = -1;
  int levelDim = -1;
  std::vector<int> horizontal;  // 1 (a list of points) or 2 (y, x), the trailing dimensions
};

class NetcdfLayout {
public:
  explicit NetcdfLayout(const Reader& r) : mR(r) {}

  bool isTimeDim(int d) const {
    const std::string& n = mR.dimName(d);
    if (oneOf(n, {"time", "Time", "valid_time", "t", "times", "TIME"})) return true;
    const Var* c = mR.var(n);
    return c && c->dims.size() == 1 && lower(c->units).find(" since ") != std::string::npos;
  }

  // The pressure coordinate of dimension d: the coordinate variable (in pressure units, or
  // with none when `unitless` allows), or any 1D (or time x level) variable over d in
  // pressure units (WRF's P_PL).
  const Var* pressureCoordinate(int d, int timeDim, bool unitless) const {
    if (const Var* c = mR.var(mR.dimName(d));
        c && c->dims == std::vector<int>{d} &&
        (pressureScale(c->units) || (unitless && c->units.empty())))
      return c;
    for (const Var& v : mR.vars()) {
      const bool shape =
          v.dims == std::vector<int>{d} || (timeDim >= 0 && v.dims == std::vector<int>{timeDim, d});
      if (shape && pressureScale(v.units)) return &v;
    }
    return nullptr;
  }

  // A level dimension by name (then rejected later if its coordinate is not a pressure, as
  // WRF's eta levels bottom_top are) or by a pressure coordinate.
  bool looksVertical(int d, int timeDim) const {
    const std::string& n = mR.dimName(d);
    return oneOf(n, {"level", "lev", "plev", "pressure", "pressure_level", "isobaricInhPa",
                     "isobaric", "num_press_levels_stag", "num_metgrid_levels", "bottom_top",
                     "height", "depth", "z", "height_above_ground"}) ||
           pressureCoordinate(d, timeDim, false) != nullptr;
  }

  std::string dimList(const Var& v) const {
    std::string s = "(";
    for (size_t i = 0; i < v.dims.size(); ++i) s += (i ? ", " : "") + mR.dimName(v.dims[i]);
    return s + ")";
  }

  FieldVar classify(const Kind& kind, const Var& v) const {
    FieldVar f;
    f.kind = &kind;
    f.var = &v;
    if (!isNumeric(v.type)) mR.fail(v.name, "is not numeric");
    for (size_t i = 0; i < v.dims.size(); ++i) {
      const int d = v.dims[i];
      if (isTimeDim(d) && f.timeDim < 0 && f.horizontal.empty()) {
        f.timeDim = d;
      } else if (f.levelDim < 0 && f.horizontal.empty() && i + 1 < v.dims.size() &&
                 looksVertical(d, f.timeDim)) {
        f.levelDim = d;
      } else {
        f.horizontal.push_back(d);
      }
    }
    const std::string expected = kind.onLevels ? "[time,] level, latitude, longitude (or y, x)"
                                               : "[time,] latitude, longitude (or y, x)";
    if (f.horizontal.empty() || f.horizontal.size() > 2)
      mR.fail(v.name, "dimensions " + dimList(v) + " are not " + expected);
    if (kind.onLevels && f.levelDim < 0)
      mR.fail(v.name,
              "dimensions " + dimList(v) + " have no pressure level (expected " + expected + ")");
    if (!kind.onLevels && f.levelDim >= 0)
      mR.fail(v.name, "dimensions " + dimList(v) + " are not " + expected);
    for (int d : f.horizontal)
      if (mR.dimLen(d) == 0) mR.fail(v.name, "dimension " + mR.dimName(d) + " is empty");
    return f;
  }

  std::vector<FieldVar> fieldVars() const {
    std::vector<FieldVar> out;
    bool haveHeight = false;
    for (const Kind& kind : kKinds) {
      if (kind.quantity == Quantity::Geopotential && haveHeight) continue;  // gh wins over z
      const Var* found = nullptr;
      for (const char* n : kind.names)
        if (!found && *n) found = mR.var(n);
      if (found) {
        out.push_back(classify(kind, *found));
      } else {
        // By standard_name only where the shape fits, so a CF file's 10 m "eastward_wind"
        // (no level) is passed over rather than rejected.
        for (const Var& v : mR.vars()) {
          if (v.standardName != kind.standardName) continue;
          bool taken = false;
          for (const FieldVar& f : out) taken = taken || f.var == &v;
          if (taken) continue;
          try {
            out.push_back(classify(kind, v));
            break;
          } catch (const Error&) {
          }
        }
      }
      if (!out.empty() && out.back().kind == &kind && kind.quantity == Quantity::Height)
        haveHeight = true;
    }
    return out;
  }

  std::optional<std::pair<const Var*, const Var*>> coordinates(const FieldVar& f) const {
    auto fits = [&](const Var& v, const std::vector<int>& dims) {
      if (v.dims == dims) return true;
      // WRF: XLAT(Time, south_north, west_east); the first time's values are used.
      return v.dims.size() == dims.size() + 1 && isTimeDim(v.dims[0]) &&
             std::equal(dims.begin(), dims.end(), v.dims.begin() + 1);
    };
    auto find = [&](bool latitude, const std::vector<int>& dims) -> const Var* {
      for (const Var& v : mR.vars())
        if ((latitude ? isLatitudeVar(v) : isLongitudeVar(v)) && isNumeric(v.type) && fits(v, dims))
          return &v;
      return nullptr;
    };
    const std::vector<int>& h = f.horizontal;
    if (h.size() == 2) {
      const Var* lat = find(true, {h[0]});
      const Var* lon = find(false, {h[1]});
      if (lat && lon) return std::make_pair(lat, lon);
    }
    const Var* lat = find(true, h);
    const Var* lon = find(false, h);
    if (lat && lon) return std::make_pair(lat, lon);
    return std::nullopt;
  }

  // The first time (or only) slice of a coordinate variable.
  std::vector<double> firstSlice(const Var& v, size_t trailingDims) const {
    std::vector<size_t> start(v.dims.size(), 0), count(v.dims.size(), 1);
    for (size_t i = v.dims.size() - trailingDims; i < v.dims.size(); ++i)
      count[i] = mR.dimLen(v.dims[i]);
    for (size_t i = 0; i < v.dims.size() - trailingDims; ++i)
      if (mR.dimLen(v.dims[i]) == 0) mR.fail(v.name, "time dimension is empty");
    return mR.read(v, start, count);
  }

  GridGeometry grid(const FieldVar& f) const {
    auto coords = coordinates(f);
    if (!coords) {
      std::string dims;
      for (int d : f.horizontal) dims += (dims.empty() ? "" : ", ") + mR.dimName(d);
      mR.fail(f.var->name, "no latitude/longitude coordinate variables over (" + dims + ")");
    }
    const auto [latVar, lonVar] = *coords;
    GridGeometry g;
    const bool separable =
        f.horizontal.size() == 2 && latVar->dims.size() == 1 && latVar->dims[0] == f.horizontal[0];
    const std::vector<double> lat = firstSlice(*latVar, separable ? 1 : f.horizontal.size());
    std::vector<double> lon = firstSlice(*lonVar, separable ? 1 : f.horizontal.size());
    if (f.horizontal.size() == 2) {
      g.ny = uint32_t(mR.dimLen(f.horizontal[0]));
      g.nx = uint32_t(mR.dimLen(f.horizontal[1]));
    } else {
      g.ny = 1;
      g.nx = uint32_t(mR.dimLen(f.horizontal[0]));
    }
    for (double v : lat)
      if (!std::isfinite(v) || std::fabs(v) > 90.0 + 1e-6)
        mR.fail(latVar->name, "latitude " + std::to_string(v) + " is not within [-90, 90]");
    for (double v : lon)
      if (!std::isfinite(v)) mR.fail(lonVar->name, "longitude is missing or not finite");
    if (separable && !lon.empty()) {
      // An axis already within [-180, 360) stays as it is (0..357.5, -180..177.5). Else the
      // whole axis moves by whole turns so its first longitude lies in [-180, 180), which
      // keeps it monotonic (350..365 -> -10..5); only when that fails is each point wrapped.
      auto inRange = [&](double shift) {
        return std::all_of(lon.begin(), lon.end(),
                           [&](double v) { return v + shift >= -180.0 && v + shift < 360.0; });
      };
      const double turns = std::floor((lon[0] + 180.0) / 360.0) * 360.0;
      if (!inRange(0.0)) {
        const bool shifted = inRange(-turns);
        for (double& v : lon) v = shifted ? v - turns : normaliseLon(v);
      }
    } else {
      for (double& v : lon) v = normaliseLon(v);
    }
    const size_t n = size_t(g.nx) * g.ny;
    g.latDeg.resize(n);
    g.lonDeg.resize(n);
    for (size_t j = 0; j < g.ny; ++j)
      for (size_t i = 0; i < g.nx; ++i) {
        const size_t k = j * g.nx + i;
        g.latDeg[k] = std::clamp(separable ? lat[j] : lat[k], -90.0, 90.0);
        g.lonDeg[k] = separable ? lon[i] : lon[k];
      }
    g.regularLatLon = isRegularGrid(g);
    return g;
  }

  // Valid times of time dimension d (Unix seconds): the CF coordinate, WRF's XTIME or
  // Times strings, or any 1D variable over d in "<unit> since <date>".
  std::vector<double> times(int d) const {
    const size_t n = mR.dimLen(d);
    auto cf = [&](const Var& v) -> std::optional<std::vector<double>> {
      if (v.dims != std::vector<int>{d} || !isNumeric(v.type) ||
          lower(v.units).find(" since ") == std::string::npos)
        return std::nullopt;
      const std::string calendar = lower(mR.textAttribute(v.id, "calendar").value_or("gregorian"));
      if (!oneOf(calendar, {"gregorian", "standard", "proleptic_gregorian", ""}))
        mR.fail(v.name, "calendar \"" + calendar + "\" is not supported (Gregorian only)");
      std::vector<double> out = mR.readAll(v);
      for (double& t : out) {
        if (!std::isfinite(t)) mR.fail(v.name, "a time value is missing");
        try {
          t = cfTimeToUnix(t, v.units);
        } catch (const Error& e) {
          mR.fail(v.name, e.what());
        }
      }
      return out;
    };
    if (const Var* c = mR.var(mR.dimName(d)))
      if (auto t = cf(*c)) return *t;
    if (const Var* x = mR.var("XTIME"))
      if (auto t = cf(*x)) return *t;
    if (const Var* s = mR.var("Times");
        s && s->type == NC_CHAR && s->dims.size() == 2 && s->dims[0] == d) {
      std::vector<double> out;
      for (size_t i = 0; i < n; ++i) {
        const std::string text = mR.readChars(*s, i);
        auto t = parseDateTime(text);
        if (!t) mR.fail(s->name, "cannot read the time \"" + text + "\"");
        out.push_back(*t);
      }
      return out;
    }
    for (const Var& v : mR.vars())
      if (auto t = cf(v)) return *t;
    mR.fail("", "time dimension " + mR.dimName(d) + " has no time coordinate");
  }

  // No time dimension: a scalar CF time coordinate (ERA5 with one time), else time 0.
  double scalarTime() const {
    for (const char* name : {"valid_time", "time", "Time"}) {
      const Var* v = mR.var(name);
      if (!v || !v->dims.empty() || !isNumeric(v->type) ||
          lower(v->units).find(" since ") == std::string::npos)
        continue;
      const double t = mR.readAll(*v).at(0);
      if (!std::isfinite(t)) mR.fail(v->name, "the time value is missing");
      try {
        return cfTimeToUnix(t, v->units);
      } catch (const Error& e) {
        mR.fail(v->name, e.what());
      }
    }
    return 0.0;
  }

  // hPa of each index of level dimension d.
  std::vector<double> levelsHpa(const FieldVar& f) const {
    const Var* c = pressureCoordinate(f.levelDim, f.timeDim, true);
    if (!c) {
      const Var* cv = mR.var(mR.dimName(f.levelDim));
      if (cv && cv->dims == std::vector<int>{f.levelDim})
        mR.fail(f.var->name, "level coordinate " + cv->name + " has units \"" + cv->units +
                                 "\", not a pressure (hPa or Pa)");
      mR.fail(f.var->name,
              "level dimension " + mR.dimName(f.levelDim) + " has no pressure coordinate variable");
    }
    std::vector<double> p = firstSlice(*c, 1);
    std::optional<double> scale = pressureScale(c->units);
    if (!scale && !c->units.empty())
      mR.fail(f.var->name, "level coordinate " + c->name + " has units \"" + c->units +
                               "\", not a pressure (hPa or Pa)");
    if (!scale) {
      // No units: values above any surface pressure in hPa must be Pa.
      const double maxP = *std::max_element(p.begin(), p.end());
      scale = maxP > 1100.0 ? 0.01 : 1.0;
    }
    for (double& x : p) {
      x *= *scale;
      if (!std::isfinite(x) || x <= 0.0 || x > 2000.0)
        mR.fail(c->name, "pressure level " + std::to_string(x) + " hPa is not a valid level");
    }
    return p;
  }

private:
  const Reader& mR;
};

// ---- units of a field -------------------------------------------------------------------

struct Conversion {
  double scale = 1.0;
  double offset = 0.0;
  bool percentByUnits = false;
};

[[noreturn]] void wrongUnits(const Reader& r, const Var& v, const char* expected) {
  r.fail(v.name, "units \"" + v.units + "\" are not " + expected);
}

Conversion conversion(const Reader& r, const FieldVar& f) {
  const std::string u = unitKey(f.var->units);
  switch (f.kind->quantity) {
    case Quantity::Fraction:
      if (oneOf(u, {"%", "percent", "pct"})) return {1.0, 0.0, true};
      if (!oneOf(u, {"", "1", "(0-1)", "0-1", "fraction", "dimensionless", "-", "~", "none"}))
        wrongUnits(r, *f.var, "a fraction (% or 1)");
      return {};
    case Quantity::Temperature:
      if (oneOf(u, {"", "k", "kelvin", "degk", "degreesk", "degree_kelvin", "deg_k"})) return {};
      if (oneOf(u, {"degc", "c", "celsius", "degreesc", "degree_celsius", "deg_c"}))
        return {1.0, 273.15, false};
      wrongUnits(r, *f.var, "a temperature (K or degC)");
    case Quantity::Height:
    case Quantity::Geopotential:
      if (oneOf(u, {"m", "gpm", "meter", "meters", "metre", "metres"}) ||
          (u.empty() && f.kind->quantity == Quantity::Height))
        return {};
      // ERA5's z is geopotential, m2 s-2 (units omitted in some conversions).
      if (oneOf(u, {"m2s-2", "m2/s2", "j/kg", "jkg-1", ""}))
        return {1.0 / kStandardGravity, 0.0, false};
      wrongUnits(r, *f.var, "a geopotential height (m, gpm) or geopotential (m2 s-2)");
    case Quantity::Wind:
      if (oneOf(u, {"", "ms-1", "m/s", "m.s-1", "meter/second", "meters/second", "metre/second",
                    "metres/second", "mps"}))
        return {};
      if (oneOf(u, {"kt", "kts", "knot", "knots"})) return {0.514444, 0.0, false};
      wrongUnits(r, *f.var, "a speed (m s-1)");
  }
  return {};
}

}  // namespace

WeatherFields readNetcdf(const std::filesystem::path& file) {
  std::error_code ec;
  if (!fs::exists(file, ec)) inputError(file.string() + ": no such file");
  if (!fs::is_regular_file(file, ec)) inputError(file.string() + ": not a regular file");

  // Classic files (CDF-1/2/5) are read into memory, checked (libnetcdf trusts their header
  // counts and can crash on corrupt ones) and opened from there: libnetcdf then reports a
  // read past the end of a truncated file as an error, where from disk it returns zeros.
  // NetCDF-4 (HDF5) files are opened from disk; HDF5 detects truncation itself.
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    char magic[4] = {};
    in.read(magic, 4);
    if (in.gcount() < 4) inputError(file.string() + ": not a NetCDF file (too short)");
    if (std::string_view(magic, 3) == "CDF") {
      in.seekg(0);
      bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      if (auto problem = detail::classicHeaderProblem(bytes))
        inputError(file.string() + ": not a valid NetCDF file: " + *problem);
    }
  }
  const bool classic = !bytes.empty();
  NcFile nc = classic ? NcFile(file, bytes) : NcFile(file);
  if (nc.status() != NC_NOERR)
    inputError(file.string() + ": not a NetCDF file (" + nc_strerror(nc.status()) + ")");

  const Reader r(file, nc.id(), classic);
  const NetcdfLayout layout(r);
  const std::vector<FieldVar> vars = layout.fieldVars();
  if (vars.empty()) {
    std::string found;
    for (const Var& v : r.vars()) found += (found.empty() ? "" : ", ") + v.name;
    r.fail("", "no usable variable (r, t, gh, z, u, v, lcc, mcc or hcc; the file has " +
                   (found.empty() ? std::string("none") : found) + ")");
  }

  const FieldVar& first = vars.front();
  r.checkSize(*first.var);  // before the grid is allocated from its dimensions
  FieldChecks checks(file.string());
  size_t nonFinite = 0;  // of the level being read
  WeatherFields out;
  out.file = file;
  out.grid = layout.grid(first);
  int timeDim = -1;
  for (const FieldVar& f : vars) {
    if (f.horizontal != first.horizontal)
      r.fail(f.var->name, "dimensions " + layout.dimList(*f.var) + " are not on the grid of " +
                              first.var->name + " " + layout.dimList(*first.var));
    if (f.timeDim >= 0 && timeDim >= 0 && f.timeDim != timeDim)
      r.fail(f.var->name,
             "time dimension " + r.dimName(f.timeDim) + " differs from " + r.dimName(timeDim));
    if (f.timeDim >= 0) timeDim = f.timeDim;
  }
  const std::vector<double> times =
      timeDim >= 0 ? layout.times(timeDim) : std::vector<double>{layout.scalarTime()};
  if (times.empty()) r.fail("", "time dimension " + r.dimName(timeDim) + " is empty");
  out.steps.resize(times.size());
  for (size_t s = 0; s < times.size(); ++s) out.steps[s].validTimeUnix = times[s];

  const size_t points = out.grid.size();
  for (const FieldVar& f : vars) {
    const Var& v = *f.var;
    const std::vector<double> levels =
        f.levelDim >= 0 ? layout.levelsHpa(f) : std::vector<double>{0.0};
    Conversion conv = conversion(r, f);
    const size_t firstField = out.steps[0].fields.size();
    double maxValue = -std::numeric_limits<double>::infinity();
    for (size_t s = 0; s < (f.timeDim >= 0 ? times.size() : size_t(1)); ++s)
      for (size_t k = 0; k < levels.size(); ++k) {
        std::vector<size_t> start(v.dims.size(), 0), count(v.dims.size(), 1);
        for (size_t i = 0; i < v.dims.size(); ++i) {
          if (v.dims[i] == f.timeDim) start[i] = s;
          if (v.dims[i] == f.levelDim) start[i] = k;
          if (std::find(f.horizontal.begin(), f.horizontal.end(), v.dims[i]) != f.horizontal.end())
            count[i] = r.dimLen(v.dims[i]);
        }
        std::vector<double> raw = r.read(v, start, count);
        LevelField field{f.kind->field, levels[k], std::vector<float>(points)};
        for (size_t p = 0; p < points; ++p) {
          // A value beyond float's range is garbage, not data: missing like a fill.
          const double x = raw[p] * conv.scale + conv.offset;
          const bool usable = std::isfinite(x) && std::fabs(x) <= double(FLT_MAX);
          if (usable) maxValue = std::max(maxValue, x);
          // NaN in raw is a fill (read() maps them); a stored value that converts to NaN
          // or beyond float is counted (FieldChecks).
          nonFinite += !usable && !std::isnan(raw[p]);
          field.values[p] = usable ? float(x) : kNaN;
        }
        checks.noteNonFinite(v.name, nonFinite, points);
        nonFinite = 0;
        out.steps[s].fields.push_back(std::move(field));
      }
    // A field without a time dimension holds at every time.
    if (f.timeDim < 0)
      for (size_t s = 1; s < out.steps.size(); ++s)
        out.steps[s].fields.insert(out.steps[s].fields.end(),
                                   out.steps[0].fields.begin() + long(firstField),
                                   out.steps[0].fields.end());
    if (f.kind->quantity != Quantity::Fraction) continue;

    // Fractions: percent by units or, whatever the units say, by a maximum above 1.5 (no
    // fraction reaches that; a percent field that does not is all but cloudless and dry).
    const bool percent = conv.percentByUnits || maxValue > 1.5;
    for (WeatherStep& step : out.steps)
      for (LevelField& field : step.fields)
        if (field.kind == f.kind->field) checks.toFraction(field.values, percent ? 0.01 : 1.0, v.name);
  }

  std::stable_sort(
      out.steps.begin(), out.steps.end(),
      [](const WeatherStep& a, const WeatherStep& b) { return a.validTimeUnix < b.validTimeUnix; });
  checks.finish(out);
  return out;
}

}  // namespace sky
