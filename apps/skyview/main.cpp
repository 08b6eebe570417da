// skyview: the skylayers scene in a window. Thin: parse, run the viewer, one line per error.
#include <cstdio>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "viewer.h"
#include "viewer_options.h"

namespace {

std::string oneLine(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    sky::view::ViewerOptions options =
        sky::view::parseViewerOptions(std::vector<std::string>(argv + 1, argv + argc));
    if (options.help) {
      std::fputs(sky::view::viewerHelpText(), stdout);
      return 0;
    }
    sky::view::Viewer viewer(std::move(options));
    return viewer.run();
  } catch (const sky::Error& e) {
    std::fprintf(stderr, "skyview: %s\n", oneLine(e.what()).c_str());
    return e.exitCode();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "skyview: internal error: %s\n", oneLine(e.what()).c_str());
    return 1;
  }
}
