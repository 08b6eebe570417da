#include "engine/weather/grib_reader.h"

#include <eccodes.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/error.h"
#include "engine/weather/field_checks.h"
#include "engine/scene/iso_time.h"

namespace sky {
namespace {

// Larger grids are taken for a corrupt header rather than allocated: one flipped bit in
// numberOfPoints would otherwise ask ecCodes for gigabytes (and ecCodes aborts the process
// when an allocation fails). 2^27 points is a 0.02-degree global grid, finer than any
// operational model.
constexpr long kMaxPoints = 1L << 27;

// ecCodes reports its errors through a logging callback, by default several lines on
// stderr. We keep the last one to put into our own one-line message instead.
thread_local std::string tLastLog;

void captureLog(const codes_context*, int level, const char* message) {
  // Called from C: must not throw.
  if ((level == CODES_LOG_ERROR || level == CODES_LOG_FATAL) && message) {
    try {
      tLastLog = message;
    } catch (...) {
    }
  }
}

// ecCodes checks some of its invariants with an assertion that aborts the process unless a
// handler is set, and corrupt input reaches them (complex packing whose group lengths add up
// to more values than the message holds). The handler must not return: ecCodes would carry
// on past the check into a buffer overrun. It throws instead; the exception unwinds through
// ecCodes' C frames (built with unwind tables), losing only that call's scratch memory, and
// readGrib2 turns it into a BadInput naming the message.
struct EccodesAssertion {
  std::string message;
};

void assertionFailed(const char* message) {
  throw EccodesAssertion{message ? message : "ecCodes assertion failed"};
}

// ecCodes keeps its multi-field state per process, so readers take turns.
std::mutex& eccodesMutex() {
  static std::mutex m;
  return m;
}

void setUpEccodes() {
  static std::once_flag once;
  std::call_once(once, [] {
    codes_context* ctx = codes_context_get_default();
    codes_context_set_logging_proc(ctx, captureLog);
    codes_set_codes_assertion_failed_proc(assertionFailed);
    // NCEP packs u and v into one message (several fields after one grid section); without
    // this ecCodes would show only the first field of such a message.
    codes_grib_multi_support_on(ctx);
  });
}

std::string eccodesReason(int err) {
  std::string why = codes_get_error_message(err);
  if (!tLastLog.empty()) why += " (" + tLastLog + ")";
  return why;
}

struct HandleDeleter {
  void operator()(codes_handle* h) const { codes_handle_delete(h); }
};
using HandlePtr = std::unique_ptr<codes_handle, HandleDeleter>;

struct IteratorDeleter {
  void operator()(codes_iterator* it) const { codes_grib_iterator_delete(it); }
};

// The open file. ecCodes' multi-field state is keyed by the FILE*, which a later fopen may
// reuse: it is reset before the file closes.
class GribFile {
public:
  explicit GribFile(const std::filesystem::path& path) : mFile(std::fopen(path.c_str(), "rb")) {}
  ~GribFile() {
    if (!mFile) return;
    codes_grib_multi_support_reset_file(codes_context_get_default(), mFile);
    std::fclose(mFile);
  }
  GribFile(const GribFile&) = delete;
  GribFile& operator=(const GribFile&) = delete;
  FILE* get() const { return mFile; }

private:
  FILE* mFile;
};

// Where each GRIB message lies in the file, found by walking the framing the way ecCodes
// does: the "GRIB" marker, the total length, and for GRIB2 every section's length and number
// up to the closing "7777". ecCodes 2.28's multi-field reader frees a buffer twice on a
// message whose sections do not add up (found by GribFuzz), so such a message is refused
// here before ecCodes sees it; truncation gets a clearer message too.
struct MessageSpan {
  uint64_t offset = 0, length = 0;
};

class Framing {
public:
  Framing(FILE* f, std::string fileName, uint64_t size)
      : mFile(f), mName(std::move(fileName)), mSize(size) {}

  std::vector<MessageSpan> scan() {
    std::vector<MessageSpan> spans;
    uint64_t pos = 0;
    while (std::optional<uint64_t> at = findMarker(pos)) {
      mNumber = int(spans.size()) + 1;
      unsigned char head[16];
      if (!readAt(*at, head, 16)) fail(*at, "the file ends inside the message header");
      MessageSpan span{*at, 0};
      if (head[7] == 2) {
        for (int i = 8; i < 16; ++i) span.length = span.length << 8 | head[i];
        checkLength(span);
        walkSections(span);
      } else if (head[7] == 1) {
        span.length = uint64_t(head[4]) << 16 | uint64_t(head[5]) << 8 | head[6];
        // Lengths past 8 MiB use ECMWF's scaled encoding, which ecCodes resolves itself.
        if (span.length & 0x800000) return spans;
        checkLength(span);
        checkEnd(span);
      } else {
        // "GRIB" in text or in another message's bytes, not a header: look further on.
        pos = *at + 4;
        continue;
      }
      spans.push_back(span);
      pos = span.offset + span.length;
    }
    return spans;
  }

private:
  [[noreturn]] void fail(uint64_t at, const std::string& what) const {
    inputError(mName + ": message " + std::to_string(mNumber) + " (byte " + std::to_string(at) +
               "): " + what);
  }
  bool readAt(uint64_t at, unsigned char* out, size_t n) const {
    return at + n <= mSize && fseeko(mFile, off_t(at), SEEK_SET) == 0 &&
           std::fread(out, 1, n, mFile) == n;
  }
  std::optional<uint64_t> findMarker(uint64_t from) const {
    unsigned char buf[1 << 16];
    while (from + 4 <= mSize) {
      size_t n = size_t(std::min<uint64_t>(sizeof buf, mSize - from));
      if (!readAt(from, buf, n)) return std::nullopt;
      for (size_t i = 0; i + 4 <= n; ++i)
        if (buf[i] == 'G' && buf[i + 1] == 'R' && buf[i + 2] == 'I' && buf[i + 3] == 'B')
          return from + i;
      from += n - 3;
    }
    return std::nullopt;
  }
  void checkLength(const MessageSpan& s) const {
    if (s.length < 20) fail(s.offset, "message length " + std::to_string(s.length));
    if (s.length > mSize - s.offset)
      fail(s.offset, std::to_string(s.length) + " bytes announced, " +
                         std::to_string(mSize - s.offset) + " left in the file (truncated?)");
  }
  void checkEnd(const MessageSpan& s) const {
    unsigned char end[4];
    if (!readAt(s.offset + s.length - 4, end, 4) || std::memcmp(end, "7777", 4) != 0)
      fail(s.offset, "no 7777 where the message should end (truncated or corrupt)");
  }
  // GRIB2 sections 1, [2], 3, 4, 5, [6], 7; a multi-field message repeats from 2, 3 or 4.
  void walkSections(const MessageSpan& s) const {
    checkEnd(s);
    const uint64_t end = s.offset + s.length - 4;
    uint64_t p = s.offset + 16;
    int last = 0;
    while (p < end) {
      unsigned char h[5];
      if (p + 5 > end || !readAt(p, h, 5)) fail(p, "a section runs into the end marker");
      uint64_t len = uint64_t(h[0]) << 24 | uint64_t(h[1]) << 16 | uint64_t(h[2]) << 8 | h[3];
      int number = h[4];
      bool ok = last == 0   ? number == 1
                : last == 1 ? number == 2 || number == 3
                : last == 7 ? number >= 2 && number <= 4
                : last == 5 ? number == 6 || number == 7
                            : number == last + 1;
      if (!ok || len < 5 || len > end - p)
        fail(p, "section " + std::to_string(number) + " of length " + std::to_string(len) +
                    " after section " + std::to_string(last));
      last = number;
      p += len;
    }
    if (last != 7) fail(s.offset, "the message ends after section " + std::to_string(last));
  }

  FILE* mFile;
  std::string mName;
  uint64_t mSize;
  int mNumber = 0;
};

// One field (one message, or one field of a multi-field message) with key access that
// throws a one-line BadInput naming the file and message number.
class Message {
public:
  Message(codes_handle* h, std::string where) : mHandle(h), mWhere(std::move(where)) {}

  codes_handle* handle() const { return mHandle; }
  [[noreturn]] void fail(const std::string& what) const { inputError(mWhere + ": " + what); }
  [[noreturn]] void failKey(const std::string& key, int err) const {
    fail("key " + key + ": " + eccodesReason(err));
  }

  bool present(const char* key) const {
    int err = 0;
    return codes_is_defined(mHandle, key) == 1 && codes_is_missing(mHandle, key, &err) == 0 &&
           err == 0;
  }
  long getLong(const char* key) const {
    long v = 0;
    if (int err = codes_get_long(mHandle, key, &v)) failKey(key, err);
    return v;
  }
  double getDouble(const char* key) const {
    double v = 0.0;
    if (int err = codes_get_double(mHandle, key, &v)) failKey(key, err);
    return v;
  }
  std::optional<std::string> tryString(const char* key) const {
    char buf[256] = {};
    size_t len = sizeof buf;
    if (codes_get_string(mHandle, key, buf, &len) != 0) return std::nullopt;
    return std::string(buf);
  }

private:
  codes_handle* mHandle;
  std::string mWhere;
};

// A field this reader keeps, in WeatherFields' naming.
struct Wanted {
  FieldKind kind;
  double pressureHpa = 0.0;
  bool fraction = false;  // r and tcc: 0..1 after conversion, clamped
};

std::string hPaText(double hPa) {
  char text[32];
  std::snprintf(text, sizeof text, "%g hPa", hPa);
  return text;
}

std::optional<Wanted> classify(const Message& m) {
  std::optional<std::string> shortName = m.tryString("shortName");
  std::optional<std::string> levelType = m.tryString("typeOfLevel");
  if (!shortName || !levelType) return std::nullopt;
  if (*shortName == "tcc") {
    static const std::pair<const char*, FieldKind> kLayers[] = {
        {"lowCloudLayer", FieldKind::CloudCoverLow},
        {"middleCloudLayer", FieldKind::CloudCoverMid},
        {"highCloudLayer", FieldKind::CloudCoverHigh}};
    for (const auto& [type, kind] : kLayers)
      if (*levelType == type) return Wanted{kind, 0.0, true};
    return std::nullopt;
  }
  // The fields on pressure levels, by the shortName fieldName() gives them.
  static const FieldKind kOnLevels[] = {FieldKind::RelativeHumidity, FieldKind::GeopotentialHeight,
                                        FieldKind::Temperature, FieldKind::WindU, FieldKind::WindV};
  const FieldKind* kind = std::find_if(std::begin(kOnLevels), std::end(kOnLevels),
                                       [&](FieldKind k) { return *shortName == fieldName(k); });
  if (kind == std::end(kOnLevels)) return std::nullopt;
  double hPa = 0.0;
  if (*levelType == "isobaricInhPa")
    hPa = m.getDouble("level");
  else if (*levelType == "isobaricInPa")  // levels below 1 hPa
    hPa = m.getDouble("level") / 100.0;
  else
    return std::nullopt;
  if (!(hPa > 0.0 && hPa < 2000.0)) m.fail(*shortName + " on isobaric level " + hPaText(hPa));
  return Wanted{*kind, hPa, *kind == FieldKind::RelativeHumidity};
}

// Percent unless the parameter table says the field is already a fraction (ECMWF-style
// "(0 - 1)").
double fractionScale(const Message& m) {
  std::optional<std::string> units = m.tryString("units");
  if (units && (*units == "(0 - 1)" || *units == "Proportion" || *units == "Fraction")) return 1.0;
  return 0.01;
}

long pointCount(const Message& m) {
  long n = m.getLong("numberOfPoints");
  if (n <= 0 || n > kMaxPoints)
    m.fail("numberOfPoints " + std::to_string(n) + " outside 1.." + std::to_string(kMaxPoints));
  return n;
}

// Every point's position from ecCodes' geoiterator, which knows every grid type ecCodes
// does (regular and rotated lat/lon, Lambert conformal, polar stereographic, Gaussian,
// reduced grids...).
GridGeometry readGeometry(const Message& m) {
  std::string gridType = m.tryString("gridType").value_or("unknown");
  if (gridType == "sh")
    m.fail("gridType sh: spherical harmonics have no grid points (convert to a grid first)");
  const long n = pointCount(m);
  GridGeometry g;
  // The counts must agree before the geoiterator runs: it writes as many points as they
  // describe into arrays sized by numberOfPoints (a corrupt Ni = 0 crashes ecCodes 2.28).
  if (gridType.starts_with("reduced_")) {
    size_t rows = 0;
    if (int err = codes_get_size(m.handle(), "pl", &rows)) m.failKey("pl", err);
    if (rows == 0 || rows > size_t(n)) m.fail("pl has " + std::to_string(rows) + " rows");
    std::vector<long> pl(rows);
    if (int err = codes_get_long_array(m.handle(), "pl", pl.data(), &rows)) m.failKey("pl", err);
    long sum = 0;
    for (long r : pl) sum += (r < 0 || r > n) ? n + 1 : r;
    if (sum != n)
      m.fail("the rows (pl) hold " + std::to_string(sum) + " points, numberOfPoints " +
             std::to_string(n));
    g.nx = uint32_t(n);
    g.ny = 1;
  } else {
    // Template 3.30 (Lambert) and polar stereographic name their counts Nx/Ny.
    long ni = m.present("Ni") ? m.getLong("Ni") : (m.present("Nx") ? m.getLong("Nx") : 0);
    long nj = m.present("Nj") ? m.getLong("Nj") : (m.present("Ny") ? m.getLong("Ny") : 0);
    if (ni <= 0 || nj <= 0 || ni > n || nj > n || ni * nj != n)
      m.fail("grid " + std::to_string(ni) + " x " + std::to_string(nj) + " but numberOfPoints " +
             std::to_string(n));
    bool columnsFirst = m.present("jPointsAreConsecutive") && m.getLong("jPointsAreConsecutive");
    g.nx = uint32_t(columnsFirst ? nj : ni);
    g.ny = uint32_t(columnsFirst ? ni : nj);
  }

  int err = 0;
  std::unique_ptr<codes_iterator, IteratorDeleter> it(codes_grib_iterator_new(m.handle(), 0, &err));
  if (!it || err) m.fail("gridType " + gridType + ": no point positions: " + eccodesReason(err));
  g.latDeg.reserve(size_t(n));
  g.lonDeg.reserve(size_t(n));
  double lat = 0.0, lon = 0.0, value = 0.0;
  while (codes_grib_iterator_next(it.get(), &lat, &lon, &value)) {
    if (g.latDeg.size() == size_t(n)) m.fail("the grid has more points than numberOfPoints");
    if (!std::isfinite(lat) || !std::isfinite(lon) || std::fabs(lat) > 90.0 + 1e-6)
      m.fail("point " + std::to_string(g.latDeg.size()) + " at latitude " + std::to_string(lat) +
             ", longitude " + std::to_string(lon));
    g.latDeg.push_back(std::clamp(lat, -90.0, 90.0));
    g.lonDeg.push_back(normaliseLon(lon));
  }
  if (g.latDeg.size() != size_t(n))
    m.fail("the grid gives " + std::to_string(g.latDeg.size()) + " points, numberOfPoints " +
           std::to_string(n));
  g.regularLatLon = gridType == "regular_ll" && isRegularGrid(g);
  return g;
}

// A cheap fingerprint to tell whether a message repeats the grid already read; on a
// mismatch the positions themselves are compared (the same grid may be encoded differently).
struct GridKey {
  std::string gridType, md5;
  long points = 0;
  bool operator==(const GridKey&) const = default;
};

GridKey gridKey(const Message& m) {
  return {m.tryString("gridType").value_or(""), m.tryString("md5GridSection").value_or(""),
          pointCount(m)};
}

bool sameGrid(const GridGeometry& a, const GridGeometry& b) {
  if (a.nx != b.nx || a.ny != b.ny || a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    double dLon = std::fabs(a.lonDeg[i] - b.lonDeg[i]);
    if (std::fabs(a.latDeg[i] - b.latDeg[i]) > 1e-6 || std::min(dLon, 360.0 - dLon) > 1e-6)
      return false;
  }
  return true;
}

// Valid time from validityDate (YYYYMMDD) and validityTime (HHMM), which ecCodes derives
// from the reference time and the (end of the) forecast step.
double validTimeUnix(const Message& m) {
  // ecCodes 2.28 loops forever computing the validity of a step in an undefined unit (found
  // by GribFuzz): the units are checked against code table 4.4 first.
  for (const char* key :
       {"indicatorOfUnitOfTimeRange", "indicatorOfUnitForTimeRange", "unitOfTimeRange"}) {
    if (!m.present(key)) continue;
    long unit = m.getLong(key);
    if (!((unit >= 0 && unit <= 7) || (unit >= 10 && unit <= 13) || unit == 254))
      m.fail(std::string(key) + " " + std::to_string(unit) + " is not a unit of time");
  }
  long date = m.getLong("validityDate");
  long time = m.getLong("validityTime");
  char text[64];
  std::snprintf(text, sizeof text, "%04ld-%02ld-%02ldT%02ld:%02ld:00Z", date / 10000,
                date / 100 % 100, date % 100, time / 100, time % 100);
  std::optional<IsoTime> t = IsoTime::parse(text);
  if (!t || date < 0 || time < 0 || time % 100 > 59)
    m.fail("validityDate " + std::to_string(date) + " validityTime " + std::to_string(time) +
           " is not a date and time");
  return double(t->unixSeconds);
}

// Reads `bits` (<= 32) big-endian bits at bit offset `pos` of `data`, advancing `pos`.
uint64_t readBits(const unsigned char* data, uint64_t& pos, long bits) {
  uint64_t v = 0;
  for (long b = 0; b < bits; ++b, ++pos) v = v << 1 | ((data[pos / 8] >> (7 - pos % 8)) & 1u);
  return v;
}

// ecCodes 2.28 decodes the data section without checking that it holds what section 5 says
// it does, and reads past its buffer when it does not (found by GribFuzz). For the packings
// that weather centres use for these fields (simple 5.0, complex 5.2, complex with spatial
// differencing 5.3) the bits the decoder will read are counted here first, following its
// layout (data_g22order_packing.c): group references, widths, lengths, then the values.
void checkDataSection(const Message& m) {
  if (!m.present("dataRepresentationTemplateNumber") || m.getLong("edition") != 2) return;
  const long tmpl = m.getLong("dataRepresentationTemplateNumber");
  const void* msg = nullptr;
  size_t msgSize = 0;
  if (int err = codes_get_message(m.handle(), &msg, &msgSize)) m.failKey("message", err);
  // Every packing starts section 5 with the reference value R, an IEEE single (octets
  // 12-15), and every value is R + X 2^E / 10^D. ecCodes reads a NaN R as 0, so each value
  // came out as finite garbage: heights near 0 m, tops below bases (issue 31, 9).
  const long section5 = m.getLong("offsetSection5");
  if (section5 < 0 || uint64_t(section5) + 15 > msgSize) m.fail("section 5 outside the message");
  const unsigned char* r = static_cast<const unsigned char*>(msg) + section5 + 11;
  const uint32_t ieee = uint32_t(r[0]) << 24 | uint32_t(r[1]) << 16 | uint32_t(r[2]) << 8 | r[3];
  if ((ieee & 0x7f800000u) == 0x7f800000u)
    m.fail(m.tryString("shortName").value_or("field") + ": the reference value of its data is " +
           ((ieee & 0x007fffffu) ? "NaN" : "infinite") + ": the field is unusable");
  if (tmpl != 0 && tmpl != 2 && tmpl != 3) return;
  const long at = m.getLong("offsetSection7"), length = m.getLong("section7Length");
  if (at < 0 || length < 5 || uint64_t(at) + uint64_t(length) > msgSize)
    m.fail("section 7 outside the message");
  const unsigned char* data = static_cast<const unsigned char*>(msg) + at + 5;
  const uint64_t haveBits = uint64_t(length - 5) * 8;
  const long values = m.getLong("numberOfValues"), bpv = m.getLong("bitsPerValue");
  if (values < 0 || values > kMaxPoints || bpv < 0 || bpv > 32)
    m.fail("numberOfValues " + std::to_string(values) + ", bitsPerValue " + std::to_string(bpv));
  auto bytes = [](uint64_t bits) { return (bits + 7) / 8 * 8; };
  auto tooShort = [&](uint64_t need) {
    m.fail("the data section holds " + std::to_string(haveBits) + " bits, the packing needs " +
           std::to_string(need));
  };
  if (tmpl == 0) {
    if (uint64_t(values) * uint64_t(bpv) > haveBits) tooShort(uint64_t(values) * uint64_t(bpv));
    return;
  }
  const long groups = m.getLong("numberOfGroupsOfDataValues");
  const long widthRef = m.getLong("referenceForGroupWidths");
  const long widthBits = m.getLong("numberOfBitsUsedForTheGroupWidths");
  const long lengthRef = m.getLong("referenceForGroupLengths");
  const long lengthInc = m.getLong("lengthIncrementForTheGroupLengths");
  const long lastLength = m.getLong("trueLengthOfLastGroup");
  const long lengthBits = m.getLong("numberOfBitsForScaledGroupLengths");
  long order = 0, extraOctets = 0;
  if (tmpl == 3) {
    order = m.getLong("orderOfSpatialDifferencing");
    extraOctets = m.getLong("numberOfOctetsExtraDescriptors");
  }
  if (groups < 0 || groups > values || widthBits < 0 || widthBits > 32 || lengthBits < 0 ||
      lengthBits > 32 || order < 0 || order > 2 || extraOctets < 0 || extraOctets > 4)
    m.fail("complex packing with " + std::to_string(groups) + " groups, group width bits " +
           std::to_string(widthBits) + ", length bits " + std::to_string(lengthBits) +
           ", spatial differencing order " + std::to_string(order));
  const uint64_t g = uint64_t(groups);
  uint64_t widthsAt =
      bytes(g * uint64_t(bpv) + (order ? uint64_t(order + 1) * extraOctets * 8 : 0));
  uint64_t lengthsAt = widthsAt + bytes(g * uint64_t(widthBits));
  uint64_t valuesAt = lengthsAt + bytes(g * uint64_t(lengthBits));
  if (valuesAt > haveBits) tooShort(valuesAt);
  uint64_t count = 0, need = valuesAt;
  uint64_t wPos = widthsAt, lPos = lengthsAt;
  for (long i = 0; i < groups; ++i) {
    uint64_t width = readBits(data, wPos, widthBits) + uint64_t(widthRef);
    uint64_t len = (i == groups - 1) ? uint64_t(lastLength)
                                     : readBits(data, lPos, lengthBits) * uint64_t(lengthInc) +
                                           uint64_t(lengthRef);
    if (i == groups - 1) readBits(data, lPos, lengthBits);
    if (width > 32 || len > uint64_t(values) || lastLength < 0)
      m.fail("complex packing group " + std::to_string(i) + ": " + std::to_string(len) +
             " values of " + std::to_string(width) + " bits");
    count += len;
    need += len * width;
    if (count > uint64_t(values))
      m.fail("complex packing groups hold more than numberOfValues " + std::to_string(values));
  }
  if (count != uint64_t(values))
    m.fail("complex packing groups hold " + std::to_string(count) + " values, numberOfValues " +
           std::to_string(values));
  if (need > haveBits) tooShort(need);
}

std::vector<float> readValues(const Message& m, size_t n, size_t& nonFinite) {
  size_t count = 0;
  if (int err = codes_get_size(m.handle(), "values", &count)) m.failKey("values", err);
  if (count != n)
    m.fail(std::to_string(count) + " values for " + std::to_string(n) + " grid points");
  std::vector<double> raw(n);
  if (int err = codes_get_double_array(m.handle(), "values", raw.data(), &count))
    m.failKey("values", err);
  if (count != n)
    m.fail("decoded " + std::to_string(count) + " of " + std::to_string(n) + " values");
  // ecCodes writes missingValue where the bitmap (or complex packing's own missing-value
  // management) marks a point missing.
  bool mayMiss =
      (m.present("bitmapPresent") && m.getLong("bitmapPresent") != 0) ||
      (m.present("missingValueManagementUsed") && m.getLong("missingValueManagementUsed") != 0);
  double missing = mayMiss ? m.getDouble("missingValue") : std::numeric_limits<double>::quiet_NaN();
  std::vector<float> out(n);
  nonFinite = 0;
  for (size_t i = 0; i < n; ++i) {
    const bool declared = mayMiss && raw[i] == missing;
    // A value the bitmap does not mark missing but that decodes to NaN or beyond float (a
    // NaN reference value or scale in the data section): missing too, but counted.
    const bool usable = std::isfinite(raw[i]) && std::fabs(raw[i]) <= double(FLT_MAX);
    if (!declared && !usable) ++nonFinite;
    out[i] = declared || !usable ? std::numeric_limits<float>::quiet_NaN() : float(raw[i]);
  }
  if (nonFinite == n)
    m.fail("every value decodes to NaN or infinity (a NaN reference value or scale?): the "
           "field is unusable");
  return out;
}

}  // namespace

WeatherFields readGrib2(const std::filesystem::path& file) {
  const std::string fileName = file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    inputError(fileName + ": no such file (expected a GRIB2 forecast file)");

  std::lock_guard lock(eccodesMutex());
  setUpEccodes();
  GribFile in(file);
  if (!in.get()) inputError(fileName + ": cannot open for reading");
  const std::vector<MessageSpan> spans =
      Framing(in.get(), fileName, std::filesystem::file_size(file, ec)).scan();
  if (spans.empty()) inputError(fileName + ": not a GRIB file (no GRIB message found)");
  std::map<uint64_t, int> numberAt;  // message offset -> 1-based message number
  for (size_t i = 0; i < spans.size(); ++i) numberAt[spans[i].offset] = int(i) + 1;
  std::rewind(in.get());

  WeatherFields out;
  out.file = file;
  std::optional<GridKey> firstKey;
  std::map<double, WeatherStep> steps;
  FieldChecks checks(fileName);
  bool haveCloudInput = false;
  int number = 0;  // of the message being read; fields of a multi-field message share it
  std::string where = fileName + ": message 1";
  try {
    for (;;) {
      tLastLog.clear();
      int err = 0;
      HandlePtr h(codes_handle_new_from_file(nullptr, in.get(), PRODUCT_GRIB, &err));
      if (err != 0) {
        where = fileName + ": message " + std::to_string(number + 1);
        inputError(where + ": " + eccodesReason(err));
      }
      if (!h) break;  // end of file
      off_t offset = 0;
      auto found = codes_get_message_offset(h.get(), &offset) == 0 ? numberAt.find(uint64_t(offset))
                                                                   : numberAt.end();
      number = found != numberAt.end() ? found->second : number + 1;
      where = fileName + ": message " + std::to_string(number);
      Message m(h.get(), where);
      std::optional<Wanted> wanted = classify(m);
      if (!wanted) continue;
      checkDataSection(m);  // before anything decodes the values (the geoiterator does)

      GridKey key = gridKey(m);
      if (!firstKey) {
        out.grid = readGeometry(m);
        firstKey = key;
      } else if (!(key == *firstKey) && !sameGrid(readGeometry(m), out.grid)) {
        m.fail("grid differs from the file's first field (" + key.gridType + ", " +
               std::to_string(key.points) + " points; expected " + firstKey->gridType + ", " +
               std::to_string(firstKey->points) + "); split the file with grib_copy");
      }

      size_t nonFinite = 0;
      LevelField field{wanted->kind, wanted->pressureHpa,
                       readValues(m, out.grid.size(), nonFinite)};
      const std::string name = fieldName(field.kind);
      checks.noteNonFinite(name, nonFinite, field.values.size());
      if (wanted->fraction) checks.toFraction(field.values, fractionScale(m), name);
      haveCloudInput = haveCloudInput || wanted->fraction;

      const double valid = validTimeUnix(m);
      WeatherStep& step = steps[valid];
      step.validTimeUnix = valid;
      if (step.find(field.kind, field.pressureHpa))
        m.fail("a second " + name +
               (field.pressureHpa > 0.0 ? " at " + hPaText(field.pressureHpa) : "") +
               " for the same valid time (ensemble members or duplicates: select one with "
               "grib_copy -w)");
      step.fields.push_back(std::move(field));
    }
  } catch (const EccodesAssertion& a) {
    inputError(where + ": corrupt message (" + a.message + ")");
  }

  if (!haveCloudInput)
    inputError(fileName +
               ": no relative humidity or cloud cover (r on isobaric levels, tcc on the low, "
               "middle or high cloud layer) in " +
               std::to_string(spans.size()) + " messages");
  for (auto& [time, step] : steps) out.steps.push_back(std::move(step));
  checks.finish(out);
  return out;
}

}  // namespace sky
