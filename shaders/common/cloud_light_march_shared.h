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
// average): 32-35 dB against the reference's 300 m parts at 320x180. 600 m gave 35-39 dB,
// 400 m 37-43 dB for 1.08-1.12x the frame at sunset. A high sun leaves the shells within a
// kilometre or two, so its long step has few parts or none.
#define CLOUD_LIGHT_LONG_PART_M 400.0
// The reference march's parts (clouds.quality reference): half as long.
#define CLOUD_LIGHT_REFERENCE_LONG_PART_M 300.0
// The most parts a long step takes (a 4.8 km step in 300 m parts).
#define CLOUD_LIGHT_MAX_LONG_PARTS 16

// The far step (past the long step, to where the path leaves the cloud shells) reaches at
// most this far from the point (m): a path at 1 degree rises through a 1.5 km layer in
// 86 km, and at 60 km from a cloud the light has crossed so much of a broken field that
// what lies beyond changes little. Its parts read only the weather map (the clouds' mean),
// at most CLOUD_LIGHT_MAX_FAR_PARTS of them, each at most CLOUD_LIGHT_FAR_PART_M long: the
// mean's cover and height profile change over kilometres.
#define CLOUD_LIGHT_FAR_REACH_M 60000.0
#define CLOUD_LIGHT_FAR_PART_M 3000.0
#define CLOUD_LIGHT_MAX_FAR_PARTS 12

// Where a light's path leaves the sample's own cloud: the first density sample at or below
// this (a twentieth of a core's density, under 0.2 optical depths in 100 m; in the
// level-of-detail's transition the far field's smooth floor lies below it). Past there the
// light crosses other clouds as a beam. Measured against Cycles on the five path-traced fields
// (docs/cloud-model.md, "A path-traced field"): the stratocumulus deck at sunset was 25.9 %
// off per pixel at 0 (every sample in the transition counted as cloud, so no path left it),
// 24.2 % at 0.05, 19.9 % at 0.1; but at 0.1 the deck seen from below fell to 2.04 against
// Cycles' 2.41 (CloudLookTest.ADecksBaseOverheadIsAsBrightAsThePathTracersBase).
#define CLOUD_LIGHT_CLEAR_DENSITY 0.05

#endif
