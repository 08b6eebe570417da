// skyrender: the command line. Thin by design: parse, call the engine, report.
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "commands.h"
#include "engine/core/error.h"
#include "help.h"

namespace {

// Errors are one line, whatever a library put in its message.
std::string oneLine(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

bool isHelp(const std::string& a) {
  return a == "--help" || a == "-h";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.empty()) {
      std::cerr << sky::overviewText();
      return 2;
    }
    if (isHelp(args[0])) {
      std::cout << sky::overviewText();
      return 0;
    }
    if (args[0] == "--version") {
      if (args.size() > 1) sky::inputError("--version takes no arguments: '" + args[1] + "'");
      std::cout << sky::versionText();
      return 0;
    }
    if (args[0] == "help") {
      if (args.size() == 1) {
        std::cout << sky::overviewText();
        return 0;
      }
      const sky::CommandHelp* help = sky::findCommandHelp(args[1]);
      if (!help)
        sky::inputError("help: unknown command '" + args[1] + "' (commands: " + sky::commandList() +
                        ")");
      std::cout << help->page;
      return 0;
    }
    const std::string command = args[0];
    args.erase(args.begin());
    const sky::CommandHelp* help = sky::findCommandHelp(command);
    if (!help)
      sky::inputError("unknown command '" + command + "' (commands: " + sky::commandList() +
                      "; see skyrender --help)");
    for (const std::string& a : args)
      if (isHelp(a)) {
        std::cout << help->page;
        return 0;
      }
    if (command == "render") return sky::renderCommand(args);
    if (command == "validate") return sky::validateCommand(args);
    if (command == "ephemeris") return sky::ephemerisCommand(args);
    if (command == "schema") return sky::schemaCommand(args);
    if (command == "devices") return sky::devicesCommand(args);
    if (command == "dsc") return sky::dscCommand(args);
    if (command == "weather") return sky::weatherCommand(args);
    if (command == "export-volume") return sky::exportVolumeCommand(args);
    if (command == "dataset") return sky::datasetCommand(args);
    if (command == "merge") return sky::mergeCommand(args);
    sky::internalError("command '" + command + "' has help but no implementation");
  } catch (const sky::Error& e) {
    std::cerr << "error: " << oneLine(e.what()) << "\n";
    return e.exitCode();
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << oneLine(e.what()) << "\n";
    return 1;
  }
}
