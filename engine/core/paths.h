#pragma once
// Where run-time data lives. shaders/ and configs/ are read from the data root:
// $SKY_DATA_DIR if set, else the source tree the binary was built from.
#include <filesystem>

namespace sky {

std::filesystem::path dataRoot();
std::filesystem::path shaderDir();  // $SKY_SHADER_DIR or dataRoot()/shaders
std::filesystem::path configDir();  // dataRoot()/configs
// Caches (SPIR-V, later baked textures): $SKY_CACHE_DIR, else $XDG_CACHE_HOME/skylayers,
// else ~/.cache/skylayers. Created on first use.
std::filesystem::path cacheDir();

}  // namespace sky
