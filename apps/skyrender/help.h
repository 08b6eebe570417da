#pragma once
// skyrender's help: the overview (skyrender --help) and each command's own page
// (skyrender COMMAND --help), one table so the two never disagree on what exists.
#include <string>
#include <vector>

namespace sky {

struct CommandHelp {
  const char* name;     // "render"
  const char* summary;  // one line for the overview
  std::string page;     // the command's whole --help text (usage, arguments, options)
};

const std::vector<CommandHelp>& commandHelp();
// The page of `name`, or nullptr for an unknown command.
const CommandHelp* findCommandHelp(const std::string& name);
// skyrender --help: usage, the commands with their summaries, the environment, exit codes.
std::string overviewText();
// "skyrender 0.1.0".
std::string versionText();
// The names of the commands, "render, validate, ...", for error messages.
std::string commandList();

}  // namespace sky
