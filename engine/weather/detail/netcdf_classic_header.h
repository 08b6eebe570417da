#pragma once
// A structural check of a classic NetCDF header (CDF-1, CDF-2 64-bit offset, CDF-5) before
// libnetcdf parses it: libnetcdf 4.9 trusts the header's counts and crashes on some corrupt
// ones (a variable count of 2^30 in a 1 kB file ends in a segfault inside nc_open).
#include <optional>
#include <string>
#include <string_view>

namespace sky::detail {

// nullopt when every count, name, type and length in the header fits the `file` bytes (the
// whole file, magic included); otherwise what is wrong and at which byte offset.
std::optional<std::string> classicHeaderProblem(std::string_view file);

}  // namespace sky::detail
