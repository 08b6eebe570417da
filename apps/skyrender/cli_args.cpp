#include "cli_args.h"

#include "engine/core/error.h"

namespace sky {

CliArgs::CliArgs(const std::string& command, const std::vector<std::string>& args,
                 const std::set<std::string>& valued, const std::set<std::string>& repeatable,
                 const std::set<std::string>& flags)
    : mCommand(command) {
  const std::string see = " (see skyrender " + command + " --help)";
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.size() < 2 || a.rfind("--", 0) != 0) {
      if (!a.empty() && a[0] == '-' && a != "-")
        inputError(command + ": unknown option '" + a + "'" + see);
      mPositional.push_back(a);
      continue;
    }
    std::string name = a, val;
    bool inlineValue = false;
    if (size_t eq = a.find('='); eq != std::string::npos) {
      name = a.substr(0, eq);
      val = a.substr(eq + 1);
      inlineValue = true;
    }
    if (flags.count(name)) {
      if (inlineValue) inputError(command + ": option " + name + " takes no value" + see);
      mFlags.insert(name);
    } else if (valued.count(name)) {
      if (!inlineValue) {
        if (i + 1 >= args.size()) inputError(command + ": option " + name + " needs a value" + see);
        val = args[++i];
      }
      auto& list = mValues[name];
      if (!list.empty() && !repeatable.count(name))
        inputError(command + ": option " + name + " given twice" + see);
      list.push_back(val);
    } else {
      inputError(command + ": unknown option '" + name + "'" + see);
    }
  }
}

void CliArgs::expectPositionals(size_t min, size_t max, const std::string& what) const {
  const std::string see = " (see skyrender " + mCommand + " --help)";
  if (mPositional.size() > max) {
    const std::string& extra = mPositional[max];
    if (max == 0) inputError(mCommand + " takes no arguments: '" + extra + "'" + see);
    inputError(mCommand + " takes " + what + ", got also '" + extra + "'" + see);
  }
  if (mPositional.size() < min) inputError(mCommand + " needs " + what + see);
}

std::optional<std::string> CliArgs::value(const std::string& option) const {
  auto it = mValues.find(option);
  if (it == mValues.end()) return std::nullopt;
  return it->second.front();
}

const std::vector<std::string>& CliArgs::values(const std::string& option) const {
  static const std::vector<std::string> kNone;
  auto it = mValues.find(option);
  return it == mValues.end() ? kNone : it->second;
}

}  // namespace sky
