#include "engine/weather/detail/netcdf_classic_header.h"

#include <cstdint>

namespace sky::detail {
namespace {

struct HeaderProblem {
  std::string what;
};

// Reads the header's big-endian fields as laid out in the NetCDF classic format
// specification (docs.unidata.ucar.edu/netcdf-c, "File Format Specifications").
class HeaderCursor {
public:
  HeaderCursor(std::string_view bytes, int version) : mB(bytes), mVersion(version) {}

  uint64_t remaining() const { return mB.size() - mPos; }

  uint64_t u32() { return big(4); }
  // NON_NEG and nelems: 8 bytes in CDF-5, else 4.
  uint64_t count() { return big(mVersion == 5 ? 8 : 4); }
  // OFFSET (a variable's begin): 4 bytes in CDF-1, else 8.
  uint64_t offset() { return big(mVersion == 1 ? 4 : 8); }

  void skip(uint64_t n, const char* what) {
    if (n > remaining()) fail(std::string(what) + " runs past the end of the file");
    mPos += size_t(n);
  }

  // `n` items of at least `minBytes` each must fit in what is left.
  void expectRoom(uint64_t n, uint64_t minBytes, const char* what) {
    if (n > remaining() / minBytes)
      fail(std::string(what) + " count " + std::to_string(n) + " does not fit the file");
  }

  void name(const char* what) {
    const uint64_t len = count();
    if (len == 0 || len > 256) fail(std::string(what) + " name length " + std::to_string(len));
    skip((len + 3) / 4 * 4, what);
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw HeaderProblem{what + " (header byte " + std::to_string(mPos) + ")"};
  }

  int version() const { return mVersion; }

private:
  uint64_t big(size_t n) {
    if (n > remaining()) fail("header ends early");
    uint64_t v = 0;
    for (size_t i = 0; i < n; ++i) v = (v << 8) | static_cast<unsigned char>(mB[mPos + i]);
    mPos += n;
    return v;
  }

  std::string_view mB;
  int mVersion;
  size_t mPos = 0;
};

constexpr uint64_t kDimensionTag = 0x0A, kVariableTag = 0x0B, kAttributeTag = 0x0C;

// Bytes per value of nc_type t, 0 when t is not a type of this format version.
uint64_t typeSize(uint64_t t, int version) {
  switch (t) {
    case 1:
    case 2:
      return 1;  // byte, char
    case 3:
      return 2;  // short
    case 4:
    case 5:
      return 4;  // int, float
    case 6:
      return 8;  // double
    default:
      break;
  }
  if (version != 5) return 0;
  switch (t) {
    case 7:
      return 1;  // ubyte
    case 8:
      return 2;  // ushort
    case 9:
      return 4;  // uint
    case 10:
    case 11:
      return 8;  // int64, uint64
    default:
      return 0;
  }
}

// ABSENT is two zeros; else the list's tag and element count.
uint64_t listHeader(HeaderCursor& c, uint64_t tag, const char* what) {
  const uint64_t t = c.u32();
  const uint64_t n = c.count();
  if (t == 0 && n == 0) return 0;
  if (t != tag) c.fail(std::string(what) + " list has tag " + std::to_string(t));
  return n;
}

void attributes(HeaderCursor& c) {
  const uint64_t n = listHeader(c, kAttributeTag, "attribute");
  const uint64_t nelems = c.version() == 5 ? 8 : 4;
  c.expectRoom(n, nelems + 4 + 4 + nelems, "attribute");
  for (uint64_t i = 0; i < n; ++i) {
    c.name("attribute");
    const uint64_t size = typeSize(c.u32(), c.version());
    if (size == 0) c.fail("attribute of an unknown type");
    const uint64_t values = c.count();
    if (values > c.remaining() / size) c.fail("attribute values run past the end of the file");
    c.skip((values * size + 3) / 4 * 4, "attribute values");
  }
}

}  // namespace

std::optional<std::string> classicHeaderProblem(std::string_view file) {
  if (file.size() < 4 || file.substr(0, 3) != "CDF") return "not a classic NetCDF file";
  const int version = file[3];
  if (version != 1 && version != 2 && version != 5) return "unknown classic format version";
  try {
    HeaderCursor c(file, version);
    c.skip(4, "magic");
    c.count();  // numrecs (or STREAMING); the record count is checked when data is read
    const uint64_t nelems = version == 5 ? 8 : 4;

    const uint64_t ndims = listHeader(c, kDimensionTag, "dimension");
    c.expectRoom(ndims, nelems + 4 + nelems, "dimension");
    int unlimited = 0;
    for (uint64_t i = 0; i < ndims; ++i) {
      c.name("dimension");
      if (c.count() == 0 && ++unlimited > 1) c.fail("more than one unlimited dimension");
    }

    attributes(c);  // global

    const uint64_t nvars = listHeader(c, kVariableTag, "variable");
    // name, rank, an ABSENT attribute list, type, vsize and begin at their smallest
    c.expectRoom(nvars, 4 * nelems + 12 + (version == 1 ? 4 : 8), "variable");
    for (uint64_t i = 0; i < nvars; ++i) {
      c.name("variable");
      const uint64_t rank = c.count();
      if (rank > 1024) c.fail("variable rank " + std::to_string(rank));
      c.expectRoom(rank, nelems, "variable dimension");
      for (uint64_t d = 0; d < rank; ++d)  // dimid: NON_NEG, 8 bytes in CDF-5
        if (c.count() >= ndims) c.fail("variable dimension id out of range");
      attributes(c);
      if (typeSize(c.u32(), version) == 0) c.fail("variable of an unknown type");
      c.count();   // vsize
      c.offset();  // begin
    }
  } catch (const HeaderProblem& p) {
    return p.what;
  }
  return std::nullopt;
}

}  // namespace sky::detail
