#include "cli_args.h"

#include "engine/core/error.h"

namespace sky {

CliArgs::CliArgs(const std::vector<std::string>& args, const std::set<std::string>& valued,
                 const std::set<std::string>& repeatable, const std::set<std::string>& flags) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.size() < 2 || a.rfind("--", 0) != 0) {
      if (!a.empty() && a[0] == '-' && a != "-")
        inputError("unknown option '" + a + "' (see --help)");
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
      if (inlineValue) inputError("option " + name + " takes no value");
      mFlags.insert(name);
    } else if (valued.count(name)) {
      if (!inlineValue) {
        if (i + 1 >= args.size()) inputError("option " + name + " needs a value");
        val = args[++i];
      }
      auto& list = mValues[name];
      if (!list.empty() && !repeatable.count(name)) inputError("option " + name + " given twice");
      list.push_back(val);
    } else {
      inputError("unknown option '" + name + "' (see --help)");
    }
  }
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
