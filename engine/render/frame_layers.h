#pragma once
// A frame's read-back images as layers of the EXR skyrender writes: the beauty, the AOVs
// (sky, high_clouds, clouds with depth, a top-down view's weather cover) and any debug
// image, with its channels named as the pass that made it says (ImageDesc::channels).
// Plain CPU work on what the frame graph read back; the renderer calls it once per frame.
#include <string>
#include <vector>

#include "engine/graph/frame_graph.h"
#include "engine/io/exr.h"
#include "engine/weather/weather_map.h"

namespace sky {

// The first `channels.size()` channels of `image` as one layer. A 3D image has its depth
// slices side by side (width * depth across).
ImageLayer imageLayer(const ReadbackImage& image, std::string name,
                      std::vector<std::string> channels, bool fullFloat = false);
// The channel names of an image: `desc.channels` split at commas (the first channels only,
// when it names fewer than the format has), or R, G, B, A as many as the format has.
std::vector<std::string> channelNames(const ImageDesc& desc);

// What a layer of a frame is called in reports and the library: its name, "beauty" for the
// main layer's R, G, B, A and "label" for its UINT label and cloud_type.
std::string frameLayerName(const ImageLayer& layer);

// Layer "" (R, G, B, A). FLOAT: physical values span from a moonless night (1e-8) to the
// sun's disc (1e5), past both ends of half's range.
ImageLayer beautyLayer(const ReadbackImage& beauty);
// Appends "sky", "high_clouds" and "clouds" (premultiplied RGB, A, depth; all zero when the
// frame has no volumetric clouds, `clouds` and `depth` null) to `image`.
void appendAovLayers(LayeredImage& image, const ReadbackImage& sky, const ReadbackImage& highClouds,
                     const ReadbackImage* clouds, const ReadbackImage* depth);
// The perception layers (docs/outputs.md) from the composite's perception image (label,
// cloud type, air transmittance, cloud shadow) and the clouds' hits (optical depth, hit
// distance; null without volumetric clouds: 0 and +inf): channels "optical_depth" and
// "distance" appended to the "clouds" layer appendAovLayers made, a layer "" of UINT
// "label" and "cloud_type", "air" (transmittance) and "ground" (cloud_shadow).
void appendPerceptionLayers(LayeredImage& image, const ReadbackImage& perception,
                            const ReadbackImage* cloudHit);
// The "weather" layer of a top-down render: the map's low and mid cover at each pixel's
// centre (row 0 the north edge, column 0 the west edge), for `skyrender dsc`.
ImageLayer weatherCoverLayer(const WeatherMap& map, const WeatherRegion& region, uint32_t width,
                             uint32_t height);

}  // namespace sky
