// skyrender export-volume: the exported grid holds the raymarch's density field at its voxel
// centres (checked against the density-slice view, which evaluates the same field along its
// own geometry), survives the OpenVDB file with its metadata, and the command fails cleanly
// on bad input. An export of several nested boxes (the path-traced field of issue 46) holds
// the field once, each grid its share, at the raymarch's level of detail.
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "engine/core/error.h"
#include "engine/io/vdb.h"
#include "engine/weather/geo.h"
#include "tests/apps/cli_fixture.h"
#include "tests/volumetric_clouds/cloud_test_util.h"

namespace sky::test {
namespace {

// The small cumulus golden scene, looking north so the density slice lies in the
// north-up plane of the camera's ENU frame.
Scene exportScene() {
  return cloudScene("cumulus_noon", {"output.width=96", "output.height=54", "camera.heading=0"});
}

// The ENU point the density slice samples for texel (i, j) of its W x H image
// (shaders/cloud_density_slice.comp): `distance` along the ground northward at `altitude`.
glm::dvec3 slicePoint(const Scene& scene, int i, int j) {
  const double R = kEarthRadiusM;
  const double distance = (i + 0.5) / CloudDensitySlicePass::kWidth * 60000.0;
  const double top = std::max(scene.clouds.low.topM, scene.clouds.mid.topM) + 500.0;
  const double altitude = (1.0 - (j + 0.5) / CloudDensitySlicePass::kHeight) * top;
  const double angle = distance / R;
  return {0.0, (R + altitude) * std::sin(angle),
          (R + altitude) * std::cos(angle) - (R + scene.camera.altitudeM)};
}

struct SliceTexel {
  int i, j;
  float density;
};

// Texels of the density slice inside cloud, spread along it.
std::vector<SliceTexel> cloudyTexels(const RenderedFrame& frame, size_t count) {
  const DebugImage& slice = frame.debug.at(0);
  const ImageLayer& layer = slice.image.layers.at(0);
  std::vector<SliceTexel> all;
  for (int j = 0; j < slice.image.height; ++j)
    for (int i = 0; i < slice.image.width; ++i) {
      const float d = layer.pixels[(size_t(j) * slice.image.width + i) * 4];
      if (d > 0.05f) all.push_back({i, j, d});
    }
  std::vector<SliceTexel> out;
  for (size_t k = 0; k < count && !all.empty(); ++k) out.push_back(all[k * all.size() / count]);
  return out;
}

class CloudVolumeExport : public CloudRenderTest {
 protected:
  // The export scene's frame with its density slice, the reference both tests sample.
  RenderedFrame renderWithSlice(const Scene& scene) {
    RenderOptions options;
    options.debugOutputs = {"cloud_density_slice"};
    return render(scene, options);
  }
};

TEST_F(CloudVolumeExport, VoxelsHoldTheRaymarchDensityAtTheirCentres) {
  const Scene scene = exportScene();
  const RenderedFrame frame = renderWithSlice(scene);
  const std::vector<SliceTexel> texels = cloudyTexels(frame, 6);
  ASSERT_EQ(texels.size(), 6u) << "the slice crosses no cloud";
  for (const SliceTexel& t : texels) {
    // One voxel centred on the slice's sample point.
    const glm::dvec3 p = slicePoint(scene, t.i, t.j);
    const double v = 1.0;
    const CloudVolume volume =
        renderer().exportCloudVolume(scene, scene.time.start, CloudVolumeBox{p - 0.5 * v, p + 0.5 * v}, v);
    ASSERT_EQ(volume.extinction.values.size(), 1u);
    const double density = volume.extinction.values[0] / scene.clouds.extinction;
    // The slice is half float (11 bits); its point is computed in float without cancelling
    // (millimetres), which matters across a sharp cloud edge.
    EXPECT_NEAR(density, t.density, 2e-3 + 4e-3 * t.density) << "slice texel " << t.i << ", " << t.j;
  }
}

TEST_F(CloudVolumeExport, TinyGridRoundTripsThroughOpenVdb) {
  const Scene scene = exportScene();
  const RenderedFrame frame = renderWithSlice(scene);
  const std::vector<SliceTexel> texels = cloudyTexels(frame, 1);
  ASSERT_EQ(texels.size(), 1u);
  const glm::dvec3 centre = slicePoint(scene, texels[0].i, texels[0].j);
  // 8 x 8 x 8 voxels of 100 m around a point inside a cloud.
  const CloudVolumeBox box{centre - 400.0, centre + 400.0};
  const CloudVolume volume = renderer().exportCloudVolume(scene, scene.time.start, box, 100.0);
  ASSERT_EQ(volume.extinction.size, glm::uvec3(8));
  float largest = 0.0f;
  for (float e : volume.extinction.values) largest = std::max(largest, e);
  EXPECT_GT(largest, 0.0f);
  EXPECT_LE(largest, scene.clouds.extinction * 1.0001);

  const fs::path dir = fs::temp_directory_path() / ("cloud-volume-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  writeCloudVolume(dir / "tiny.vdb", volume);
  const VdbFile file = readVdb(dir / "tiny.vdb", "density");
  fs::remove_all(dir);

  EXPECT_EQ(file.grid.size, glm::uvec3(8));
  EXPECT_NEAR(file.grid.voxelSize, 100.0, 1e-9);
  EXPECT_LT(glm::length(file.grid.firstVoxelCentre - (box.minM + 50.0)), 1e-6);
  ASSERT_EQ(file.grid.values.size(), volume.extinction.values.size());
  for (size_t i = 0; i < file.grid.values.size(); ++i)
    ASSERT_EQ(file.grid.values[i], volume.extinction.values[i]) << "voxel " << i;

  auto number = [&](const std::string& key) { return std::get<double>(file.metadata.at(key)); };
  auto vector = [&](const std::string& key) { return std::get<glm::dvec3>(file.metadata.at(key)); };
  EXPECT_EQ(std::get<int64_t>(file.metadata.at("camera_width")), 96);
  EXPECT_EQ(std::get<int64_t>(file.metadata.at("camera_height")), 54);
  EXPECT_EQ(number("camera_heading_deg"), 0.0);
  EXPECT_EQ(number("camera_vertical_fov_deg"), scene.camera.verticalFov);
  EXPECT_EQ(number("extinction_per_density"), scene.clouds.extinction);
  EXPECT_EQ(number("phase_g"), scene.clouds.g);
  EXPECT_EQ(number("phase_g_back"), scene.clouds.gBack);
  EXPECT_EQ(number("phase_back_weight"), scene.clouds.backWeight);
  EXPECT_EQ(std::get<std::string>(file.metadata.at("phase")), "dual_lobe");
  EXPECT_EQ(std::get<std::string>(file.metadata.at("sky_model")), "kozlov");
  EXPECT_LT(glm::length(vector("sun_direction") - frame.lighting.sun.direction), 1e-9);
  EXPECT_LT(glm::length(vector("camera_forward") -
                        glm::dvec3(glm::vec3(makeViewState(scene.camera, 96, 54).forward))),
            1e-6);
  const glm::vec4 top = frame.lighting.gpu.palette.ambientTop + frame.lighting.gpu.moonPalette.ambientTop;
  EXPECT_LT(glm::length(vector("ambient_top") - glm::dvec3(glm::vec3(top))), 1e-6);
  // Noon in June at 47 N: the sun high, its light at the clouds a few units strong.
  EXPECT_GT(number("sun_elevation_deg"), 60.0);
  EXPECT_GT(vector("sun_illuminance").g, 1.0);
  // Each layer's light at its base, middle and top (the path tracer's lamp takes that profile):
  // the middle of the layer the grid lies in is the one above, and the air dims the base most.
  const std::string layer = number("light_altitude_m") > number("low_top_m") ? "mid" : "low";
  EXPECT_LT(glm::length(vector("sun_illuminance_" + layer + "_middle") - vector("sun_illuminance")),
            1e-6);
  for (const std::string l : {"low", "mid"}) {
    EXPECT_LT(vector("sun_illuminance_" + l + "_base").b, vector("sun_illuminance_" + l + "_middle").b);
    EXPECT_LT(vector("sun_illuminance_" + l + "_middle").b, vector("sun_illuminance_" + l + "_top").b);
  }
  EXPECT_EQ(number("voxel_m"), 100.0);
}

// Three nested parts, finest first, in the shape of a view toward the horizon: the near one
// shares its west, east and bottom faces with nothing, the outer ones extend past them.
std::vector<CloudVolumePart> nestedParts() {
  return {{{glm::dvec3(-1000, 500, 500), glm::dvec3(1000, 3000, 2500)}, 50.0},
          {{glm::dvec3(-2500, 500, 500), glm::dvec3(2500, 7000, 2500)}, 100.0},
          {{glm::dvec3(-5000, 0, 400), glm::dvec3(5000, 12000, 2500)}, 250.0}};
}

TEST(CloudVolumeParts, SharesSumToOneInsideTheOutermostPart) {
  const std::vector<CloudVolumePart> parts = nestedParts();
  checkCloudVolumeParts(parts);
  std::mt19937 rng(46);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const CloudVolumeBox& outer = parts.back().box;
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 p =
        outer.minM + glm::dvec3(u(rng), u(rng), u(rng)) * (outer.maxM - outer.minM);
    double sum = 0.0;
    for (size_t k = 0; k < parts.size(); ++k) {
      const double share = cloudVolumeShare(parts, k, p);
      ASSERT_GE(share, 0.0);
      ASSERT_LE(share, 1.0);
      sum += share;
    }
    ASSERT_NEAR(sum, 1.0, 1e-12) << p.x << ", " << p.y << ", " << p.z;
  }
  // Deep inside the finest part it holds all; its band is two voxels of the next part.
  EXPECT_EQ(cloudVolumeShare(parts, 0, glm::dvec3(0, 1500, 1500)), 1.0);
  EXPECT_EQ(cloudVolumeBlendM(parts, 0), 200.0);
  EXPECT_EQ(cloudVolumeBlendM(parts, 1), 500.0);
  EXPECT_EQ(cloudVolumeBlendM(parts, 2), 0.0);
  // Halfway into the band by its north face: half each to the first and the second.
  EXPECT_NEAR(cloudVolumeShare(parts, 0, glm::dvec3(0, 2900, 1500)), 0.5, 1e-12);
  EXPECT_NEAR(cloudVolumeShare(parts, 1, glm::dvec3(0, 2900, 1500)), 0.5, 1e-12);
  // Its top face is the outermost's too: no band there, the fine grid holds the field to it.
  EXPECT_EQ(cloudVolumeShare(parts, 0, glm::dvec3(0, 1500, 2499)), 1.0);
  // Outside a part it holds nothing.
  EXPECT_EQ(cloudVolumeShare(parts, 0, glm::dvec3(0, 3500, 1500)), 0.0);
  EXPECT_EQ(cloudVolumeShare(parts, 2, glm::dvec3(0, 1500, 1500)), 0.0);
}

TEST(CloudVolumeParts, PartsMustBeNestedFinestFirst) {
  std::vector<CloudVolumePart> parts = nestedParts();
  std::swap(parts[0], parts[1]);
  try {
    checkCloudVolumeParts(parts);
    FAIL() << "parts out of order passed";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_THAT(e.what(), HasSubstr("--box -1000,500,500,1000,3000,2500 (box 2) must contain "
                                    "--box -2500,500,500,2500,7000,2500 (box 1)"));
  }
}

// The multi-box export at the raymarch's level of detail: at every voxel centre of every part,
// the part's value over its share is the field at that point as a sample of that footprint
// sees it (the CPU twin, engine/render/cloud_field.h, which the single-box tests hold to the
// GPU at full detail), and the shares make the parts add up to the field once.
TEST_F(CloudVolumeExport, NestedBoxesHoldTheFieldAtTheRaymarchsLevelOfDetail) {
  // Looking north; a small image, so a pixel is wide and the footprint reaches the detail
  // noise (0.0321 m a metre: 50 m at 1.6 km, the far field's mean by 20 km).
  const Scene scene =
      cloudScene("cumulus_noon", {"output.width=32", "output.height=18", "camera.heading=0"});
  const std::vector<CloudVolumePart> parts = nestedParts();
  CloudVolumeRequest request;
  request.parts = parts;
  request.lod = CloudVolumeLod::View;
  const std::vector<CloudVolume> volumes =
      renderer().exportCloudVolumes(scene, scene.time.start, request);
  ASSERT_EQ(volumes.size(), 3u);
  const CloudField field = renderer().cloudField(scene, scene.time.start);
  const double extinction = scene.clouds.extinction;
  const double perM = makeViewState(scene.camera, 32, 18).forward.w;
  size_t compared = 0, cloudy = 0, far = 0;
  double worst = 0.0;
  for (size_t k = 0; k < parts.size(); ++k) {
    const VdbGrid& grid = volumes[k].extinction;
    EXPECT_EQ(grid.name, k == 0 ? "density" : "density_" + std::to_string(k));
    EXPECT_EQ(std::get<int64_t>(volumes[k].metadata.at("grid_index")), int64_t(k));
    EXPECT_EQ(std::get<int64_t>(volumes[k].metadata.at("grid_count")), 3);
    EXPECT_EQ(std::get<std::string>(volumes[k].metadata.at("lod")), "view");
    EXPECT_EQ(std::get<double>(volumes[k].metadata.at("footprint_min_m")), parts[k].voxelM);
    EXPECT_EQ(std::get<double>(volumes[k].metadata.at("blend_m")), cloudVolumeBlendM(parts, k));
    EXPECT_EQ(grid.voxelSize, parts[k].voxelM);
    size_t i = 0;
    for (uint32_t z = 0; z < grid.size.z; ++z)
      for (uint32_t y = 0; y < grid.size.y; ++y)
        for (uint32_t x = 0; x < grid.size.x; ++x, ++i) {
          const glm::dvec3 p = grid.firstVoxelCentre + glm::dvec3(x, y, z) * grid.voxelSize;
          const double share = cloudVolumeShare(parts, k, p);
          if (share < 0.05) {
            ASSERT_EQ(share > 0.0 ? grid.values[i] >= 0.0f : grid.values[i] == 0.0f, true) << k;
            continue;
          }
          const float footprint = float(std::max(perM * glm::length(p), parts[k].voxelM));
          const double cpu = field.sample(p, footprint).density;
          const double gpu = grid.values[i] / extinction / share;
          const double err = std::abs(cpu - gpu);
          ++compared;
          cloudy += gpu > 0.0;
          worst = std::max(worst, err);
          // As the single-box comparison (cloud_field_test.cpp): float against double
          // geography, sharpened at the cloud's edge.
          far += err > 0.01 + 0.02 * gpu;
        }
  }
  std::printf("%zu voxels compared, %zu cloudy, worst %.4f, off %zu\n", compared, cloudy, worst,
              far);
  ASSERT_GT(cloudy, compared / 50) << "the parts should hold cloud";
  EXPECT_LE(far, compared / 200) << "voxels off by more than 0.01 + 2 %";
  EXPECT_LT(worst, 0.05);
}

class ExportVolumeCli : public SkyrenderCli {
protected:
  std::string scene() const {
    return (configDir() / "tests" / "clouds" / "cumulus_noon.yaml").string();
  }
  // A failed export: exit 2, one error line holding `fragment`, no file written.
  void expectBadInput(const std::string& args, const std::string& fragment) {
    const fs::path vdb = mDir / "out" / "v.vdb";
    CliRun r = run("export-volume " + scene() + " " + args + " --out " + vdb.string());
    EXPECT_EQ(r.rc, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_THAT(r.err, HasSubstr("error: "));
    EXPECT_THAT(r.err, HasSubstr(fragment));
    EXPECT_TRUE(outEmpty()) << "a failed export left files behind";
  }
};

TEST_F(ExportVolumeCli, WritesAGridOpenVdbReads) {
  const fs::path vdb = mDir / "out" / "v.vdb";
  CliRun r = run("export-volume " + scene() +
                 " --width 96 --height 54 --box -200,-200,500,200,200,900 --voxel-m 50 --out " +
                 vdb.string());
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("wrote " + vdb.string() + " (8x8x8 voxels of 50 m"));
  const VdbFile file = readVdb(vdb, "density");
  EXPECT_EQ(file.grid.size, glm::uvec3(8));
  EXPECT_EQ(std::get<int64_t>(file.metadata.at("camera_width")), 96);
  EXPECT_LT(glm::length(std::get<glm::dvec3>(file.metadata.at("box_min_m")) -
                        glm::dvec3(-200, -200, 500)),
            1e-9);
  // Nothing but the file: the temporary it was written through is gone.
  EXPECT_EQ(std::distance(fs::directory_iterator(mDir / "out"), fs::directory_iterator()), 1);
}

TEST_F(ExportVolumeCli, NestedBoxesAreTheGridsOfOneFile) {
  const fs::path vdb = mDir / "out" / "field.vdb";
  CliRun r = run("export-volume " + scene() +
                 " --width 96 --height 54 --box -200,-200,500,200,200,900 --box "
                 "-400,-400,500,400,400,1300 --voxel-m 50 --voxel-m 100 --lod view --out " +
                 vdb.string());
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("wrote " + vdb.string() + " grid density (8x8x8 voxels of 50 m"));
  EXPECT_THAT(r.out, HasSubstr("wrote " + vdb.string() + " grid density_1 (8x8x8 voxels of 100 m"));
  const VdbFile fine = readVdb(vdb, "density");
  const VdbFile coarse = readVdb(vdb, "density_1");
  EXPECT_EQ(fine.grid.size, glm::uvec3(8));
  EXPECT_EQ(coarse.grid.voxelSize, 100.0);
  EXPECT_EQ(std::get<int64_t>(coarse.metadata.at("grid_index")), 1);
  EXPECT_EQ(std::get<int64_t>(fine.metadata.at("grid_count")), 2);
  EXPECT_EQ(std::get<double>(fine.metadata.at("blend_m")), 200.0);
  EXPECT_EQ(std::get<std::string>(coarse.metadata.at("lod")), "view");
  EXPECT_EQ(std::distance(fs::directory_iterator(mDir / "out"), fs::directory_iterator()), 1);
}

TEST_F(ExportVolumeCli, BadNestedBoxesAreOneLineAndWriteNothing) {
  const std::string inner = "--box -200,-200,500,200,200,900";
  const std::string outer = "--box -400,-400,500,400,400,1300";
  expectBadInput(outer + " " + inner,
                 "--box -200,-200,500,200,200,900 (box 2) must contain --box "
                 "-400,-400,500,400,400,1300 (box 1): several boxes are nested, finest first");
  expectBadInput(inner + " " + outer + " " + outer + " --voxel-m 50 --voxel-m 100",
                 "--voxel-m is given 2 times for 3 --box: give one voxel for every box, or one "
                 "for each box in order");
  expectBadInput(inner + " " + outer + " --voxel-m 50 --voxel-m x",
                 "--voxel-m 'x': expected a number");
  expectBadInput(inner + " --lod coarse", "--lod 'coarse': expected full or view");
  // Five boxes of 400^3 voxels: each within 2^26, together past 2^28.
  std::string five;
  for (int i = 0; i < 5; ++i) five += " --box 0,0,0,400,400,400";
  expectBadInput(five + " --voxel-m 1",
                 "--box: the 5 boxes need 320000000 voxels in all, more "
                 "than the 268435456 allowed");
}

TEST_F(ExportVolumeCli, BadBoxIsOneLineAndWritesNothing) {
  expectBadInput("--box 1,2,3", "--box '1,2,3': expected six numbers E0,N0,U0,E1,N1,U1");
  expectBadInput("--box 0,0,0,1,1,x", "expected six numbers");
  expectBadInput("--box 0,0,0,1,1,1,1", "expected six numbers");
  expectBadInput("--box 0,0,0,-1,1,1", "the maximum east (-1) must lie above the minimum (0)");
  expectBadInput("--box 0,0,0,1,1,1 --voxel-m 0", "--voxel-m 0: out of range");
  expectBadInput("--box 0,0,0,100000,100000,5000 --voxel-m 1",
                 "voxels, more than the 67108864 allowed");
  expectBadInput("--set camera.mode=geographic_topdown", "geographic_topdown");
  expectBadInput("--set weather.cover_low=0", "no low or mid clouds");
}

TEST_F(ExportVolumeCli, OutMustBeAVdbFileInAFolderThatExists) {
  CliRun r = run("export-volume " + scene() + " --out " + (mDir / "nowhere" / "v.vdb").string());
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("does not exist"));
  r = run("export-volume " + scene() + " --out " + (mDir / "out" / "v.exr").string());
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("expected a .vdb file"));
  EXPECT_TRUE(outEmpty());
}

}  // namespace
}  // namespace sky::test
