#pragma once
// The display's night look (output.night_look): as a scene dims the eye's rods take over from
// its cones, so dim parts of an image lose their colour and shift toward blue (the Purkinje
// effect). Applied to the physical scene-linear image before the exposure, because it depends
// on the absolute luminance the exposure then hides; an OCIO look (a fixed transform of the
// exposed image) cannot know it. Never applied to the EXR.
#include <vector>

namespace sky {

// The share of the cone (photopic) response at luminance `cdPerM2`: 1 at and above 3 cd/m^2,
// 0 at and below 0.01 cd/m^2 (fully scotopic), smooth in log luminance in between (the
// mesopic range, CIE 191:2010's limits).
double photopicShare(double cdPerM2);

// In place, on interleaved RGBA in the renderer's units (1 = 10^4 cd/m^2, linear Rec.709):
// each pixel blends from its colour toward the rods' response, its scotopic luminance
// (Larson, Rushmeier & Piatko 1997: V = Y (1.33 (1 + (Y + Z) / X) - 1.68), scaled so white
// keeps its luminance) in a blue grey
// of chromaticity (0.28, 0.29), by 1 - photopicShare. Alpha is left alone.
void applyNightLook(std::vector<float>& rgba);

}  // namespace sky
