#pragma once
// What a frame is built from, worked out once by the Renderer before any layer adds a pass,
// and read, never changed, by the layers (engine/render/sky_layer.h, volumetric_cloud_layer.h):
//   - FrameSetup: the weather map, the scene's clouds placed in it, where their rays start and
//     the lights after the local weather. The sky is lit by these too, so they are the
//     frame's, not the clouds' layer's.
//   - CloudFieldFrame: the cloud field as the cloud passes see it in one graph: its textures
//     and tables imported, the raymarch's uniforms at a view and its variant. A frame, a
//     volume export and the CPU field (the queries) each take theirs from cloudFieldFrame(),
//     so they march through the same field.
#include <cstdint>

#include "engine/lighting/lighting_state.h"
#include "engine/render/cloud_layers.h"
#include "engine/scene/scene.h"
#include "engine/weather/local_weather.h"
#include "passes/cloud_field/cloud_field.h"
#include "shaders/common/view_shared.h"
#include "shaders/common/volumetric_clouds_shared.h"

namespace sky {

struct FrameSetup {
  Scene cloudScene;  // the scene with the weather map's region and layer altitudes filled in
  VolumetricCloudsSettings volumetric;  // the cloud passes' settings, from cloudScene
  CloudFrameGeometry geometry;          // where the clouds' rays start (cloudFrameGeometry)
  LightingState lighting;               // the frame's lights after the local weather
  LocalWeather localWeather;            // the weather where the camera stands
  const WeatherMap* weather;  // owned by the CloudLayers, valid until its next weatherMap()
};

// The setup of a frame of `scene` at `time`: the weather map (built or kept by `weather`), the
// scene's clouds placed in it, the lights after the local weather. BadInput for bad weather
// settings or files.
FrameSetup frameSetup(CloudLayers& weather, const Scene& scene, const IsoTime& time);

struct CloudFieldFrame {
  CloudLayers::Frame frame;    // the textures, coverage tables and noise means
  shared::CloudParams params;  // cloudParams() at the view
  CloudVariant variant;        // cloudVariant()
  CloudFieldKey key;           // what the light volume and the shadow map are made from
  double texturesMs = 0.0;     // importing (keeping, loading or baking) the textures
};

// The cloud field of `setup` at `time` for passes drawn at `view`, its textures imported into
// `graph`, or `made`'s when another view of the frame imported them. `settingsRevision`: the
// revision of the setup's cloud scene (SettingsRevisions::of) the key carries. Call only when
// the setup's weather map has low or mid cover.
CloudFieldFrame cloudFieldFrame(FrameGraph& graph, CloudLayers& weather, const FrameSetup& setup,
                                const IsoTime& time, const shared::ViewState& view,
                                uint64_t settingsRevision = 0,
                                const CloudLayers::Frame* made = nullptr);

}  // namespace sky
