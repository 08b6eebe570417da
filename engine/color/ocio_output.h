#pragma once
// Display output through OpenColorIO: scene-linear renders become display-referred pixels
// for a display/view pair of the active OCIO config. OCIO types stay behind a pimpl so
// users of this header do not need the OCIO headers.
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sky {

class OcioOutput {
public:
  // Loads and validates the config once at start-up. The config is chosen as:
  // explicit path (--ocio FILE) > $OCIO > configDir()/ocio/config.ocio.
  // A missing, unparsable or invalid config is a BadInput error naming the file.
  static OcioOutput load(const std::optional<std::filesystem::path>& explicitConfig = std::nullopt);

  OcioOutput(OcioOutput&&) noexcept;
  OcioOutput& operator=(OcioOutput&&) noexcept;
  OcioOutput(const OcioOutput&) = delete;
  OcioOutput& operator=(const OcioOutput&) = delete;
  ~OcioOutput();

  // The file the config came from; valid for the object's lifetime.
  const std::filesystem::path& configPath() const;
  // Active displays of the config, in config order.
  std::vector<std::string> displays() const;
  // Active views of `display`, in config order; empty for an unknown display.
  std::vector<std::string> views(const std::string& display) const;
  // Call while validating settings, before any rendering: BadInput naming the available
  // displays (or views of that display) when the pair does not exist, or naming the config
  // when its transforms for the pair cannot be built (a LUT file missing).
  void checkDisplayView(const std::string& display, const std::string& view) const;
  // Multiplies RGB by 2^exposureEv, then converts scene_linear -> display/view in place on
  // interleaved RGBA floats (alpha untouched). Thread-safe; processors are cached per
  // display and view for the object's lifetime (not per exposure: a time-lapse has one a frame).
  void toDisplay(std::span<float> rgba, const std::string& display, const std::string& view,
                 double exposureEv) const;

private:
  struct Impl;
  explicit OcioOutput(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> mImpl;
};

}  // namespace sky
