#include "engine/color/ocio_output.h"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <mutex>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/paths.h"

namespace OCIO = OCIO_NAMESPACE;

namespace sky {
namespace fs = std::filesystem;

namespace {

// OCIO messages can span several lines (YAML context, validation lists); our errors are one
// line, so every run of whitespace containing a newline becomes a single space.
std::string oneLine(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  bool pendingSpace = false;
  for (char c : text) {
    if (c == '\n' || c == '\r' || c == '\t') {
      pendingSpace = true;
      continue;
    }
    if (pendingSpace && !out.empty() && out.back() != ' ') out += ' ';
    pendingSpace = false;
    out += c;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

// One processor per display and view. The exposure is not in the key nor in the chain: a
// time-lapse under automatic exposure has a new value every frame, and a processor each (in
// our map and in OCIO's own processor cache) grew a 2,000-frame run by 58 KB a frame with
// AgX's LUT (SkyrenderCli.AThousandFramesInOneProcessKeepMemoryFlat).
std::string cacheKey(const std::string& display, const std::string& view) {
  return display + '\x1f' + view;
}

}  // namespace

struct OcioOutput::Impl {
  fs::path path;
  OCIO::ConstConfigRcPtr config;
  mutable std::mutex mutex;
  mutable std::map<std::string, OCIO::ConstCPUProcessorRcPtr> processors;

  OCIO::ConstCPUProcessorRcPtr processor(const OcioOutput& self, const std::string& display,
                                         const std::string& view) const;
};

OcioOutput::OcioOutput(std::unique_ptr<Impl> impl) : mImpl(std::move(impl)) {}
OcioOutput::OcioOutput(OcioOutput&&) noexcept = default;
OcioOutput& OcioOutput::operator=(OcioOutput&&) noexcept = default;
OcioOutput::~OcioOutput() = default;

OcioOutput OcioOutput::load(const std::optional<fs::path>& explicitConfig) {
  fs::path path;
  std::string source;
  const char* env = std::getenv("OCIO");
  if (explicitConfig) {
    path = *explicitConfig;
    source = "--ocio";
  } else if (env && *env) {
    path = env;
    source = "$OCIO";
  } else {
    path = configDir() / "ocio" / "config.ocio";
    source = "default";
  }
  const std::string where = path.string() + ": OCIO config (" + source + ")";

  // OCIO reports a missing file as a parse failure; saying "not found" is clearer.
  std::error_code ec;
  if (!fs::exists(path, ec)) inputError(where + ": file not found");
  if (fs::is_directory(path, ec)) inputError(where + ": is a directory, not a config file");
  refuseSpecialFile(path);

  auto impl = std::make_unique<Impl>();
  impl->path = path;
  try {
    impl->config = OCIO::Config::CreateFromFile(path.c_str());
  } catch (const OCIO::Exception& e) {
    inputError(where + ": cannot load: " + oneLine(e.what()));
  }
  try {
    impl->config->validate();
  } catch (const OCIO::Exception& e) {
    inputError(where + ": invalid: " + oneLine(e.what()));
  }
  // toDisplay converts from scene_linear; a config without it cannot serve us at all, and
  // failing here beats failing at the first frame.
  if (!impl->config->hasRole(OCIO::ROLE_SCENE_LINEAR))
    inputError(where + ": has no '" + std::string(OCIO::ROLE_SCENE_LINEAR) + "' role");
  if (impl->config->getNumDisplays() == 0) inputError(where + ": defines no active display");
  return OcioOutput(std::move(impl));
}

const fs::path& OcioOutput::configPath() const {
  return mImpl->path;
}

std::vector<std::string> OcioOutput::displays() const {
  std::vector<std::string> out;
  try {
    for (int i = 0; i < mImpl->config->getNumDisplays(); ++i)
      out.emplace_back(mImpl->config->getDisplay(i));
  } catch (const OCIO::Exception& e) {
    internalError("OCIO: listing displays of " + mImpl->path.string() + ": " + oneLine(e.what()));
  }
  return out;
}

std::vector<std::string> OcioOutput::views(const std::string& display) const {
  std::vector<std::string> out;
  std::vector<std::string> known = displays();
  if (std::find(known.begin(), known.end(), display) == known.end()) return out;
  try {
    for (int i = 0; i < mImpl->config->getNumViews(display.c_str()); ++i)
      out.emplace_back(mImpl->config->getView(display.c_str(), i));
  } catch (const OCIO::Exception& e) {
    internalError("OCIO: listing views of display '" + display + "' in " + mImpl->path.string() +
                  ": " + oneLine(e.what()));
  }
  return out;
}

namespace {
// BadInput naming what the config has when it lacks the display or the view.
void checkNames(const OcioOutput& ocio, const std::string& display, const std::string& view) {
  std::vector<std::string> known = ocio.displays();
  if (std::find(known.begin(), known.end(), display) == known.end())
    inputError("output.display: unknown OCIO display '" + display +
               "' (available: " + joinNames(known) + ")");
  std::vector<std::string> viewNames = ocio.views(display);
  if (std::find(viewNames.begin(), viewNames.end(), view) == viewNames.end())
    inputError("output.view: unknown OCIO view '" + view + "' for display '" + display +
               "' (available: " + joinNames(viewNames) + ")");
}
}  // namespace

void OcioOutput::checkDisplayView(const std::string& display, const std::string& view) const {
  checkNames(*this, display, view);
  // The processor reads the files the view's transforms name (LUTs): one that is missing
  // fails here, in `validate` and before a render, not after its frame (issue 31, 11).
  mImpl->processor(*this, display, view);
}

OCIO::ConstCPUProcessorRcPtr OcioOutput::Impl::processor(const OcioOutput& self,
                                                         const std::string& display,
                                                         const std::string& view) const {
  const std::string key = cacheKey(display, view);
  std::lock_guard<std::mutex> lock(mutex);
  if (auto it = processors.find(key); it != processors.end()) return it->second;

  checkNames(self, display, view);
  try {
    OCIO::DisplayViewTransformRcPtr dv = OCIO::DisplayViewTransform::Create();
    dv->setSrc(OCIO::ROLE_SCENE_LINEAR);
    dv->setDisplay(display.c_str());
    dv->setView(view.c_str());
    OCIO::ConstCPUProcessorRcPtr cpu = config->getProcessor(dv)->getDefaultCPUProcessor();
    processors.emplace(key, cpu);
    return cpu;
  } catch (const OCIO::Exception& e) {
    // The pair exists (checked above), so the config itself is broken for it: user-fixable.
    inputError(path.string() + ": OCIO cannot build display '" + display + "' view '" + view +
               "': " + oneLine(e.what()));
  }
}

void OcioOutput::toDisplay(std::span<float> rgba, const std::string& display,
                           const std::string& view, double exposureEv) const {
  if (rgba.size() % 4 != 0)
    internalError("OcioOutput::toDisplay: " + std::to_string(rgba.size()) +
                  " floats is not a whole number of RGBA pixels");
  if (!std::isfinite(exposureEv))
    inputError("output.exposure: " + std::to_string(exposureEv) + " EV is not a finite number");
  OCIO::ConstCPUProcessorRcPtr cpu = mImpl->processor(*this, display, view);
  if (rgba.empty()) return;
  // The exposure, before the view (scene-linear RGB; alpha untouched).
  if (exposureEv != 0.0) {
    const float scale = static_cast<float>(std::exp2(exposureEv));
    for (size_t i = 0; i < rgba.size(); i += 4)
      for (size_t c = 0; c < 3; ++c) rgba[i + c] *= scale;
  }
  try {
    // RGB ordering with a 16-byte pixel stride: OCIO reads and writes only R, G, B, so alpha
    // stays untouched whatever transforms a user's config contains.
    const ptrdiff_t f = sizeof(float);
    const long pixels = static_cast<long>(rgba.size() / 4);
    OCIO::PackedImageDesc image(rgba.data(), pixels, 1, OCIO::CHANNEL_ORDERING_RGB,
                                OCIO::BIT_DEPTH_F32, f, 4 * f, pixels * 4 * f);
    cpu->apply(image);
  } catch (const OCIO::Exception& e) {
    internalError("OCIO: applying display '" + display + "' view '" + view +
                  "': " + oneLine(e.what()));
  }
}

}  // namespace sky
