#pragma once
// A small, strict command-line parser: every unknown or malformed argument is a BadInput
// error naming it, so `skyrender` exits 2 with one line instead of guessing.
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace sky {

class CliArgs {
public:
  // `valued`: options that take a value (--out DIR or --out=DIR); `repeatable` among them may
  // appear several times; `flags`: options without a value.
  CliArgs(const std::vector<std::string>& args, const std::set<std::string>& valued,
          const std::set<std::string>& repeatable, const std::set<std::string>& flags);

  const std::vector<std::string>& positional() const { return mPositional; }
  std::optional<std::string> value(const std::string& option) const;
  const std::vector<std::string>& values(const std::string& option) const;
  bool flag(const std::string& option) const { return mFlags.count(option) > 0; }

private:
  std::vector<std::string> mPositional;
  std::map<std::string, std::vector<std::string>> mValues;
  std::set<std::string> mFlags;
};

}  // namespace sky
