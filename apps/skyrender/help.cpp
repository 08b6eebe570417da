#include "help.h"

#include "engine/core/paths.h"

namespace sky {
namespace {

constexpr const char* kFooter = R"(
exit codes: 0 success, 2 bad input (scene, arguments, files), 1 internal or device error,
130 / 143 interrupted (SIGINT / SIGTERM). Every error is one line on stderr saying what
and where. skyrender --help lists the commands and the environment variables.
)";

constexpr const char* kRender = R"(usage: skyrender render [SCENE] [options]

Renders SCENE (YAML or JSON; without it the embedded default scene, configs/default.yaml)
into DIR/NAME.exr, NAME.png and NAME.json. A scene whose time is a range START/END/STEP
writes numbered frames NAME_0001.exr/.png/.json, ... An empty scene file is an error:
give no SCENE for the default scene, or write {} for the format's defaults.

options:
  --out DIR            output folder, created if missing (default: out); a folder the
                       run created is removed again when nothing was written into it
  --name NAME          file stem, same as --set output.name=NAME
  --width W            same as --set output.width=W
  --height H           same as --set output.height=H
  --time TIME          same as --set time=TIME: an instant (ISO 8601 with a zone, Z or
                       +HH:MM) or a time-lapse START/END/STEP, e.g.
                       2024-06-21T00:00Z/2024-06-22T00:00Z/15m
  --set KEY.PATH=VALUE override any scene key; VALUE is read as a YAML scalar or flow
                       sequence (e.g. --set camera.heading=250); repeatable;
                       validated exactly like the file
  --dump-graph FILE    also write the compiled frame graph as Graphviz (dot -Tsvg FILE)
  --debug-output NAME  also write NAME.<name>.exr: any image of the frame's graph by its
                       name; repeatable or comma-separated. `--debug-output list` prints
                       the scene's images (which pass writes each, how it is shown, its
                       size, what it holds) and renders nothing
  --debug-passes       every image of the frame: NAME.passes.png, a labelled contact
                       sheet (one tile per image with its pass and GPU ms), the images of
                       the frame's size as EXR layers debug.<name>, the others as
                       NAME.<name>.exr
  --shard I/N          a time-lapse's frames in N contiguous shares: write share I
                       (1 <= I <= N) and its manifest DIR/manifest.I-of-N.jsonl for
                       `skyrender merge DIR`; with clouds.temporal.mode on the shard first
                       draws 2 x block^2 frames before its own, unwritten (docs/datasets.md)
  --gpu NAME|INDEX     Vulkan device by index or name substring (default: a GPU if
                       present, else lavapipe)
  --ocio FILE          OpenColorIO config (default: $OCIO, else configs/ocio/config.ocio)

outputs:
  NAME.exr   scene-linear Rec.709, multi-layer: R,G,B,A (beauty), sky.R/G/B (clear
             sky) and high_clouds.R/G/B/A (premultiplied, A = coverage) in half float;
             clouds.R/G/B/A/depth (volumetric clouds, premultiplied, A = opacity, depth
             in m) in 32-bit float; camera.mode geographic_topdown adds
             weather.cover_low/_mid (half); output.perception adds the perception
             layers clouds.optical_depth/.distance, label and cloud_type (UINT),
             air.transmittance and ground.cloud_shadow (docs/outputs.md)
  NAME.png   8-bit display image through output.display / output.view, exposure applied
  NAME.json  settings (paths resolved), time, sun, moon and light (as `ephemeris` prints
             them), per-pass GPU milliseconds, total, device name, cache use

A time-lapse stopped by SIGINT (Ctrl-C) or SIGTERM finishes the frame it is writing,
keeps every finished frame, prints "interrupted after N of M frames" and exits 130 / 143.
)";

constexpr const char* kValidate =
    R"(usage: skyrender validate SCENE [--set KEY.PATH=VALUE]... [--ocio FILE]

Checks SCENE as `render` would (the display and view against the OCIO config included)
and prints its effective settings, every default filled in, in the scene's own format
(YAML or JSON). Relative paths are printed resolved, so the printed scene renders the
same from any folder.

options:
  --set KEY.PATH=VALUE override a scene key, as for render; repeatable
  --ocio FILE          OpenColorIO config (default: $OCIO, else configs/ocio/config.ocio)
)";

constexpr const char* kEphemeris =
    R"(usage: skyrender ephemeris --lat D --lon D --time ISO8601 [options]

Prints the sun's and the moon's positions (NREL SPA, Meeus), the moon's phase and the key
light of the lighting model at a place and instant, as JSON.

options:
  --lat D              latitude, degrees north (-90..90), required
  --lon D              longitude, degrees east (-180..180), required
  --time ISO8601       the instant with a zone (2024-06-21T12:00Z), required
  --height-m M         observer height above sea level (default 0)
  --pressure-hpa P     air pressure for refraction (default 1010; 0 turns it off)
  --temperature-c T    air temperature for refraction (default 10)
)";

constexpr const char* kSchema = R"(usage: skyrender schema [--dataset]

Prints the JSON Schema (draft 2020-12) of scene files; configs/schema/scene.schema.json is
a copy. With --dataset, the schema of dataset specs (skyrender dataset);
configs/schema/dataset.schema.json is a copy.
)";

constexpr const char* kDevices = R"(usage: skyrender devices [--gpu NAME|INDEX]

Lists the Vulkan devices and marks the one render would pick. Takes no other arguments.

options:
  --gpu NAME|INDEX     show which device this choice picks
)";

constexpr const char* kDsc = R"(usage: skyrender dsc RENDER.exr [--cell PX] [--threshold T]

Compares a camera.mode geographic_topdown render's cloud opacity with its weather map's
cover over PX x PX blocks: Dice of the blocks above T (Lu (28)), mean absolute error,
correlation and the block count. A correlation needs at least 2 blocks across each axis
of the image.

options:
  --cell PX            block size in pixels, a whole number (default 8)
  --threshold T        a block is cloudy above this mean (0..1, default 0.1)
)";

constexpr const char* kWeather =
    R"(usage: skyrender weather FILE [--scene SCENE] [--out DIR] [--set KEY.PATH=VALUE]...

The cloud map a GRIB2 or NetCDF forecast gives (Lu (1)(2) per layer, or the model's own
cover): DIR/STEM.weather.exr (cover_low, cover_mid, cover_high, type and each layer's
base and top altitude per texel, 32-bit float) and STEM.weather.png (low red, mid green,
high blue). Prints each layer's covered fraction, mean cover, altitudes and Dice against
the file's own cloud cover (tcc) when it has one. The map covers weather.region when the
scene or --set gives one, else the file's whole grid.

options:
  --scene SCENE        take the weather settings (levels, time, evolution, region) from
                       SCENE (default: the embedded default scene)
  --out DIR            output folder, created if missing (default: out)
  --set KEY.PATH=VALUE override a scene key, e.g. --set 'weather.region.lat=[0,55]'
                       --set 'weather.region.lon=[39,105]'; repeatable
)";

constexpr const char* kExportVolume =
    R"(usage: skyrender export-volume [SCENE] --out FILE.vdb [options]

Writes the low and mid cloud density of SCENE (default: the embedded default scene) inside
a box around the camera as an OpenVDB fog volume, for a path tracer (scripts/pathtrace): the
float grid "density" holds the extinction per metre (the raymarch's density times
clouds.extinction) at each voxel centre, in the camera's east-north-up frame (metres, the
camera at the origin). The grid's metadata hold the camera (place, heading, pitch, field
of view, image size and view axes), the sun's and the moon's direction and illuminance at
the clouds, the sky's ambient radiance from above and below, and the phase function
(docs/outputs.md). Needs low or mid cover and camera.mode observer.

options:
  --out FILE.vdb       the file to write (its folder must exist); written whole or not at all
  --box E0,N0,U0,E1,N1,U1
                       the box in metres east, north and up of the camera, minimum corner
                       then maximum (default: a 6 km square centred 4 km ahead along the
                       heading, from the lowest layer's base to the highest layer's top).
                       Repeatable: several boxes are one field in nested parts, finest
                       first, each inside the next, each its own grid ("density",
                       "density_1", ...) holding its share of the field; each hands the field
                       to the next over a band of two of the next one's voxels inside each
                       face the next reaches well past, so a path tracer that adds the grids
                       sees the field once (docs/outputs.md)
  --voxel-m M          voxel edge in metres (default: 50); the grid has ceil(size / M)
                       voxels along each axis, at most 2^26 a box and 2^28 in all. Give it
                       once for every box or once for each --box, in order
  --lod full|view      full (default): every noise octave at every voxel; view: the field as
                       the raymarch resolves it, each voxel seen as a sample one pixel of the
                       scene's camera (output.width, height) wide at its distance, and no
                       finer than the voxel
  --width W, --height H
                       the image size recorded for the camera (same as --set output.width)
  --time TIME          one instant, same as --set time=TIME
  --set KEY.PATH=VALUE override any scene key; repeatable
  --gpu NAME|INDEX     Vulkan device by index or name substring
)";

constexpr const char* kDataset =
    R"(usage: skyrender dataset SPEC --out DIR [--shard I/N] [options]

Renders the samples of the dataset spec SPEC (YAML or JSON, docs/datasets.md; its schema:
skyrender schema --dataset): sample k's scene is the spec's base scene with each range and
choice drawn from (seed, k) alone, so any process renders it bit for bit the same. Each
sample writes DIR/sample_NNNNNN.exr (with the perception layers, docs/outputs.md), .png
and .yaml (its scene: skyrender render renders it again), then one JSON line to the
manifest, DIR/manifest.jsonl (a shard's: manifest.I-of-N.jsonl): index, scene parameters,
sun elevation, cover per layer, the share of each label, file names and SHA-256 checksums.

A killed run, run again with the same arguments, goes on: a sample is complete once its
manifest line exists (its files are in place before), so the finished ones are skipped
and nothing is duplicated. A terminal shows a progress bar; a summary line ends the run.

options:
  --out DIR            the dataset's folder, created if missing (default: out); a folder
                       holding another spec's samples is refused
  --shard I/N          render only shard I of N (1 <= I <= N): the samples k with
                       k % N == I - 1; `skyrender merge DIR` joins the shards' manifests
  --gpu NAME|INDEX     Vulkan device by index or name substring
  --ocio FILE          OpenColorIO config (default: $OCIO, else configs/ocio/config.ocio)

A run stopped by SIGINT or SIGTERM finishes the sample it is writing and exits 130 / 143.
)";

constexpr const char* kMerge = R"(usage: skyrender merge DIR [DIR...]

Joins the shard manifests (manifest.I-of-N.jsonl) in the folders into DIR/manifest.jsonl
(the first folder's; one line per sample, by index; files of the other folders named
relative to it) and writes DIR/dataset.json (count, samples, missing, present twice, the
mean share of each label). Reports on stderr any sample missing or present twice and then
exits 3: run the shard again (it skips what it finished) and merge again.
)";

}  // namespace

const std::vector<CommandHelp>& commandHelp() {
  static const std::vector<CommandHelp> commands = {
      {"render", "render a scene (or the default scene) to EXR, PNG and a JSON report",
       std::string(kRender) + kFooter},
      {"validate", "check a scene and print its effective settings",
       std::string(kValidate) + kFooter},
      {"ephemeris", "sun and moon positions, moon phase and key light as JSON",
       std::string(kEphemeris) + kFooter},
      {"schema", "the JSON Schema of scene files", std::string(kSchema) + kFooter},
      {"devices", "the Vulkan devices and which one is picked", std::string(kDevices) + kFooter},
      {"dsc", "compare a top-down render's cloud opacity with its weather map",
       std::string(kDsc) + kFooter},
      {"weather", "the cloud map a GRIB2/NetCDF forecast gives, with per-layer figures",
       std::string(kWeather) + kFooter},
      {"export-volume", "the cloud density in a box as an OpenVDB grid, for a path tracer",
       std::string(kExportVolume) + kFooter},
      {"dataset", "render a dataset spec's samples, reproducible, resumable and shardable",
       std::string(kDataset) + kFooter},
      {"merge", "join a sharded dataset's manifests and report what is missing",
       std::string(kMerge) + kFooter},
  };
  return commands;
}

const CommandHelp* findCommandHelp(const std::string& name) {
  for (const CommandHelp& c : commandHelp())
    if (name == c.name) return &c;
  return nullptr;
}

std::string commandList() {
  std::string out;
  for (const CommandHelp& c : commandHelp()) out += (out.empty() ? "" : ", ") + std::string(c.name);
  return out;
}

std::string versionText() {
  return std::string("skyrender ") + skylayersVersion() + "\n";
}

std::string overviewText() {
  std::string out = R"(skyrender - render skies and clouds with skylayers

usage: skyrender COMMAND [arguments] [options]
       skyrender COMMAND --help    the command's arguments, options and outputs
       skyrender --version

commands:
)";
  for (const CommandHelp& c : commandHelp()) {
    std::string name = std::string("  ") + c.name;
    name.resize(17, ' ');
    out += name + c.summary + "\n";
  }
  out += R"(
environment:
  SKY_VALIDATION=1   enable the Vulkan validation layers (messages go to stderr)
  SKY_DATA_DIR       folder holding shaders/ and configs/ (default: the source tree)
  SKY_CACHE_DIR      cache folder for SPIR-V, baked high-cloud textures and cloud noise
                     (default: ~/.cache/skylayers); a render still works when it cannot
                     be written, says so once on stderr and in the report
  OCIO               OpenColorIO config used when --ocio is absent
)";
  out += kFooter;
  return out;
}

}  // namespace sky
