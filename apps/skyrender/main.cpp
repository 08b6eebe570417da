// skyrender: the command line. Thin by design: parse, call the engine, report.
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "commands.h"
#include "engine/core/error.h"

namespace {

// Errors are one line, whatever a library put in its message.
std::string oneLine(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
      std::cout << sky::usageText();
      return args.empty() ? 2 : 0;
    }
    const std::string command = args[0];
    args.erase(args.begin());
    for (const std::string& a : args)
      if (a == "--help" || a == "-h") {
        std::cout << sky::usageText();
        return 0;
      }
    if (command == "render") return sky::renderCommand(args);
    if (command == "validate") return sky::validateCommand(args);
    if (command == "ephemeris") return sky::ephemerisCommand(args);
    if (command == "schema") return sky::schemaCommand(args);
    if (command == "devices") return sky::devicesCommand(args);
    if (command == "dsc") return sky::dscCommand(args);
    if (command == "weather") return sky::weatherCommand(args);
    sky::inputError(
        "unknown command '" + command +
        "' (commands: render, validate, ephemeris, schema, devices, dsc, weather; see --help)");
  } catch (const sky::Error& e) {
    std::cerr << "error: " << oneLine(e.what()) << "\n";
    return e.exitCode();
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << oneLine(e.what()) << "\n";
    return 1;
  }
}
