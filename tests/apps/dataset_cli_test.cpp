// skyrender dataset and merge as a user runs them: shards whose union is the whole run file
// for file, a run killed and run again that loses and repeats nothing, the errors, and the
// perception layers of skyrender render's EXR.
#include <set>

#include <nlohmann/json.hpp>

#include "cli_fixture.h"
#include "engine/core/sha256.h"
#include "engine/io/exr.h"

namespace sky {
namespace {

// Four tiny samples of cumulus at noon, the view and the weather drawn.
constexpr const char* kSpec = R"(scene: SCENE
count: 4
seed: 11
output: {width: 24, height: 14}
camera:
  heading: [150, 250]
  pitch: [0, 20]
weather:
  cover_low: [0.3, 0.8]
  seed: [1, 50]
)";

class DatasetCli : public SkyrenderCli {
protected:
  fs::path spec() {
    std::string text = kSpec;
    const fs::path scene = fs::path(std::getenv("SKY_DATA_DIR")) / "configs" / "tests" /
                           "clouds" / "cumulus_noon.yaml";
    text.replace(text.find("SCENE"), 5, scene.string());
    return write("spec.yaml", text);
  }
  // The manifest's lines by index.
  static std::map<int64_t, nlohmann::json> lines(const fs::path& manifest) {
    std::map<int64_t, nlohmann::json> out;
    std::ifstream in(manifest);
    for (std::string l; std::getline(in, l);) {
      const nlohmann::json j = nlohmann::json::parse(l);
      EXPECT_FALSE(out.count(j["index"].get<int64_t>())) << "index twice: " << l;
      out[j["index"].get<int64_t>()] = j;
    }
    return out;
  }
  // Every sample file of a folder by name, with its checksum.
  static std::map<std::string, std::string> files(const fs::path& dir) {
    std::map<std::string, std::string> out;
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      EXPECT_EQ(name.find(".tmp-"), std::string::npos) << "a temporary left: " << name;
      if (name.rfind("sample_", 0) == 0) out[name] = sha256File(e.path());
    }
    return out;
  }
};

TEST_F(DatasetCli, ShardsMakeTheWholeRunFileForFile) {
  const fs::path whole = mDir / "whole", sharded = mDir / "sharded";
  CliRun r = run("dataset " + spec().string() + " --out " + whole.string());
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("4 samples, 4 rendered, 0 already there"));
  for (const char* shard : {"1/3", "2/3", "3/3"}) {
    r = run("dataset " + spec().string() + " --out " + sharded.string() + " --shard " + shard);
    ASSERT_EQ(r.rc, 0) << r.err;
  }
  r = run("merge " + sharded.string());
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("4 of 4 samples"));
  // The same files, checksum for checksum, and the same lines.
  const auto a = files(whole), b = files(sharded);
  EXPECT_EQ(a.size(), 12u) << "EXR, PNG and scene of each sample";
  EXPECT_EQ(a, b);
  const auto la = lines(whole / "manifest.jsonl"), lb = lines(sharded / "manifest.jsonl");
  ASSERT_EQ(la.size(), 4u);
  EXPECT_EQ(la, lb);
  // A line's checksums are its files'; its scene file renders the sample again.
  const nlohmann::json& l = la.at(2);
  EXPECT_EQ(l["files"]["exr"]["sha256"], a.at("sample_000002.exr"));
  EXPECT_EQ(l["files"]["scene"]["name"], "sample_000002.yaml");
  EXPECT_TRUE(l.contains("sun_elevation_deg"));
  EXPECT_TRUE(l["cover"].contains("low"));
  double shares = 0.0;
  for (const auto& [name, share] : l["labels"].items()) shares += share.get<double>();
  EXPECT_NEAR(shares, 1.0, 1e-9);
  r = run("render " + (whole / "sample_000002.yaml").string() + " --out " + out());
  ASSERT_EQ(r.rc, 0) << r.err;
  const LayeredImage again = readExr(fs::path(out()) / "sample_000002.exr");
  const LayeredImage first = readExr(whole / "sample_000002.exr");
  ASSERT_EQ(again.layers.size(), first.layers.size());
  for (size_t i = 0; i < first.layers.size(); ++i)
    EXPECT_EQ(again.layers[i].pixels, first.layers[i].pixels) << first.layers[i].name;
}

TEST_F(DatasetCli, AKilledRunGoesOnAndRepeatsNothing) {
  const fs::path whole = mDir / "whole", resumed = mDir / "resumed";
  ASSERT_EQ(run("dataset " + spec().string() + " --out " + whole.string()).rc, 0);
  // A run killed after two samples, while appending its third line: the folder holds two
  // lines, a half line, and the third sample's files (renamed in before its line).
  ASSERT_EQ(run("dataset " + spec().string() + " --out " + resumed.string()).rc, 0);
  {
    std::ifstream in(resumed / "manifest.jsonl");
    std::string a, b, c;
    std::getline(in, a);
    std::getline(in, b);
    std::getline(in, c);
    std::ofstream(resumed / "manifest.jsonl") << a << "\n" << b << "\n" << c.substr(0, 40);
  }
  fs::remove(resumed / "sample_000003.exr");
  CliRun r = run("dataset " + spec().string() + " --out " + resumed.string());
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("4 samples, 2 rendered, 2 already there"));
  EXPECT_EQ(files(whole), files(resumed));
  EXPECT_EQ(lines(whole / "manifest.jsonl"), lines(resumed / "manifest.jsonl"));
  // Nothing left to do: a third run renders nothing.
  r = run("dataset " + spec().string() + " --out " + resumed.string());
  EXPECT_THAT(r.out, HasSubstr("0 rendered, 4 already there"));
}

TEST_F(DatasetCli, TheErrorsSayWhatAndWhere) {
  CliRun r = run("dataset " + write("bad.yaml", "count: 4\ncamera:\n  pitch: [0, 99]\n").string() +
                 " --out " + out());
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("bad.yaml:3:"));
  EXPECT_THAT(r.err, HasSubstr("camera.pitch[1]"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(outEmpty());
  r = run("dataset " + spec().string() + " --out " + out() + " --shard 3/2");
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("--shard '3/2'"));
  EXPECT_TRUE(outEmpty());
  // A folder that holds another spec's samples is refused.
  ASSERT_EQ(run("dataset " + spec().string() + " --out " + out() + " --shard 1/4").rc, 0);
  const fs::path other = write("other.yaml", "count: 3\noutput: {width: 8, height: 8}\n");
  r = run("dataset " + other.string() + " --out " + out());
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("another dataset spec"));
  // Merging one shard of four: three samples missing, exit 3.
  r = run("merge " + out());
  EXPECT_EQ(r.rc, 3) << r.err;
  EXPECT_THAT(r.err, HasSubstr("missing 3 samples: 1-3"));
  r = run("merge " + (mDir / "nowhere").string());
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("not a folder"));
  // A device lost at the first sample: one line, exit 1, and the folder the run made is gone
  // (no empty manifest left in it).
  r = run("dataset " + spec().string() + " --out " + (mDir / "lost").string(),
          "SKY_FAULT=device_lost_submit@1");
  EXPECT_EQ(r.rc, 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("was lost"));
  EXPECT_FALSE(fs::exists(mDir / "lost"));
}

TEST_F(DatasetCli, RenderWritesThePerceptionLayers) {
  const fs::path scene = fs::path(std::getenv("SKY_DATA_DIR")) / "configs" / "tests" / "clouds" /
                         "cumulus_noon.yaml";
  CliRun r = run("render " + scene.string() + " --set output.perception=true --width 32 " +
                 "--height 18 --out " + out());
  ASSERT_EQ(r.rc, 0) << r.err;
  const LayeredImage exr = readExr(fs::path(out()) / "cumulus_noon.exr");
  std::set<std::string> channels;
  for (const ImageLayer& l : exr.layers)
    for (const std::string& c : l.channels) channels.insert(l.name.empty() ? c : l.name + "." + c);
  for (const char* c : {"clouds.optical_depth", "clouds.distance", "label", "cloud_type",
                        "air.transmittance", "ground.cloud_shadow"})
    EXPECT_TRUE(channels.count(c)) << c;
  EXPECT_TRUE(exr.attributes.count("skylayers:visibility_m"));
  const nlohmann::json report =
      nlohmann::json::parse(readTextFile(fs::path(out()) / "cumulus_noon.json"));
  EXPECT_GT(report["perception"]["visibility_m"].get<double>(), 0.0);
  EXPECT_GE(report["perception"]["sun_visible"].get<double>(), 0.0);
  EXPECT_TRUE(report["perception"]["label_shares"].contains("low_cloud"));
  // A top-down map has no observer's rays to label.
  r = run("render " + scene.string() + " --set output.perception=true --set " +
          "camera.mode=geographic_topdown --out " + out() + "/td");
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("perception needs camera.mode observer"));
}

}  // namespace
}  // namespace sky

namespace sky {
namespace {

// The mean PSNR (dB) of two EXRs' beauty over their peak.
double beautyPsnr(const fs::path& a, const fs::path& b) {
  const LayeredImage x = readExr(a), y = readExr(b);
  const ImageLayer *lx = x.find(""), *ly = y.find("");
  double err = 0.0, peak = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < lx->pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    err += double(lx->pixels[i] - ly->pixels[i]) * double(lx->pixels[i] - ly->pixels[i]);
    peak = std::max(peak, double(lx->pixels[i]));
    ++n;
  }
  return err == 0.0 ? 999.0 : 10.0 * std::log10(peak * peak / (err / double(n)));
}

TEST_F(DatasetCli, ATimeLapsesShardsAreItsFramesAndMerge) {
  const fs::path scene = fs::path(std::getenv("SKY_DATA_DIR")) / "configs" / "tests" / "clouds" /
                         "cumulus_noon.yaml";
  const std::string base = "render " + scene.string() +
                           " --width 24 --height 14 --time 2024-06-21T12:00:00+02:00/"
                           "2024-06-21T12:05:00+02:00/1m";
  const fs::path whole = mDir / "whole", sharded = mDir / "sharded";
  ASSERT_EQ(run(base + " --out " + whole.string()).rc, 0);
  for (const char* s : {"1/3", "2/3", "3/3"}) {
    const CliRun r = run(base + " --out " + sharded.string() + " --shard " + s);
    ASSERT_EQ(r.rc, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr("wrote 2 frames"));
  }
  const CliRun m = run("merge " + sharded.string());
  ASSERT_EQ(m.rc, 0) << m.err;
  EXPECT_THAT(m.out, HasSubstr("6 of 6"));
  // A minute's step moves the sun past what a kept light volume may serve: every frame is
  // its own, and the shards' files are the whole run's, checksum for checksum.
  for (int i = 1; i <= 6; ++i)
    for (const char* ext : {".exr", ".png"}) {
      const std::string name = "cumulus_noon_000" + std::to_string(i) + ext;
      EXPECT_EQ(sha256File(whole / name), sha256File(sharded / name)) << name;
    }
  const CliRun r = run("render " + scene.string() + " --shard 1/2 --out " + out());
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("one instant"));
}

TEST_F(DatasetCli, WithTemporalReuseAShardWarmsUpToTheWholeRunsHistory) {
  const fs::path scene = fs::path(std::getenv("SKY_DATA_DIR")) / "configs" / "tests" / "clouds" /
                         "cumulus_noon.yaml";
  // 21 frames half a second apart, the history marched in 2 x 2 blocks; shard 2 of 2 writes
  // frames 11-21 and draws the 8 before them first.
  const std::string base = "render " + scene.string() +
                           " --width 32 --height 18 --set clouds.temporal.mode=on"
                           " --set clouds.temporal.block=2 --time 2024-06-21T12:00:00+02:00/"
                           "2024-06-21T12:00:10+02:00/0.5s";
  const fs::path whole = mDir / "whole", sharded = mDir / "sharded";
  ASSERT_EQ(run(base + " --out " + whole.string()).rc, 0);
  const CliRun r = run(base + " --out " + sharded.string() + " --shard 2/2");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("8 warm-up frames"));
  double worst = 999.0;
  for (int i = 11; i <= 21; ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "cumulus_noon_%04d.exr", i);
    worst = std::min(worst, beautyPsnr(whole / name, sharded / name));
  }
  std::printf("worst PSNR of the shard's frames against the whole run's: %.1f dB\n", worst);
  // Measured 94 dB: the shard marches the very pixels with the very jitter the whole run does
  // (RenderOptions::sequenceFrame); what is left is the cut's history mixed in by the wind's
  // reprojection. With the warm-up alone (other pixels marched, other jitter) it was 37 dB.
  EXPECT_GT(worst, 60.0);
}

}  // namespace
}  // namespace sky
