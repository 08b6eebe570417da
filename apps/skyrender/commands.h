#pragma once
// The skyrender sub-commands. Each returns the process exit code or throws sky::Error.
#include <string>
#include <vector>

namespace sky {

int renderCommand(const std::vector<std::string>& args);
int validateCommand(const std::vector<std::string>& args);
int ephemerisCommand(const std::vector<std::string>& args);
int schemaCommand(const std::vector<std::string>& args);
int devicesCommand(const std::vector<std::string>& args);
int dscCommand(const std::vector<std::string>& args);
int weatherCommand(const std::vector<std::string>& args);
int exportVolumeCommand(const std::vector<std::string>& args);
int datasetCommand(const std::vector<std::string>& args);
int mergeCommand(const std::vector<std::string>& args);

}  // namespace sky
