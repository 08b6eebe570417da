#pragma once
// configs/default.yaml, embedded at build time.
const char* skyDefaultSceneText();
