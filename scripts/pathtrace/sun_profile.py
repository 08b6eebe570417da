#!/usr/bin/python3
"""The sun's light across a cloud layer for the path tracer (render_cycles.py): the lamp's
illuminance and the sheets of air that give it the raymarch's profile in altitude.

The raymarch lights each cloud sample with the sun's light through the air down to the
sample's own altitude (volumetric_clouds.comp keyLightAt: log E quadratic through the layer's
base, middle and top, which export-volume writes as sun_illuminance_{low,mid}_{base,middle,top}).
A low sun makes it much dimmer and redder at a layer's base than at its top (3 degrees up: a
third of the middle's at the base in green, 1.7 times at the top). Cycles' sun lamp has one
illuminance everywhere; render_cycles.py gives it this profile with absorbing sheets of air.

    /usr/bin/python3 scripts/pathtrace/sun_profile.py --check      # the self-test (ctest)
    /usr/bin/python3 scripts/pathtrace/sun_profile.py EXPORT.vdb   # an export's sheets
"""
import argparse
import math
import sys

LAYER_LEVELS = ("base", "middle", "top")
SHEET_STEP = 0.07   # the most log E any sheet takes in any channel: the light within 3.5 %
SHEET_GRAIN = 256   # a layer's altitudes, in this many parts, are gathered into sheets
SHEET_M = 1.0


def layer_log_light(m, layer):
    """log E of the sun's light across a layer, as the raymarch takes it (volumetric_clouds.comp
    keyLightAt): quadratic in the layer's fraction f through its base, middle and top."""
    b, mid, t = ([math.log(max(c, 1e-30)) for c in m[f"sun_illuminance_{layer}_{k}"]]
                 for k in LAYER_LEVELS)
    base, top = float(m[f"{layer}_base_m"]), float(m[f"{layer}_top_m"])

    def log_e(altitude):
        f = min(max((altitude - base) / max(top - base, 1.0), 0.0), 1.0)
        return [bb * 2.0 * (f - 0.5) * (f - 1.0) - mm * 4.0 * f * (f - 1.0) + tt * 2.0 * f * (f - 0.5)
                for bb, mm, tt in zip(b, mid, t)]
    return base, top, log_e


def sun_profile(m, metas, flat):
    """The sun lamp's illuminance and the sheets of air that give its light the raymarch's
    profile in altitude: [(z0, z1, sigma RGB per metre)] in the grid's frame.

    The raymarch lights each sample with the sun's light at the sample's own altitude, which a
    low sun makes much dimmer and redder at a layer's base than at its top (3 degrees up: a
    third of the middle's at the base in green, 1.7 times at the top); a sun lamp has one
    illuminance everywhere. So the lamp takes the light at the top of the highest layer the
    export reaches into, and thin horizontal sheets of air absorb it on the way down: the
    layer cut into intervals over which log E rises by SHEET_STEP in its fastest channel, each
    with a sheet SHEET_M thick at its middle whose optical depth along the sun's slanted path
    is log E(top of the interval) - log E(its bottom). A sample below a sheet gets the light
    through it, so the light at every altitude is the raymarch's within half a step (a
    staircase about the profile): 40 sheets for a 3 degree sun's low layer, 4 at noon.
    Only shadow rays see the sheets (render_cycles.py: their objects are visible to shadow
    rays alone, and the sun lamp has no multiple importance sampling), so the sheets dim
    nothing but the sun's own rays: a camera ray or one scattered inside the cloud crosses no
    sheet, which also keeps them from costing the paths a boundary crossing each. A sample
    inside a sheet (1 m in 60) misses that sheet. The world's shadow rays would cross them
    too, and Cycles without the world's importance sampling loses half the sky light in a
    volume (measured: 0.090 against 0.193 on cumulus_sun3_away), so with both lights the sun
    and the sky are rendered apart, each with all the samples, and added (render_cycles.py):
    light is additive.
    flat, an export from before the per-layer levels, or a sun at or below the horizon: the
    middle's light, no sheets."""
    e_mid = [float(c) for c in m["sun_illuminance"]]
    levels = [f"sun_illuminance_{l}_{k}" for l in ("low", "mid") for k in LAYER_LEVELS]
    sin_e = math.sin(math.radians(float(m["sun_elevation_deg"])))
    if flat or sin_e <= 0.0 or any(k not in m for k in levels):
        return e_mid, []
    camera = float(m["camera_altitude_m"])
    highest = max(camera + float(g["box_max_m"][2]) for g in metas)
    lb, lt, low = layer_log_light(m, "low")
    mb, mt, mid = layer_log_light(m, "mid")

    def log_at(altitude):
        if altitude <= lt:
            return low(altitude)
        if altitude >= mb:
            return mid(altitude)
        a, b = low(lt), mid(mb)   # between the layers: log E linear
        f = (altitude - lt) / max(mb - lt, 1.0)
        return [x + f * (y - x) for x, y in zip(a, b)]
    # No cloud lies between the layers, so a box that stops short of the mid layer needs only
    # the low one.
    spans = [(lb, lt)] if highest <= mb else [(lb, lt), (lt, mb), (mb, mt)]
    sheets = []
    for z0, z1 in spans:
        a = z0
        for k in range(1, SHEET_GRAIN + 1):
            b = z0 + (z1 - z0) * k / SHEET_GRAIN
            rise = [y - x for x, y in zip(log_at(a), log_at(b))]
            if max(rise) < SHEET_STEP and k < SHEET_GRAIN:
                continue
            if max(rise) > 0.0:
                centre = 0.5 * (a + b) - camera
                sheets.append((centre - 0.5 * SHEET_M, centre + 0.5 * SHEET_M,
                               [max(0.0, sin_e * r / SHEET_M) for r in rise]))
            a = b
    top = [math.exp(c) for c in log_at(spans[-1][1])]
    return top, sheets


def slant_light(top, sheets, z, sin_e):
    """The light the sheets leave at z (the grid's frame): the lamp's, dimmed along the sun's
    slanted path up through every sheet above z."""
    tau = [0.0, 0.0, 0.0]
    for z0, z1, sigma in sheets:
        inside = max(0.0, z1 - max(z0, z))
        for c in range(3):
            tau[c] += sigma[c] * inside / sin_e
    return [t * math.exp(-x) for t, x in zip(top, tau)]


def synthetic_metadata():
    """An export's light at a 3 degree sun over layers of 500-2500 and 3000-6500 m (the values
    export-volume wrote for configs/pathtrace/cumulus_sun3_away.yaml)."""
    m = {"sun_elevation_deg": 3.0, "camera_altitude_m": 2.0, "sun_illuminance": (0.7537, 0.3560, 0.0726),
         "low_base_m": 500.0, "low_top_m": 2500.0, "mid_base_m": 3000.0, "mid_top_m": 6500.0}
    levels = {"low": ((0.3422, 0.1253, 0.0117), (0.7537, 0.3560, 0.0726), (1.0982, 0.6050, 0.1781)),
              "mid": ((1.2279, 0.7159, 0.2395), (1.5203, 1.0244, 0.4721), (1.6848, 1.2573, 0.7236))}
    for layer, values in levels.items():
        for level, v in zip(LAYER_LEVELS, values):
            m[f"sun_illuminance_{layer}_{level}"] = v
    return m


def check():
    """The sheets give the raymarch's light at every altitude of the layers they cover within
    half a step (5 %; a staircase about its log-quadratic profile) and its mean
    over each layer within 1 %, no two touch, and flat or a sun below the horizon gives the
    middle's light and no sheets."""
    m = synthetic_metadata()
    sin_e = math.sin(math.radians(m["sun_elevation_deg"]))
    failures = []
    for box_top, layers in ((2548.0, ("low",)), (6000.0, ("low", "mid"))):
        metas = [{"box_min_m": (-2000.0, 4770.0, 448.0), "box_max_m": (2000.0, 8570.0, box_top)}]
        top, sheets = sun_profile(m, metas, False)
        if not 20 * len(layers) <= len(sheets) <= 60 * len(layers):
            failures.append(f"box top {box_top}: {len(sheets)} sheets for {len(layers)} layers")
        for (_, a1, _), (b0, _, _) in zip(sheets, sheets[1:]):
            if not b0 > a1:
                failures.append(f"sheets touch at {a1} m")
        for layer in layers:
            base, height, log_e = layer_log_light(m, layer)
            sums = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
            for k in range(1001):
                altitude = base + (height - base) * k / 1000.0
                got = slant_light(top, sheets, altitude - m["camera_altitude_m"], sin_e)
                want = [math.exp(c) for c in log_e(altitude)]
                for c in range(3):
                    sums[0][c] += got[c]
                    sums[1][c] += want[c]
                    if abs(got[c] / want[c] - 1.0) > 0.05:
                        failures.append(f"{layer} at {altitude:.0f} m, channel {c}: "
                                        f"{got[c]:.4f} against the raymarch's {want[c]:.4f}")
            for c in range(3):
                if abs(sums[0][c] / sums[1][c] - 1.0) > 0.01:
                    failures.append(f"{layer}'s mean, channel {c}: {sums[0][c] / sums[1][c]:.4f} "
                                    f"of the raymarch's")
    for metas, flat, sun in (([{"box_min_m": (0, 0, 0), "box_max_m": (1, 1, 1)}], True, 3.0),
                             ([{"box_min_m": (0, 0, 0), "box_max_m": (1, 1, 1)}], False, -1.0)):
        mm = dict(m, sun_elevation_deg=sun)
        top, sheets = sun_profile(mm, metas, flat)
        if sheets or list(top) != list(m["sun_illuminance"]):
            failures.append(f"flat {flat}, sun {sun}: expected the middle's light and no sheets")
    for f in failures:
        print("sun_profile check:", f)
    print("sun_profile check:", "FAIL" if failures else "ok")
    return 1 if failures else 0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("vdb", nargs="*", help="exports (skyrender export-volume) whose sheets to print")
    p.add_argument("--check", action="store_true", help="the self-test")
    args = p.parse_args()
    if args.check:
        return check()
    import pyopenvdb
    for path in args.vdb:
        metas = [dict(g.metadata) for g in pyopenvdb.readAllGridMetadata(path)
                 if g.name == "density" or g.name.startswith("density_")]
        m = next(g for g in metas if g.get("grid_index", 0) == 0)
        top, sheets = sun_profile(m, metas, False)
        print(f"{path}: lamp {', '.join(f'{c:.4f}' for c in top)}")
        for z0, z1, sigma in sheets:
            print(f"  {z0:8.1f} to {z1:8.1f} m: sigma {', '.join(f'{c:.3e}' for c in sigma)} /m")
    return 0


if __name__ == "__main__":
    sys.exit(main())
