#pragma once
// configs/default.yaml, embedded at build time: the scene skyview opens without a file (the
// same text skyrender embeds, configured here so apps/skyrender stays untouched).
namespace sky::view {
const char* defaultSceneText();
}
