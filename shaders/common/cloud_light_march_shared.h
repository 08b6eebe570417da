// The light march's schedule constants, shared by cloud_light_march.glsl and its C++ twin
// (engine/clouds/cloud_math.h).
#ifndef SKY_CLOUD_LIGHT_MARCH_SHARED_H
#define SKY_CLOUD_LIGHT_MARCH_SHARED_H

// The long step (over [distance, 5 distance], or to where the path leaves the cloud shells
// if that is sooner) is sampled in parts no longer than this (m). One sample at its middle
// (Schneider 2015's far sample) read a single point of the clouds for 4.8 km of the sun's
// path: under a low sun it either filled the path with the clouds' mean (every cumulus grey)
// or, resolving the outlines, lit a stratocumulus deck through whatever gap it hit. Parts of
// 1.2 km still left sunset clouds too bright, in grain (a noisy optical depth brightens on
// average); 600 m brings the default sunset within 1 dB of the reference's 300 m. A high sun
// leaves the shells within a kilometre or two, so its long step has few parts or none.
#define CLOUD_LIGHT_LONG_PART_M 600.0
// The reference march's parts (clouds.quality reference): half as long.
#define CLOUD_LIGHT_REFERENCE_LONG_PART_M 300.0
// The most parts a long step takes (a 4.8 km step in 300 m parts).
#define CLOUD_LIGHT_MAX_LONG_PARTS 16

#endif
