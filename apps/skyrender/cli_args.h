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
  // `command`: the sub-command, named in messages; `valued`: options that take a value
  // (--out DIR or --out=DIR); `repeatable` among them may appear several times; `flags`:
  // options without a value.
  CliArgs(const std::string& command, const std::vector<std::string>& args,
          const std::set<std::string>& valued, const std::set<std::string>& repeatable,
          const std::set<std::string>& flags);

  // Between `min` and `max` positional arguments, else BadInput: "<command> takes no
  // arguments: 'x'", "<command> needs <what>", "<command> takes <what>, got also 'y'", each
  // pointing at skyrender <command> --help.
  void expectPositionals(size_t min, size_t max, const std::string& what) const;

  const std::string& command() const { return mCommand; }
  const std::vector<std::string>& positional() const { return mPositional; }
  std::optional<std::string> value(const std::string& option) const;
  const std::vector<std::string>& values(const std::string& option) const;
  bool flag(const std::string& option) const { return mFlags.count(option) > 0; }

private:
  std::string mCommand;
  std::vector<std::string> mPositional;
  std::map<std::string, std::vector<std::string>> mValues;
  std::set<std::string> mFlags;
};

}  // namespace sky
