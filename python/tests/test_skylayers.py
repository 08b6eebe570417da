"""`import skylayers` as a script uses it (docs/python.md): scenes from a path, text or a
dict; keys set by path; frames as numpy arrays over the frame's memory; lights; errors."""
import math
import os
import sys

import numpy as np
import pytest

import skylayers


def test_a_render_gives_the_layers_as_arrays(small_sky):
    frame = small_sky.render()
    assert frame.keys() == ["beauty", "sky", "high_clouds", "clouds"]
    beauty = frame["beauty"]
    assert beauty.dtype == np.float32 and beauty.shape == (18, 32, 4)
    assert np.isfinite(beauty).all() and beauty[..., :3].max() > 0
    assert frame["clouds"].shape == (18, 32, 5)
    assert frame.channels("clouds") == ["R", "G", "B", "A", "depth"]
    assert frame.display.dtype == np.uint8 and frame.display.shape == (18, 32, 4)
    assert (frame.display[..., 3] == 255).all()
    assert frame.report["size"] == [32, 18]
    assert [p["name"] for p in frame.report["passes"]]
    with pytest.raises(KeyError):
        frame["nonsense"]


def test_arrays_share_the_frames_memory_and_keep_it_alive(small_sky):
    frame = small_sky.render()
    a = frame["beauty"]
    b = frame["beauty"]
    # No copy: both views are the same memory, owned by the frame.
    assert a.__array_interface__["data"][0] == b.__array_interface__["data"][0]
    assert not a.flags["OWNDATA"]
    expected = a.copy()
    del frame, b
    for _ in range(3):
        small_sky.render()  # would reuse freed memory if the array did not hold the frame
    assert np.array_equal(a, expected)
    assert sys.getrefcount(a.base) >= 2


def test_the_same_scene_gives_the_same_bits(small_sky):
    first = small_sky.render()["beauty"].copy()
    again = small_sky.render()["beauty"]
    assert np.array_equal(first, again)


def test_render_sets_size_time_and_keys(small_sky):
    frame = small_sky.render(width=20, height=10, time="2024-06-21T20:00:00+02:00",
                             **{"camera.heading": 300, "weather.cover_low": 0.2})
    assert frame["beauty"].shape == (10, 20, 4)
    assert frame.time == "2024-06-21T20:00:00+02:00"
    assert small_sky.camera["heading"] == 300
    assert "cover_low: 0.2" in small_sky.scene_yaml()


def test_a_scene_from_a_dict_text_or_path(tmp_path):
    scene = {"output": {"width": 16, "height": 8}, "camera": {"heading": 90, "pitch": 20}}
    sky = skylayers.Sky(scene)
    assert sky.camera["heading"] == 90
    text = sky.scene_yaml()
    assert skylayers.Sky(text).camera["pitch"] == 20
    path = tmp_path / "scene.yaml"
    path.write_text(text)
    assert skylayers.Sky(path).camera["heading"] == 90
    assert skylayers.Sky(str(path)).render()["beauty"].shape == (8, 16, 4)


def test_bad_input_is_one_line_naming_it_and_keeps_the_scene(small_sky):
    before = small_sky.scene_yaml()
    with pytest.raises(skylayers.Error) as e:
        small_sky.set("camera.latitud", 10)
    assert e.value.kind == "bad_input"
    assert "set camera.latitud=10: unknown key" in str(e.value)
    assert "\n" not in str(e.value)
    with pytest.raises(skylayers.Error, match="camera.pitch"):
        small_sky.set("camera.pitch", float("nan"))
    with pytest.raises(skylayers.Error):
        small_sky.render(**{"camera.latitude": 95})
    assert small_sky.scene_yaml() == before
    with pytest.raises(skylayers.Error, match="nonexistent"):
        skylayers.Sky("/nonexistent/scene.yaml")
    with pytest.raises(skylayers.Error):
        skylayers.Sky(42)


def test_lighting_and_ephemeris_in_lux():
    # Zurich at midsummer noon: the sun 66 degrees up, direct light 70-120 klux.
    noon = skylayers.ephemeris(47.37, 8.54, "2024-06-21T13:30:00+02:00", altitude_m=500)
    assert noon["key"] == "sun" and noon["day_factor"] == pytest.approx(1.0)
    assert noon["sun"]["elevation_deg"] == pytest.approx(90 - 47.37 + 23.44, abs=0.5)
    assert all(70e3 < e < 120e3 for e in noon["sun"]["illuminance_lux"])
    d = noon["sun"]["direction"]
    assert math.degrees(math.asin(d[2])) == pytest.approx(noon["sun"]["elevation_deg"])
    night = skylayers.ephemeris(47.37, 8.54, "2024-06-22T02:00:00+02:00")
    assert night["key"] == "moon" and night["sun"]["illuminance_lux"] == (0.0, 0.0, 0.0)


def test_a_skys_lighting_elsewhere_leaves_it_as_it_was(small_sky):
    here = small_sky.lighting()
    sydney = small_sky.lighting(time="2024-06-21T12:00:00+10:00", position=(-33.86, 151.21, 0))
    assert sydney["sun"]["elevation_deg"] == pytest.approx(90 - 33.86 - 23.44, abs=0.5)
    assert small_sky.lighting() == here


def test_the_module_says_where_its_data_is():
    assert skylayers.__version__ == "0.1.0"
    assert os.path.samefile(skylayers.data_directory(), os.environ["SKY_DATA_DIR"])


def test_line_of_sight_queries_through_the_clouds(small_sky):
    cam = small_sky.camera
    lats = cam["latitude"] + 0.005 * np.arange(40)
    a = np.stack([lats, np.full(40, cam["longitude"]), np.full(40, 1000.0)], axis=-1)
    b = a.copy()
    b[:, 2] = 4000.0  # straight up through the low layer
    cloud = small_sky.transmittance(a, b, through="cloud")
    assert cloud.shape == (40,)
    assert (cloud < 0.4).any() and (cloud == 1.0).any()
    rgb = small_sky.transmittance(a, b, rgb=True)
    assert rgb.shape == (40, 3) and (rgb[:, 2] <= rgb[:, 0]).all()  # the air dims blue most
    assert np.allclose(small_sky.transmittance(a, b), cloud * small_sky.transmittance(
        a, b, through="air"), rtol=1e-3)
    d = small_sky.first_cloud(a, b)
    assert np.isnan(d[cloud == 1.0]).all() and (d[cloud < 0.4] > 0).all()
    assert small_sky.transmittance(a.reshape(4, 10, 3), b.reshape(4, 10, 3)).shape == (4, 10)
    ext = small_sky.cloud_extinction(a + [0, 0, 1000.0])
    assert ext.shape == (40,) and (ext >= 0).all()
    assert small_sky.cover(cam["latitude"], cam["longitude"])["low"] >= 0.0
    lat, lon, alt = small_sky.pixel_point(16, 9, 1000.0)
    assert alt > cam["altitude_m"]  # the default camera looks up
    with pytest.raises(skylayers.Error, match="shape"):
        small_sky.transmittance(a[:, :2], b[:, :2])


def test_the_ambient_light_as_spherical_harmonics(small_sky):
    small_sky.set("time", "2024-06-21T13:30:00+02:00")
    small_sky.set("weather.cover_low", 0)
    small_sky.set("high_clouds.cover", 0)
    sh = small_sky.ambient()
    assert sh.shape == (9, 3)
    up = skylayers.irradiance(sh, (0, 0, 1))
    assert all(5e3 < e < 3e4 for e in up) and up[2] > up[0]
    with pytest.raises(skylayers.Error, match="9, 3"):
        skylayers.irradiance(sh[:4], (0, 0, 1))


def test_a_forecasts_cloud_map_as_arrays():
    grib = os.path.join(os.environ["SKY_DATA_DIR"],
                        "tests/data/weather/gfs_2p5deg_r_gh_t_tcc_uv500.grib2")
    m = skylayers.weather(grib, **{"weather.region.lat": [0, 55], "weather.region.lon": [90, 150]})
    assert m["region"] == {"lat": (0.0, 55.0), "lon": (90.0, 150.0)}
    low = m["cover_low"]
    assert low.dtype == np.float32 and low.ndim == 2 and low.shape == m["low_top_m"].shape
    assert 0.0 <= low.min() and low.max() <= 1.0 and low.max() > 0.1
    assert (m["low_top_m"] >= m["low_base_m"]).all()
    with pytest.raises(skylayers.Error, match="nonexistent"):
        skylayers.weather("/nonexistent/forecast.grib2")


def test_a_hosts_camera_axes_and_projection_matrix(small_sky):
    # Looking east, level, banked 20 degrees right; then a 50 degree perspective matrix.
    r = math.radians(20)
    small_sky.set_camera_axes((1, 0, 0), (0, -math.sin(r), math.cos(r)))
    cam = small_sky.camera
    assert cam["heading"] == pytest.approx(90) and cam["pitch"] == pytest.approx(0)
    assert cam["roll"] == pytest.approx(20)
    f = 1 / math.tan(math.radians(25))
    m = np.zeros((4, 4))
    m[0, 0], m[1, 1], m[2, 2], m[2, 3], m[3, 2] = f * 18 / 32, f, -1.0, -0.2, -1.0
    small_sky.set_projection_matrix(m)
    assert "vertical_fov: 50" in small_sky.scene_yaml()
    with pytest.raises(skylayers.Error, match="4, 4"):
        small_sky.set_projection_matrix(np.eye(3))


def test_an_ecef_pose(small_sky):
    # 1500 m above the ellipsoid at 0N 90E, looking north and 10 degrees up, level.
    p = math.radians(10)
    small_sky.set_camera_ecef((0, 6378137.0 + 1500.0, 0), (0, math.sin(p), math.cos(p)),
                              (0, math.cos(p), -math.sin(p)))
    cam = small_sky.camera
    assert cam["latitude"] == pytest.approx(0, abs=1e-9)
    assert cam["longitude"] == pytest.approx(90)
    assert cam["altitude_m"] == pytest.approx(1500, abs=1e-3)
    assert cam["heading"] == pytest.approx(0, abs=1e-9)
    assert cam["pitch"] == pytest.approx(10) and cam["roll"] == pytest.approx(0, abs=1e-9)
    with pytest.raises(skylayers.Error, match="not near the Earth's surface"):
        small_sky.set_camera_ecef((0, 0, 0), (1, 0, 0), (0, 0, 1))


def test_a_rig_of_views_in_one_frame_is_each_views_own_render(small_sky):
    views = [{"heading": 280, "pitch": 5, "width": 32, "height": 18},
             {"heading": 10, "pitch": 20, "roll": 10, "vertical_fov": 40, "width": 16,
              "height": 16}]
    frames = small_sky.render_views(views, display=False)
    assert [f["beauty"].shape for f in frames] == [(18, 32, 4), (16, 16, 4)]
    small_sky.set("camera.heading", 10)
    small_sky.set("camera.pitch", 20)
    small_sky.set("camera.roll", 10)
    alone = small_sky.render(16, 16, display=False, **{"camera.vertical_fov": 40})
    assert np.array_equal(frames[1]["beauty"], alone["beauty"])
    with pytest.raises(skylayers.Error, match="view 0: unknown key 'fov'"):
        small_sky.render_views([{"fov": 30, "width": 8, "height": 8}])


def test_the_perception_layers_as_arrays(small_sky):
    small_sky.set("output.perception", True)
    frame = small_sky.render()
    assert {"label", "cloud_type", "air", "ground"} <= set(frame.keys())
    label = frame["label"][..., 0]
    assert label.shape == (18, 32)
    assert set(np.unique(label)) <= set(range(7))
    assert (label == 1).any(), "the built-in scene shows the ground"
    assert frame.channels("clouds")[-2:] == ["optical_depth", "distance"]
    shares = frame.report["perception"]["label_shares"]
    assert math.isclose(shares["ground"], float((label == 1).mean()), abs_tol=1e-9)


def test_a_datasets_manifest_and_samples(tmp_path):
    import hashlib
    import subprocess
    spec = tmp_path / "spec.yaml"
    spec.write_text("count: 2\nseed: 5\noutput: {width: 16, height: 9}\n"
                    "camera: {heading: [0, 360]}\n")
    out = tmp_path / "ds"
    subprocess.run([os.environ["SKY_SKYRENDER"], "dataset", str(spec), "--out", str(out),
                    "--shard", "2/2"], check=True, capture_output=True)
    # One shard of two, not merged yet: its manifest alone.
    samples = skylayers.read_manifest(out)
    assert [s["index"] for s in samples] == [1]
    subprocess.run([os.environ["SKY_SKYRENDER"], "dataset", str(spec), "--out", str(out),
                    "--shard", "1/2"], check=True, capture_output=True)
    with open(out / "manifest.1-of-2.jsonl", "a") as f:
        f.write('{"index": 7, "co')  # a line a killed run left unfinished
    samples = skylayers.read_manifest(out)
    assert [s["index"] for s in samples] == [0, 1]
    s = samples[1]
    exr = out / s["files"]["exr"]["name"]
    assert hashlib.sha256(exr.read_bytes()).hexdigest() == s["files"]["exr"]["sha256"]
    layers = skylayers.read_exr(exr)
    assert {"R", "G", "B", "A", "label", "cloud_type", "clouds.optical_depth",
            "air.transmittance", "ground.cloud_shadow"} <= set(layers)
    assert layers["label"].shape == (9, 16)
    assert math.isclose(s["labels"]["ground"], float((layers["label"] == 1).mean()), abs_tol=1e-9)
    with pytest.raises(skylayers.Error):
        skylayers.read_manifest(tmp_path)
