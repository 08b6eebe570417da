// `import skylayers`: the public C++ API (lib/include/skylayers/skylayers.h) for Python, with
// pybind11 (docs/python.md). A frame's images are numpy arrays over the frame's own memory:
// each array's base is the Frame object, which keeps the pixels alive with no copy.
#include <pybind11/eval.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <skylayers/skylayers.h>

namespace py = pybind11;

namespace {

// A scene value as a scene file would write it: text as it is, anything else as JSON (a
// number, true/false, a list: JSON is YAML's subset for these). The scene reader then checks
// it exactly as a file's value.
std::string sceneValue(const py::handle& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  return py::module_::import("json").attr("dumps")(value).cast<std::string>();
}

// Sky(scene): a dict (the scene file's structure), a path (str or os.PathLike) of a .yaml,
// .yml or .json file, YAML text, or None for the built-in default scene.
skylayers::Sky makeSky(const py::object& scene, const std::vector<std::string>& overrides,
                       const skylayers::DeviceOptions& device) {
  if (scene.is_none()) return skylayers::Sky::fromDefault(overrides, device);
  if (py::isinstance<py::dict>(scene)) {
    const std::string json = py::module_::import("json").attr("dumps")(scene).cast<std::string>();
    return skylayers::Sky::fromText(json, "json", "<dict>", overrides, device);
  }
  const py::module_ os = py::module_::import("os");
  if (!py::isinstance<py::str>(scene) && py::hasattr(scene, "__fspath__"))
    return skylayers::Sky::fromFile(os.attr("fspath")(scene).cast<std::string>(), overrides,
                                    device);
  if (!py::isinstance<py::str>(scene))
    throw skylayers::Error(skylayers::Error::Kind::BadInput,
                           "Sky(scene): expected a path, YAML text, a dict or None, not " +
                               py::str(py::type::of(scene).attr("__name__")).cast<std::string>());
  const std::string text = scene.cast<std::string>();
  // One line naming a scene file is a path (a missing one is an error naming it); anything
  // else is the scene's text.
  const bool oneLine = text.find('\n') == std::string::npos;
  const auto endsWith = [&](const char* suffix) {
    const std::string s = suffix;
    return text.size() >= s.size() && text.compare(text.size() - s.size(), s.size(), s) == 0;
  };
  if (oneLine && (endsWith(".yaml") || endsWith(".yml") || endsWith(".json") ||
                  os.attr("path").attr("isfile")(text).cast<bool>()))
    return skylayers::Sky::fromFile(text, overrides, device);
  return skylayers::Sky::fromText(text, "yaml", "<text>", overrides, device);
}

py::dict lightDict(const skylayers::Light& light) {
  py::dict d;
  d["direction"] = py::make_tuple(light.direction[0], light.direction[1], light.direction[2]);
  d["azimuth_deg"] = light.azimuthDeg;
  d["elevation_deg"] = light.elevationDeg;
  d["illuminance_lux"] =
      py::make_tuple(light.illuminanceLux[0], light.illuminanceLux[1], light.illuminanceLux[2]);
  d["cloud_transmittance"] = light.cloudTransmittance;
  return d;
}

py::dict lightingDict(const skylayers::Lighting& lighting) {
  py::dict d;
  d["sun"] = lightDict(lighting.sun);
  d["moon"] = lightDict(lighting.moon);
  d["day_factor"] = lighting.dayFactor;
  d["key"] = lighting.key;
  return d;
}

// A rendered frame: maps layer names to (H, W, C) float32 arrays that share its memory.
class PyFrame {
public:
  explicit PyFrame(skylayers::Frame frame) : mFrame(std::move(frame)) {}

  std::vector<std::string> keys() const {
    std::vector<std::string> names = {"beauty"};
    for (const skylayers::Image& image : mFrame.layers) names.push_back(image.name);
    return names;
  }
  const skylayers::Image* find(const std::string& name) const {
    if (name == "beauty") return &mFrame.beauty;
    for (const skylayers::Image& image : mFrame.layers)
      if (image.name == name) return &image;
    return nullptr;
  }
  const skylayers::Frame& frame() const { return mFrame; }
  skylayers::Frame& frame() { return mFrame; }

private:
  skylayers::Frame mFrame;
};

py::array imageArray(const skylayers::Image& image, py::handle owner) {
  const py::ssize_t h = image.height, w = image.width,
                    c = static_cast<py::ssize_t>(image.channels.size());
  const py::ssize_t f = sizeof(float);
  return py::array_t<float>({h, w, c}, {w * c * f, c * f, f}, image.pixels.data(), owner);
}

// Points given as numpy arrays, converted to float64 and made contiguous as needed.
using PointArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// (..., 3) arrays of (latitude, longitude, altitude m) as points, with their leading shape.
std::vector<skylayers::GeoPoint> geoPoints(const PointArray& a, const char* name,
                                           std::vector<py::ssize_t>& shape) {
  if (a.ndim() < 1 || a.shape(a.ndim() - 1) != 3)
    throw skylayers::Error(skylayers::Error::Kind::BadInput,
                           std::string(name) +
                               ": expected an array of shape (..., 3): latitude, longitude, "
                               "altitude in metres");
  shape.assign(a.shape(), a.shape() + a.ndim() - 1);
  const double* v = a.data();
  std::vector<skylayers::GeoPoint> points(static_cast<size_t>(a.size() / 3));
  for (size_t i = 0; i < points.size(); ++i) points[i] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
  return points;
}

// The lines from a to b of two (..., 3) arrays of the same shape, and that leading shape.
struct Lines {
  std::vector<skylayers::GeoPoint> from, to;
  std::vector<py::ssize_t> shape;
};
Lines geoLines(const PointArray& a, const PointArray& b, const std::string& call) {
  Lines lines;
  std::vector<py::ssize_t> shapeB;
  lines.from = geoPoints(a, (call + " a").c_str(), lines.shape);
  lines.to = geoPoints(b, (call + " b").c_str(), shapeB);
  if (lines.shape != shapeB)
    throw skylayers::Error(skylayers::Error::Kind::BadInput,
                           call + ": a and b must have the same shape");
  return lines;
}

}  // namespace

PYBIND11_MODULE(skylayers, m) {
  m.doc() = "skylayers: real-time sky and cloud rendering from weather data (docs/python.md)";
  m.attr("__version__") = skylayers::version();

  static py::exception<skylayers::Error> error(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const skylayers::Error& e) {
      // One line saying what and where; .kind is "bad_input" (the caller can fix it) or
      // "internal".
      py::object instance = py::reinterpret_borrow<py::object>(error)(py::str(e.what()));
      instance.attr("kind") =
          e.kind() == skylayers::Error::Kind::BadInput ? "bad_input" : "internal";
      PyErr_SetObject(error.ptr(), instance.ptr());
    }
  });

  m.def(
      "irradiance",
      [](const PointArray& sh, std::array<double, 3> normal) {
        if (sh.ndim() != 2 || sh.shape(0) != 9 || sh.shape(1) != 3)
          throw skylayers::Error(skylayers::Error::Kind::BadInput,
                                 "irradiance: expected spherical harmonics of shape (9, 3)");
        skylayers::SphericalHarmonics c;
        for (int i = 0; i < 9; ++i)
          for (int k = 0; k < 3; ++k) c[i][k] = sh.at(i, k);
        const std::array<double, 3> e = skylayers::irradiance(c, normal);
        return py::make_tuple(e[0], e[1], e[2]);
      },
      py::arg("sh"), py::arg("normal"),
      "Illuminance (lux, R, G, B) on a surface with unit normal (east, north, up) under "
      "Sky.ambient()'s radiance.");
  m.def(
      "weather",
      [](const py::object& file, const py::kwargs& keys) {
        std::vector<std::string> overrides;
        for (const auto& [key, value] : keys)
          overrides.push_back(key.cast<std::string>() + "=" + sceneValue(value));
        const std::string path = py::module_::import("os").attr("fspath")(file).cast<std::string>();
        skylayers::WeatherGrid grid;
        {
          py::gil_scoped_release release;
          grid = skylayers::weatherMap(path, overrides);
        }
        py::dict out;
        const skylayers::Image& image = grid.image;
        const size_t n = image.channels.size();
        for (size_t c = 0; c < n; ++c) {
          py::array_t<float> a({py::ssize_t(image.height), py::ssize_t(image.width)});
          float* o = a.mutable_data();
          for (size_t i = 0; i < size_t(image.width) * size_t(image.height); ++i)
            o[i] = image.pixels[i * n + c];
          out[py::str(image.channels[c])] = a;
        }
        py::dict region;
        region["lat"] = py::make_tuple(grid.southDeg, grid.northDeg);
        region["lon"] = py::make_tuple(grid.westDeg, grid.eastDeg);
        out["region"] = region;
        return out;
      },
      py::arg("file"),
      "The cloud map of a GRIB2 or NetCDF forecast file as skyrender weather writes it: a "
      "dict of (H, W) float32 arrays (cover_low, cover_mid, cover_high, type, and each "
      "layer's base and top in m; row 0 north) and 'region'. Scene keys as "
      "**{'weather.region.lat': [0, 55]}.");
  m.def(
      "read_exr",
      [](const py::object& file) {
        const std::string path = py::module_::import("os").attr("fspath")(file).cast<std::string>();
        std::vector<skylayers::Image> images;
        {
          py::gil_scoped_release release;
          images = skylayers::readExr(path);
        }
        py::dict out;
        for (const skylayers::Image& image : images) {
          const size_t n = image.channels.size();
          for (size_t c = 0; c < n; ++c) {
            const std::string& channel = image.channels[c];
            const std::string key = image.name == "beauty" || image.name == channel
                                        ? channel
                                        : image.name + "." + channel;
            py::array_t<float> a({py::ssize_t(image.height), py::ssize_t(image.width)});
            float* o = a.mutable_data();
            for (size_t i = 0; i < size_t(image.width) * size_t(image.height); ++i)
              o[i] = image.pixels[i * n + c];
            out[py::str(key)] = a;
          }
        }
        return out;
      },
      py::arg("file"),
      "The channels of an EXR that skyrender or a dataset wrote, by their names in the file: "
      "a dict of (H, W) float32 arrays ('R', 'G', 'B', 'A', 'label', 'cloud_type', "
      "'clouds.optical_depth', 'air.transmittance', ...; docs/outputs.md).");
  // A dataset's manifest (docs/datasets.md): plain JSON Lines, read in Python.
  py::exec(R"py(
def read_manifest(folder):
    """A dataset's samples, by index: the lines of FOLDER/manifest.jsonl (a merged or an
    unsharded run's), or, where there is none yet, of its shard manifests
    (manifest.I-of-N.jsonl) joined. Each is a dict: index, scene, sun_elevation_deg, cover,
    labels, visibility_m, sun_visible, files (name and sha256 of the exr, png and scene). A
    last line a killed run left unfinished is not a sample."""
    import glob, json, os, re
    folder = os.fspath(folder)
    merged = os.path.join(folder, "manifest.jsonl")
    if os.path.exists(merged):
        paths = [merged]
    else:
        paths = sorted(p for p in glob.glob(os.path.join(folder, "manifest.*.jsonl"))
                       if re.fullmatch(r"manifest\.[0-9]+-of-[0-9]+\.jsonl", os.path.basename(p)))
    if not paths:
        raise Error("%s: no dataset manifest (manifest.jsonl or manifest.I-of-N.jsonl)" % folder)
    samples = {}
    for path in paths:
        with open(path, encoding="utf-8") as f:
            text = f.read()
        lines = text.split("\n")
        for number, line in enumerate(lines[:-1], 1):  # the last piece has no newline
            if line.strip():
                try:
                    sample = json.loads(line)
                except ValueError as e:
                    raise Error("%s:%d: not a JSON line: %s" % (path, number, e))
                samples.setdefault(sample["index"], sample)
    return [samples[k] for k in sorted(samples)]
)py", m.attr("__dict__"));

  m.def("data_directory", &skylayers::dataDirectory,
        "The folder the shaders and configs are read from.");
  m.def(
      "ephemeris",
      [](double lat, double lon, const std::string& time, double altitudeM) {
        return lightingDict(skylayers::lightingAt(lat, lon, altitudeM, time));
      },
      py::arg("lat"), py::arg("lon"), py::arg("time"), py::arg("altitude_m") = 0.0,
      "The sun and moon at a place and ISO 8601 instant (no GPU): direction (east, north, up), "
      "azimuth, apparent elevation, illuminance in lux per linear Rec.709 channel, the "
      "day factor and the key light.");

  py::class_<PyFrame>(m, "Frame",
                      "A rendered frame: frame['beauty'] and the other layers as float32 "
                      "(H, W, C) arrays sharing the frame's memory.")
      .def("keys", &PyFrame::keys)
      .def("__iter__", [](const PyFrame& f) { return py::iter(py::cast(f.keys())); })
      .def("__len__", [](const PyFrame& f) { return f.keys().size(); })
      .def("__contains__",
           [](const PyFrame& f, const std::string& name) { return f.find(name) != nullptr; })
      .def("__getitem__",
           [](py::object self, const std::string& name) {
             const PyFrame& f = self.cast<const PyFrame&>();
             const skylayers::Image* image = f.find(name);
             if (!image) throw py::key_error("the frame has no layer '" + name + "'");
             return imageArray(*image, self);
           })
      .def("channels",
           [](const PyFrame& f, const std::string& name) {
             const skylayers::Image* image = f.find(name);
             if (!image) throw py::key_error("the frame has no layer '" + name + "'");
             return image->channels;
           })
      .def_property_readonly(
          "display",
          [](py::object self) -> py::object {
            const skylayers::Frame& f = self.cast<const PyFrame&>().frame();
            if (f.display.empty()) return py::none();
            const py::ssize_t h = f.beauty.height, w = f.beauty.width;
            return py::array_t<uint8_t>({h, w, py::ssize_t(4)},
                                        {w * 4, py::ssize_t(4), py::ssize_t(1)}, f.display.data(),
                                        self);
          },
          "The display image, (H, W, 4) uint8: the codes of skyrender's PNG.")
      .def_property_readonly(
          "report",
          [](const PyFrame& f) {
            return py::module_::import("json").attr("loads")(f.frame().report);
          },
          "The render report as a dict (docs/outputs.md).")
      .def_property_readonly("time", [](const PyFrame& f) { return f.frame().time; })
      .def_property_readonly("gpu_ms", [](const PyFrame& f) { return f.frame().gpuMs; })
      .def_property_readonly("exposure_ev", [](const PyFrame& f) { return f.frame().exposureEv; });

  py::class_<skylayers::Sky>(m, "Sky",
                             "A scene and everything made for it on the GPU; render many frames "
                             "through one Sky.")
      .def(py::init([](const py::object& scene, const std::string& gpu, bool validation,
                       const std::string& ocio) {
             skylayers::DeviceOptions device;
             device.gpu = gpu;
             device.validation = validation;
             device.ocioConfig = ocio;
             return makeSky(scene, {}, device);
           }),
           py::arg("scene") = py::none(), py::kw_only(), py::arg("gpu") = "",
           py::arg("validation") = false, py::arg("ocio") = "",
           "scene: a path, YAML text, a dict with the scene file's structure, or None for the "
           "built-in scene. gpu: '' picks one, else an index or part of a name.")
      .def(
          "set",
          [](skylayers::Sky& sky, const std::string& key, const py::handle& value) {
            sky.set(key, sceneValue(value));
          },
          py::arg("key"), py::arg("value"),
          "Sets a scene key by its path, e.g. set('camera.heading', 305); checked as a scene "
          "file is. A bad key or value raises skylayers.Error and keeps the scene.")
      .def(
          "render",
          [](skylayers::Sky& sky, std::optional<int> width, std::optional<int> height,
             std::optional<std::string> time, bool display, const py::kwargs& keys) {
            std::vector<std::string> assignments;
            if (width) assignments.push_back("output.width=" + std::to_string(*width));
            if (height) assignments.push_back("output.height=" + std::to_string(*height));
            if (time) assignments.push_back("time=" + *time);
            for (const auto& [key, value] : keys)
              assignments.push_back(key.cast<std::string>() + "=" + sceneValue(value));
            if (!assignments.empty()) sky.set(assignments);
            skylayers::Frame frame;
            {
              py::gil_scoped_release release;
              frame = sky.render({.layers = true, .display = display});
            }
            return PyFrame(std::move(frame));
          },
          py::arg("width") = py::none(), py::arg("height") = py::none(),
          py::arg("time") = py::none(), py::kw_only(), py::arg("display") = true,
          "Renders a frame. width, height, time and any scene keys given as "
          "**{'key.path': value} are set first (and stay set).")
      .def(
          "render_views",
          [](skylayers::Sky& sky, const std::vector<py::dict>& given, bool display) {
            std::vector<skylayers::View> views;
            for (size_t i = 0; i < given.size(); ++i) {
              const py::dict& d = given[i];
              for (const auto& [key, value] : d) {
                const std::string k = key.cast<std::string>();
                if (k != "heading" && k != "pitch" && k != "roll" && k != "vertical_fov" &&
                    k != "width" && k != "height")
                  throw skylayers::Error(
                      skylayers::Error::Kind::BadInput,
                      "render_views: view " + std::to_string(i) + ": unknown key '" + k +
                          "' (heading, pitch, roll, vertical_fov, width, height)");
              }
              const auto number = [&](const char* k, double fallback) {
                return d.contains(k) ? d[k].cast<double>() : fallback;
              };
              skylayers::View v;
              v.headingDeg = number("heading", 0.0);
              v.pitchDeg = number("pitch", 0.0);
              v.rollDeg = number("roll", 0.0);
              v.verticalFovDeg = number("vertical_fov", 60.0);
              v.width = d.contains("width") ? d["width"].cast<int>() : 0;
              v.height = d.contains("height") ? d["height"].cast<int>() : 0;
              views.push_back(v);
            }
            std::vector<skylayers::Frame> frames;
            {
              py::gil_scoped_release release;
              frames = sky.renderViews(views, {.layers = true, .display = display});
            }
            std::vector<PyFrame> out;
            for (skylayers::Frame& f : frames) out.emplace_back(std::move(f));
            return out;
          },
          py::arg("views"), py::kw_only(), py::arg("display") = true,
          "Several cameras at the Sky's camera place in one frame (one GPU submit): views is a "
          "list of dicts with heading, pitch, roll, vertical_fov (degrees), width and height. "
          "Returns one Frame per view, each the frame render() gives for that camera.")
      .def(
          "lighting",
          [](const skylayers::Sky& sky, std::optional<std::string> time,
             std::optional<std::tuple<double, double, double>> position) {
            const std::string at = time.value_or(sky.time());
            if (position) {
              const auto [lat, lon, alt] = *position;
              return lightingDict(sky.lighting(at, lat, lon, alt));
            }
            return lightingDict(time ? sky.lighting(at) : sky.lighting());
          },
          py::arg("time") = py::none(), py::arg("position") = py::none(),
          "The sun and moon at the camera (or position=(lat, lon, altitude_m)) and the scene's "
          "time (or time=ISO 8601), as a dict; the Sky's own time and camera stay.")
      .def(
          "transmittance",
          [](skylayers::Sky& sky, const PointArray& a, const PointArray& b,
             const std::string& through, bool rgb) {
            const Lines given = geoLines(a, b, "transmittance");
            if (through != "all" && through != "cloud" && through != "air")
              throw skylayers::Error(
                  skylayers::Error::Kind::BadInput,
                  "transmittance: through='" + through + "': expected 'all', 'cloud' or 'air'");
            std::vector<std::array<skylayers::GeoPoint, 2>> lines(given.from.size());
            for (size_t i = 0; i < lines.size(); ++i) lines[i] = {given.from[i], given.to[i]};
            std::vector<skylayers::Transmittance> t;
            {
              py::gil_scoped_release release;
              t = sky.transmittance(lines);
            }
            std::vector<py::ssize_t> shape = given.shape;
            if (rgb) shape.push_back(3);
            py::array_t<double> out(shape);
            double* o = out.mutable_data();
            for (size_t i = 0; i < t.size(); ++i) {
              std::array<double, 3> v =
                  through == "cloud" ? std::array<double, 3>{t[i].cloud, t[i].cloud, t[i].cloud}
                  : through == "air" ? t[i].air
                                     : t[i].total();
              if (rgb)
                for (int c = 0; c < 3; ++c) o[3 * i + c] = v[c];
              else  // Rec.709 luminance weights
                o[i] = 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2];
            }
            return out;
          },
          py::arg("a"), py::arg("b"), py::kw_only(), py::arg("through") = "all",
          py::arg("rgb") = false,
          "Transmittance along straight lines from a to b, arrays of shape (..., 3) of "
          "(latitude, longitude, altitude m): shape (...), or (..., 3) with rgb=True. "
          "through='cloud' or 'air' for one medium alone; the air's is weighted by Rec.709 "
          "luminance unless rgb. On the CPU, from the field the GPU marches.")
      .def(
          "first_cloud",
          [](skylayers::Sky& sky, const PointArray& a, const PointArray& b, double opticalDepth) {
            const Lines lines = geoLines(a, b, "first_cloud");
            const std::vector<skylayers::GeoPoint>& from = lines.from;
            const std::vector<skylayers::GeoPoint>& to = lines.to;
            py::array_t<double> out(lines.shape);
            double* o = out.mutable_data();
            for (size_t i = 0; i < from.size(); ++i) {
              const double d = sky.firstCloud(from[i], to[i], opticalDepth);
              o[i] = d < 0.0 ? std::numeric_limits<double>::quiet_NaN() : d;
            }
            return out;
          },
          py::arg("a"), py::arg("b"), py::arg("optical_depth") = 0.1,
          "Metres from a toward b at which the cloud optical depth passes optical_depth; NaN "
          "where it does not before b.")
      .def(
          "cloud_extinction",
          [](skylayers::Sky& sky, const PointArray& p) {
            std::vector<py::ssize_t> shape;
            const std::vector<skylayers::GeoPoint> points = geoPoints(p, "cloud_extinction", shape);
            py::array_t<double> out(shape);
            double* o = out.mutable_data();
            for (size_t i = 0; i < points.size(); ++i) o[i] = sky.cloudExtinction(points[i]);
            return out;
          },
          py::arg("points"), "Extinction through cloud (1/m) at points of shape (..., 3).")
      .def(
          "cover",
          [](skylayers::Sky& sky, double lat, double lon) {
            const skylayers::CloudCover c = sky.cover(lat, lon);
            py::dict d;
            d["low"] = c.low;
            d["mid"] = c.mid;
            d["type"] = c.type;
            return d;
          },
          py::arg("lat"), py::arg("lon"), "The weather map's low and mid cover and type there.")
      .def(
          "pixel_point",
          [](const skylayers::Sky& sky, double x, double y, double distance) {
            const skylayers::GeoPoint p = sky.pixelPoint(x, y, distance);
            return py::make_tuple(p.latitudeDeg, p.longitudeDeg, p.altitudeM);
          },
          py::arg("x"), py::arg("y"), py::arg("distance_m"),
          "(lat, lon, altitude m) distance_m along the camera's ray through pixel (x, y).")
      .def(
          "ambient",
          [](skylayers::Sky& sky) {
            skylayers::SphericalHarmonics sh;
            {
              py::gil_scoped_release release;
              sh = sky.ambient();
            }
            py::array_t<double> out({py::ssize_t(9), py::ssize_t(3)});
            for (int i = 0; i < 9; ++i)
              for (int c = 0; c < 3; ++c) out.mutable_at(i, c) = sh[i][c];
            return out;
          },
          "The light around the camera without the sun's and moon's discs: (9, 3) spherical "
          "harmonic coefficients of the radiance in cd/m^2 (docs/library.md). Renders the "
          "sphere at 64 x 32.")
      .def("set_camera_axes", &skylayers::Sky::setCameraAxes, py::arg("forward"), py::arg("up"),
           "Points the camera along `forward` with `up` (east, north, up vectors, e.g. the "
           "columns of a host's camera matrix): sets camera.heading, pitch and roll.")
      .def("set_camera_ecef", &skylayers::Sky::setCameraEcef, py::arg("position"),
           py::arg("forward"), py::arg("up"),
           "Places the camera from an Earth-centred, Earth-fixed pose (WGS84, metres): its "
           "position and its forward and up vectors in ECEF. Sets camera.latitude, longitude, "
           "altitude_m (height above the ellipsoid), heading, pitch and roll.")
      .def(
          "set_projection_matrix",
          [](skylayers::Sky& sky, const PointArray& matrix) {
            if (matrix.ndim() != 2 || matrix.shape(0) != 4 || matrix.shape(1) != 4)
              throw skylayers::Error(skylayers::Error::Kind::BadInput,
                                     "set_projection_matrix: expected a (4, 4) matrix");
            std::array<double, 16> columnMajor;
            for (int c = 0; c < 4; ++c)
              for (int r = 0; r < 4; ++r) columnMajor[size_t(c * 4 + r)] = matrix.at(r, c);
            sky.setProjectionMatrix(columnMajor);
          },
          py::arg("matrix"),
          "The vertical field of view from a symmetric perspective matrix, (4, 4) indexed "
          "[row, column] as written in maths (OpenGL or Vulkan clip conventions).")
      .def("scene_yaml", &skylayers::Sky::sceneYaml, "The effective scene as YAML.")
      .def_property_readonly("time", &skylayers::Sky::time)
      .def_property_readonly("device_name", &skylayers::Sky::deviceName)
      .def_property_readonly("validation_messages", &skylayers::Sky::validationMessages)
      .def_property_readonly("camera", [](const skylayers::Sky& sky) {
        const skylayers::GeoPose p = sky.camera();
        py::dict d;
        d["latitude"] = p.latitudeDeg;
        d["longitude"] = p.longitudeDeg;
        d["altitude_m"] = p.altitudeM;
        d["heading"] = p.headingDeg;
        d["pitch"] = p.pitchDeg;
        d["roll"] = p.rollDeg;
        return d;
      });
}
