// Renders a small frame of the built-in scene through the installed library and prints what
// a host would check: where the data came from, the image, the sun. Exit 1 on anything off.
#include <cmath>
#include <cstdio>

#include <skylayers/skylayers.h>

int main() {
  try {
    skylayers::Sky sky = skylayers::Sky::fromDefault({"output.width=24", "output.height=16"});
    const skylayers::Frame frame = sky.render({.layers = false, .display = true});
    const skylayers::Image& beauty = frame.beauty;
    double sum = 0.0;
    for (float v : beauty.pixels) {
      if (!std::isfinite(v)) {
        std::printf("consumer: a pixel is not finite\n");
        return 1;
      }
      sum += v;
    }
    const skylayers::Lighting light = sky.lighting();
    std::printf("version %s\ndata %s\nimage %dx%d channels %zu display %zu sum %.6g\n",
                skylayers::version(), skylayers::dataDirectory().c_str(), beauty.width,
                beauty.height, beauty.channels.size(), frame.display.size(), sum);
    std::printf("sun elevation %.3f key %s validation %llu\n", light.sun.elevationDeg,
                light.key.c_str(), static_cast<unsigned long long>(sky.validationMessages()));
    // A wrong key is the library's Error, caught here by its type across the library's edge.
    try {
      sky.set("camera.latitud", "10");
      std::printf("consumer: a wrong key was taken\n");
      return 1;
    } catch (const skylayers::Error& e) {
      std::printf("error %s: %s\n",
                  e.kind() == skylayers::Error::Kind::BadInput ? "bad_input" : "internal",
                  e.what());
    }
    return sky.validationMessages() == 0 && sum > 0.0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::printf("consumer: %s\n", e.what());
    return 1;
  }
}
