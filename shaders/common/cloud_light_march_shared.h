// The light march's schedule constants, shared by cloud_light_march.glsl and its C++ twin
// (engine/clouds/cloud_math.h).
#ifndef SKY_CLOUD_LIGHT_MARCH_SHARED_H
#define SKY_CLOUD_LIGHT_MARCH_SHARED_H

// The long step (over [distance, CLOUD_LIGHT_RESOLVED_REACH distance], or to where the path
// leaves the cloud shells if that is sooner) is sampled in parts no longer than this (m),
// each read at one point. A part longer than the clouds it crosses sees a random draw of
// their optical depth: it lands in a cloud and is opaque, or in a gap and is clear, and the
// clouds it steps over are missed; a noisy optical depth brightens on average (the mean of
// exp(-tau) exceeds exp(-mean tau)). One sample at the step's middle (Schneider 2015's far
// sample) read a single point for 4.8 km of the sun's path; parts of 1.2 km left sunset
// clouds too bright, in grain; 400 m parts were enough for issue 16's clouds (37-43 dB
// against the reference's 300 m parts at 320x180). Issue 46's cumulus are many small clouds,
// a few hundred metres across, that 400 m parts step over: on the path-traced field with a 3
// degree sun behind the camera they gave the clouds' sunlight 1.43 times what a march in 50 m
// parts over the whole path gives (0.070 against 0.049; Cycles 0.042), all of it from the
// long step, and the view was 15.1 % brighter than Cycles' and 24.4 % off per pixel
// (docs/cloud-model.md, "The long step's parts"). 125 m parts over 1.2-3 km, and the far
// step's clumped mean past there: +8.3 % and 20.5 %, the stratocumulus deck at sunset from
// +17.1 % and 22.5 % to +9.8 % and 16.7 %, at about the cost of the 400 m parts over
// 1.2-6 km (100 m parts over all of it: +5.9 % and 19.0 %, the deck +12.1 % and 18.7 %, for
// 1.5x the frame at sunset). A high sun leaves the shells within a kilometre or two, so its
// long step has few parts or none.
#define CLOUD_LIGHT_LONG_PART_M 125.0
// Where the long step of the march as tuned ends, in units of clouds.light_distance_m: the
// clouds nearer than that cast the shadows a view sees, one by one; past it the far step's
// clumped mean (the chance that the path misses every cloud, not which ones it hits). From
// 6 km on the mean gives the light of marching the clouds (a shader copy reading them in 50 m
// parts there: the field's sunlight 0.071 against 0.070); taken from nearer it leaves the
// 3 degree field brighter than marching on (100 m parts: +5.9 % to 6 km, +8.1 % to 3 km,
// +10.6 % to 2.4 km), but costs a third as many reads as 100 m parts to 6 km. 3 km keeps
// the frame at sunset at about the cost it had.
#define CLOUD_LIGHT_RESOLVED_REACH 2.5
// The reference march's parts (clouds.quality reference): its long step runs on to
// 5 light_distance_m (lightMarchReach) in parts of this length. On that field its clouds'
// sunlight is 0.047 (0.060 with the 300 m parts it had), converged: a march in 50 m parts
// over the whole path gives 0.049.
#define CLOUD_LIGHT_REFERENCE_LONG_PART_M 50.0
// The most parts a long step takes (the reference's 4.8 km in 50 m parts).
#define CLOUD_LIGHT_MAX_LONG_PARTS 96

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
