#pragma once
// configs/default.yaml, embedded at build time: the scene `skyrender render` renders and
// skyview opens without a file, from anywhere.
const char* skyDefaultSceneText();
