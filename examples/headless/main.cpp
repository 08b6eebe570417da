// Renders the sunset over Zurich into memory and writes it as a PNG: a host with no window.
// Usage: headless OUT.png [SCENE.yaml]
#include <cstdio>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include <skylayers/skylayers.h>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: headless OUT.png [SCENE.yaml]\n");
    return 2;
  }
  try {
    skylayers::Sky sky = argc > 2 ? skylayers::Sky::fromFile(argv[2]) : skylayers::Sky::fromDefault();
    sky.setCamera({.latitudeDeg = 47.37, .longitudeDeg = 8.54, .altitudeM = 500.0,
                   .headingDeg = 300.0, .pitchDeg = 8.0});
    sky.setTime("2024-06-21T21:00:00+02:00");
    sky.setSize(320, 180);
    const skylayers::Frame frame = sky.render({.display = true});
    const int w = frame.beauty.width, h = frame.beauty.height;
    if (!stbi_write_png(argv[1], w, h, 4, frame.display.data(), w * 4)) {
      std::fprintf(stderr, "headless: cannot write %s\n", argv[1]);
      return 1;
    }
    const skylayers::Lighting light = sky.lighting();
    std::printf("wrote %s (%dx%d, %.1f ms GPU on %s), sun %.1f deg up\n", argv[1], w, h,
                frame.gpuMs, sky.deviceName().c_str(), light.sun.elevationDeg);
    return 0;
  } catch (const skylayers::Error& e) {
    std::fprintf(stderr, "headless: %s\n", e.what());
    return e.kind() == skylayers::Error::Kind::BadInput ? 2 : 1;
  }
}
