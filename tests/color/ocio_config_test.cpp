// The shipped configs/ocio/config.ocio, checked with OCIO's own API (no sky code in the way).
#include <OpenColorIO/OpenColorIO.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "engine/core/files.h"
#include "engine/core/paths.h"

namespace OCIO = OCIO_NAMESPACE;

namespace sky {
namespace {

OCIO::ConstConfigRcPtr shippedConfig() {
  return OCIO::Config::CreateFromFile((configDir() / "ocio" / "config.ocio").c_str());
}

TEST(OcioConfig, PassesOcioValidation) {
  OCIO::ConstConfigRcPtr config = shippedConfig();
  EXPECT_NO_THROW(config->validate());
  EXPECT_EQ(config->getMajorVersion(), 2u);
  EXPECT_EQ(config->getMinorVersion(), 1u);
}

TEST(OcioConfig, RolesAndColorSpaces) {
  OCIO::ConstConfigRcPtr config = shippedConfig();
  EXPECT_STREQ(config->getColorSpace(OCIO::ROLE_SCENE_LINEAR)->getName(), "Linear Rec.709 (sRGB)");
  EXPECT_STREQ(config->getColorSpace(OCIO::ROLE_INTERCHANGE_SCENE)->getName(), "ACES2065-1");
  EXPECT_STREQ(config->getColorSpace(OCIO::ROLE_DATA)->getName(), "Raw");

  for (const char* name :
       {"ACES2065-1", "ACEScg", "Linear Rec.709 (sRGB)", "sRGB - Texture", "Raw"}) {
    OCIO::ConstColorSpaceRcPtr cs = config->getColorSpace(name);
    ASSERT_TRUE(cs) << name;
    EXPECT_EQ(cs->getReferenceSpaceType(), OCIO::REFERENCE_SPACE_SCENE) << name;
  }
  // ACES2065-1 is the scene reference: no transform either way.
  OCIO::ConstColorSpaceRcPtr aces = config->getColorSpace("ACES2065-1");
  EXPECT_FALSE(aces->getTransform(OCIO::COLORSPACE_DIR_TO_REFERENCE));
  EXPECT_FALSE(aces->getTransform(OCIO::COLORSPACE_DIR_FROM_REFERENCE));
  EXPECT_TRUE(config->getColorSpace("Raw")->isData());
  EXPECT_FALSE(config->getColorSpace("Linear Rec.709 (sRGB)")->isData());

  OCIO::ConstColorSpaceRcPtr display = config->getColorSpace("sRGB - Display");
  ASSERT_TRUE(display);
  EXPECT_EQ(display->getReferenceSpaceType(), OCIO::REFERENCE_SPACE_DISPLAY);
}

TEST(OcioConfig, BuiltFromBuiltinsAndTheGeneratedAgxCurveOnly) {
  // One LUT file, AgX's contrast curve, which scripts/ocio/make_agx.py writes next to the
  // config (luts/, on the config's search path): the folder works wherever it is copied.
  const std::string text = readTextFile(configDir() / "ocio" / "config.ocio");
  const size_t file = text.find("FileTransform");
  ASSERT_NE(file, std::string::npos);
  EXPECT_EQ(text.find("FileTransform", file + 1), std::string::npos);
  EXPECT_NE(text.find("src: agx_base_contrast.spi1d"), std::string::npos);
  EXPECT_TRUE(std::filesystem::is_regular_file(configDir() / "ocio" / "luts" /
                                               "agx_base_contrast.spi1d"));
  EXPECT_NE(text.find("ACES-OUTPUT - ACES2065-1_to_CIE-XYZ-D65 - SDR-VIDEO_1.0"),
            std::string::npos);
  EXPECT_NE(text.find("DISPLAY - CIE-XYZ-D65_to_sRGB"), std::string::npos);
}

TEST(OcioConfig, TextureSpaceIsSrgbEncodedLinearRec709) {
  OCIO::ConstConfigRcPtr config = shippedConfig();
  OCIO::ConstCPUProcessorRcPtr toLinear =
      config->getProcessor("sRGB - Texture", "Linear Rec.709 (sRGB)")->getDefaultCPUProcessor();
  // sRGB code values and their linear values from the IEC 61966-2-1 formula.
  float rgb[3] = {0.461356f, 0.04045f, 1.0f};
  toLinear->applyRGB(rgb);
  EXPECT_NEAR(rgb[0], 0.18f, 1e-4f);
  EXPECT_NEAR(rgb[1], 0.04045f / 12.92f, 1e-5f);
  EXPECT_NEAR(rgb[2], 1.0f, 1e-4f);
}

TEST(OcioConfig, AcesCgMatchesPublishedRec709Matrix) {
  // Linear Rec.709 red in ACEScg (AP1, Bradford D65 -> ACES white), as in the ACES
  // documentation's Rec.709-to-AP1 matrix first column: 0.6131, 0.0702, 0.0206.
  OCIO::ConstConfigRcPtr config = shippedConfig();
  OCIO::ConstCPUProcessorRcPtr p =
      config->getProcessor("Linear Rec.709 (sRGB)", "ACEScg")->getDefaultCPUProcessor();
  float rgb[3] = {1.0f, 0.0f, 0.0f};
  p->applyRGB(rgb);
  EXPECT_NEAR(rgb[0], 0.6131f, 2e-4f);
  EXPECT_NEAR(rgb[1], 0.0702f, 2e-4f);
  EXPECT_NEAR(rgb[2], 0.0206f, 2e-4f);
}

}  // namespace
}  // namespace sky
