// The light march's schedule constants, shared by cloud_light_march.glsl and its C++ twin
// (engine/clouds/cloud_math.h).
#ifndef SKY_CLOUD_LIGHT_MARCH_SHARED_H
#define SKY_CLOUD_LIGHT_MARCH_SHARED_H

// The long step (over [distance, 5 distance]) is sampled at this many equal parts. One sample
// at its middle (Schneider 2015's far sample) reads a single point of the clouds for 4.8 km
// of the sun's path: under a low sun it either filled the path with the clouds' mean (every
// cumulus grey) or, resolving the outlines, lit a stratocumulus deck through whatever gap it
// hit. Three parts bring both within 1-4 dB of the reference march (docs/clouds.md).
#define CLOUD_LIGHT_LONG_SAMPLES 3

#endif
