#!/usr/bin/python3
"""The path-traced field's measurements (issue 46; docs/cloud-model.md "A path-traced field"),
for compare.py: our whole field of clouds at a low sun against Cycles', on the final image.

For a scene S in DIR it reads S.exr (ours: beauty, `sky`, `clouds` with its depth), S_ms0.exr
(the same clouds with clouds.multiple_scattering 0), S.vdb (the camera, the sun, the layers and
the boxes), S_cycles.exr and S_cycles_nishita.exr (Cycles' clouds, premultiplied, under our
sky and under Blender's Nishita sky; either may be missing), and the world checks S_clear.exr,
S_world_check.exr and S_nishita_check.exr.

**Cycles' clouds in our final image.** Our beauty is `beyond (1 - A) + T C + A S` per channel
(passes/atmosphere_composite): C and A the clouds layer, T the air's transmittance to the
clouds and S the light it scatters in, both at the clouds' depth, and `beyond` what lies behind
(the sky; below the clouds near the horizon dimmed by the overcast's share). The two renders of
ours differ only in C (the diffusion term), so T = (beauty - beauty_ms0) / (C - C_ms0). beyond
is our `sky` times each row's beauty / sky on its clear pixels (1 away from the horizon). Then
S = (beauty - T C - beyond (1 - A)) / A. Where our clouds are too thin (A < 0.05) for that,
T and S are taken from the nearest pixel where they are known. Cycles' final image is then
`beyond (1 - A_c) + T C_c + A_c S`: the same sky, the same air in front, only the clouds' own
light (and opacity) differ.

**Compared pixels**: above the horizon, and whose centre ray leaves the cloud layer's top
inside the exported boxes (rays that run on through the layer past the outermost box, in the
last degree above the horizon, would see clouds Cycles has not got).

**Metrics**, per renderer on its own alpha:
- ratio: mean luminance of the opaque cloud pixels (alpha > 0.95) over that of the clear sky
  pixels (alpha < 0.02) of the final image; ours / Cycles - 1 is its error (goal: within 20 %);
- error: mean |Y_ours - Y_cycles| / Y_cycles over the pixels where both alphas exceed 0.5
  (goal <= 25 %), and its signed mean;
- lit hue: the HSV hue of the mean linear RGB of the brightest quarter of the opaque cloud
  pixels (Cycles' ranked on its 3x3-smoothed luminance, so its noise does not pick them); the
  difference in degrees (goal within 8 degrees);
- the skies: our clear sky (S_clear.exr: our view of it from the clouds' altitude, where both
  worlds are) against Cycles' view of each world through the same camera, luminance and
  blue/red in bands of elevation (1 degree wide) within 15 degrees of the view's heading.
"""
import colorsys
import math
import pathlib
import sys

import numpy as np
import OpenImageIO as oiio
import pyopenvdb
from scipy import ndimage

OPAQUE = 0.95
CLEAR = 0.02
CLOUD = 0.5
SOLVE_ALPHA = 0.05            # the least opacity of ours that T and S are solved at
LIT_SHARE = 0.25              # the brightest quarter of the opaque cloud pixels
GOAL_RATIO = 0.20
GOAL_ERROR = 0.25
GOAL_HUE_DEG = 8.0
EARTH_RADIUS_M = 6371000.0    # the export's frame (GEO_EARTH_RADIUS_M)
GROUND_RADIUS_M = 6360000.0   # the physical sky's ground sphere (atmosphere.ground_radius_km)
SKY_ELEVATIONS = (2, 5, 10, 20, 30)
NEAR_M = 10000.0              # "near" clouds: our clouds' depth under 10 km


def read(path, names):
    buf = oiio.ImageBuf(str(path))
    if buf.has_error:
        sys.exit(f"error: {path}: {buf.geterror()}")
    spec = buf.spec()
    channels = list(spec.channelnames)
    pixels = buf.get_pixels(oiio.FLOAT).reshape(spec.height, spec.width, spec.nchannels)
    try:
        return np.stack([pixels[:, :, channels.index(n)] for n in names], axis=-1).astype(np.float64)
    except ValueError:
        sys.exit(f"error: {path}: needs channels {names}, has {channels}")


def grids(path):
    found = {g.name: dict(g.metadata) for g in pyopenvdb.readAllGridMetadata(str(path))
             if g.name == "density" or g.name.startswith("density_")}
    if "density" not in found:
        sys.exit(f"error: {path}: no grid named 'density'")
    return sorted(found.values(), key=lambda m: int(m.get("grid_index", 0)))


def luminance(rgb):
    return rgb[..., 0] * 0.2126 + rgb[..., 1] * 0.7152 + rgb[..., 2] * 0.0722


def box3(img):
    p = np.pad(img, 1, mode="edge")
    h, w = img.shape
    return sum(p[y:y + h, x:x + w] for y in range(3) for x in range(3)) / 9.0


def directions(meta):
    """Each pixel centre's view direction (ENU, unit), as the raymarch builds its rays."""
    w, h = int(meta["camera_width"]), int(meta["camera_height"])
    tan_v = math.tan(0.5 * math.radians(meta["camera_vertical_fov_deg"]))
    tan_h = tan_v * w / h
    f, r, u = (np.array(meta[k]) for k in ("camera_forward", "camera_right", "camera_up"))
    uu = (np.arange(w) + 0.5) / w
    vv = (np.arange(h) + 0.5) / h
    d = (f[None, None, :] + ((2 * uu - 1) * tan_h)[None, :, None] * r[None, None, :] -
         ((2 * vv - 1) * tan_v)[:, None, None] * u[None, None, :])
    return d / np.linalg.norm(d, axis=-1, keepdims=True)


def compared_region(meta, outer, d):
    """Above the horizon, and the ray leaves the layer's top inside the outermost box."""
    cam = float(meta["camera_altitude_m"])
    horizon_z = -math.sqrt(max(1.0 - (GROUND_RADIUS_M / (GROUND_RADIUS_M + cam)) ** 2, 0.0))
    above = d[..., 2] > horizon_z
    # The top of the highest layer the boxes reach into.
    box_top = cam + float(outer["box_max_m"][2])
    top = float(meta["mid_top_m"]) if box_top > float(meta["mid_base_m"]) else float(meta["low_top_m"])
    r0 = EARTH_RADIUS_M + cam
    r1 = EARTH_RADIUS_M + top
    b = r0 * d[..., 2]
    t = -b + np.sqrt(np.maximum(b * b - r0 * r0 + r1 * r1, 0.0))
    x, y = t * d[..., 0], t * d[..., 1]
    lo, hi = outer["box_min_m"], outer["box_max_m"]
    inside = (x >= lo[0]) & (x <= hi[0]) & (y >= lo[1]) & (y <= hi[1])
    return above & inside, above


def nearest_fill(values, known):
    """values where known, else the nearest known pixel's (per channel image, HxWxC)."""
    if known.all() or not known.any():
        return values
    _, (iy, ix) = ndimage.distance_transform_edt(~known, return_indices=True)
    return values[iy, ix]


def air_in_front(ours, ms0):
    """T, S and beyond per pixel from our two renders (module docstring)."""
    beauty, sky = ours["beauty"], ours["sky"]
    c, a = ours["clouds"][..., :3], ours["clouds"][..., 3:4]
    dc = c - ms0["clouds"][..., :3]
    db = beauty - ms0["beauty"]
    # beyond: the sky, times each row's own factor (the overcast's dimming near the horizon).
    clear = (a[..., 0] < 0.002) & (luminance(sky) > 0)
    factor = np.ones(sky.shape[0])
    rows = np.flatnonzero(clear.any(axis=1))
    if len(rows):
        per_row = np.array([np.median(luminance(beauty[r][clear[r]]) / luminance(sky[r][clear[r]]))
                            for r in rows])
        factor = np.interp(np.arange(sky.shape[0]), rows, per_row)
    beyond = sky * factor[:, None, None]
    beyond = np.where(clear[..., None], beauty, beyond)
    solve = (a[..., 0] >= SOLVE_ALPHA) & np.all(np.abs(dc) > 1e-4 * (np.abs(c) + 1e-6), axis=-1)
    t = np.where(solve[..., None], db / np.where(solve[..., None], dc, 1.0), 1.0)
    t = np.clip(t, 0.0, 1.5)
    s = np.where(solve[..., None], (beauty - t * c - beyond * (1 - a)) / np.maximum(a, SOLVE_ALPHA), 0.0)
    s = np.maximum(s, 0.0)
    t = nearest_fill(t, solve)
    s = nearest_fill(s, solve)
    return {"t": t, "s": s, "beyond": beyond, "solved": solve, "row_factor": factor,
            "alpha_moved": float(np.abs(a - ms0["clouds"][..., 3:4]).max())}


def final(air, rgba):
    a = rgba[..., 3:4]
    return air["beyond"] * (1 - a) + air["t"] * rgba[..., :3] + a * air["s"]


def hue_deg(rgb):
    r, g, b = (float(x) for x in rgb)
    m = max(r, g, b)
    if m <= 0:
        return float("nan")
    return 360.0 * colorsys.rgb_to_hsv(r / m, g / m, b / m)[0]


def hue_difference(a, b):
    return (a - b + 180.0) % 360.0 - 180.0


def lit_of(img, opaque, key):
    lit = np.zeros_like(opaque)
    lit[opaque] = key[opaque] >= np.quantile(key[opaque], 1.0 - LIT_SHARE)
    return lit


def measure(img, alpha, region, near, rank=None):
    """The ratio, the lit hue and what they are made of, for one renderer; the same for the
    clouds nearer than NEAR_M (`near`, by our clouds' depth) alone."""
    y = luminance(img)
    key = rank if rank is not None else y
    opaque = region & (alpha > OPAQUE)
    clear = region & (alpha < CLEAR)
    out = {"opaque_pixels": int(opaque.sum()), "clear_pixels": int(clear.sum())}
    if opaque.sum() < 20 or clear.sum() < 20:
        return out
    out["cloud_luminance"] = float(y[opaque].mean())
    out["sky_luminance"] = float(y[clear].mean())
    out["ratio"] = out["cloud_luminance"] / out["sky_luminance"]
    lit = lit_of(img, opaque, key)
    mean = img[lit].mean(axis=0)
    out["lit_rgb"] = [float(v) for v in mean]
    out["lit_hue_deg"] = hue_deg(mean)
    out["lit_blue_red"] = float(mean[2] / max(mean[0], 1e-30))
    out["lit_luminance"] = float(y[lit].mean())
    cloud_mean = img[opaque].mean(axis=0)
    out["cloud_blue_red"] = float(cloud_mean[2] / max(cloud_mean[0], 1e-30))
    # Against the sky beside them: each row's opaque clouds over its clear sky, weighted by the
    # row's cloud pixels (rows with at least 3 of each). The sky darkens upward and brightens
    # toward a low sun, so the frame's mean sky says little about a cloud's own surroundings.
    num = den = 0.0
    for row in range(img.shape[0]):
        c, k = opaque[row], clear[row]
        if c.sum() >= 3 and k.sum() >= 3:
            num += c.sum() * y[row][c].mean() / y[row][k].mean()
            den += c.sum()
    if den > 0:
        out["row_ratio"] = num / den
    near_opaque = opaque & near
    out["near_opaque_pixels"] = int(near_opaque.sum())
    if near_opaque.sum() >= 20:
        out["near_ratio"] = float(y[near_opaque].mean()) / out["sky_luminance"]
        near_lit = lit_of(img, near_opaque, key)
        near_mean = img[near_lit].mean(axis=0)
        out["near_lit_hue_deg"] = hue_deg(near_mean)
        out["near_lit_blue_red"] = float(near_mean[2] / max(near_mean[0], 1e-30))
    return out


def sky_check(directory, scene, meta, d, above):
    ours_path = directory / f"{scene}_clear.exr"
    if not ours_path.exists():
        return None
    ours = read(ours_path, ["R", "G", "B"])
    worlds = {"sky": directory / f"{scene}_world_check.exr",
              "nishita": directory / f"{scene}_nishita_check.exr"}
    worlds = {k: read(p, ["R", "G", "B"]) for k, p in worlds.items() if p.exists()}
    elevation = np.degrees(np.arcsin(np.clip(d[..., 2], -1, 1)))
    azimuth = np.degrees(np.arctan2(d[..., 0], d[..., 1]))
    heading = float(meta["camera_heading_deg"])
    near_heading = np.abs(hue_difference(azimuth, heading)) < 15.0
    rows = []
    for e in SKY_ELEVATIONS:
        band = above & near_heading & (np.abs(elevation - e) < 0.5)
        if band.sum() < 3:
            continue
        row = {"elevation_deg": e, "ours_luminance": float(luminance(ours[band]).mean()),
               "ours_blue_red": float(ours[band][:, 2].mean() / ours[band][:, 0].mean())}
        for k, img in worlds.items():
            row[f"{k}_luminance"] = float(luminance(img[band]).mean())
            row[f"{k}_blue_red"] = float(img[band][:, 2].mean() / img[band][:, 0].mean())
        rows.append(row)
    whole = {"ours_luminance": float(luminance(ours[above]).mean()),
             "ours_blue_red": float(ours[above][:, 2].mean() / ours[above][:, 0].mean())}
    for k, img in worlds.items():
        whole[f"{k}_luminance"] = float(luminance(img[above]).mean())
        whole[f"{k}_blue_red"] = float(img[above][:, 2].mean() / img[above][:, 0].mean())
    return {"heading_deg": heading, "bands": rows, "frame": whole}


def srgb(linear):
    x = np.clip(linear, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)


def error_panel(rel, mask):
    img = np.full(rel.shape + (3,), 0.15)
    t = np.clip(rel / 0.5, -1.0, 1.0)
    red = np.stack([np.ones_like(t), 1 - t, 1 - t], axis=-1)
    blue = np.stack([1 + t, 1 + t, np.ones_like(t)], axis=-1)
    img[mask] = np.where((t >= 0)[..., None], red, blue)[mask]
    return img


def compare_field(directory, scene, images, write_png):
    ours = {"beauty": read(directory / f"{scene}.exr", ["R", "G", "B"]),
            "sky": read(directory / f"{scene}.exr", ["sky.R", "sky.G", "sky.B"]),
            "clouds": read(directory / f"{scene}.exr", ["clouds.R", "clouds.G", "clouds.B", "clouds.A"])}
    ms0 = {"beauty": read(directory / f"{scene}_ms0.exr", ["R", "G", "B"]),
           "clouds": read(directory / f"{scene}_ms0.exr", ["clouds.R", "clouds.G", "clouds.B", "clouds.A"])}
    parts = grids(directory / f"{scene}.vdb")
    meta, outer = parts[0], parts[-1]
    d = directions(meta)
    if d.shape[:2] != ours["beauty"].shape[:2]:
        sys.exit(f"error: {scene}: the grid's camera is {d.shape[1]}x{d.shape[0]}, the render "
                 f"{ours['beauty'].shape[1]}x{ours['beauty'].shape[0]}")
    region, above = compared_region(meta, outer, d)
    depth = read(directory / f"{scene}.exr", ["clouds.depth"])[..., 0]
    near = (depth > 0) & (depth < NEAR_M)
    air = air_in_front(ours, ms0)
    a_ours = ours["clouds"][..., 3]
    img_ours = ours["beauty"]
    # The identity: our own clouds through the recovered air give our beauty back.
    recon = final(air, ours["clouds"])
    cloud_px = region & (a_ours > CLOUD)
    result = {
        "scene": scene, "kind": "field",
        "size": [int(d.shape[1]), int(d.shape[0])],
        "sun_elevation_deg": float(meta["sun_elevation_deg"]),
        "sun_azimuth_deg": float(meta["sun_azimuth_deg"]),
        "camera_pitch_deg": float(meta["camera_pitch_deg"]),
        "boxes": [{"min_m": list(m["box_min_m"]), "max_m": list(m["box_max_m"]), "voxel_m": float(m["voxel_m"])}
                  for m in parts],
        "compared_pixels": int(region.sum()),
        "above_horizon_pixels": int(above.sum()),
        "air": {"alpha_moved_by_ms0": air["alpha_moved"],
                "solved_share_of_cloud": float(air["solved"][cloud_px].mean()) if cloud_px.any() else None,
                "row_factor_min": float(air["row_factor"].min()),
                "recomposite_error": float(np.abs(luminance(recon[cloud_px]) / luminance(img_ours[cloud_px]) - 1).mean())
                if cloud_px.any() else None,
                "transmittance_luminance_on_cloud": float(luminance(air["t"][cloud_px]).mean())
                if cloud_px.any() else None},
        "ours": measure(img_ours, a_ours, region, near),
        "cycles": {},
    }
    panels = {"ours": img_ours}
    for world, name in (("sky", f"{scene}_cycles.exr"), ("nishita", f"{scene}_cycles_nishita.exr")):
        path = directory / name
        if not path.exists():
            continue
        rgba = read(path, ["R", "G", "B", "A"])
        if rgba.shape[:2] != img_ours.shape[:2]:
            sys.exit(f"error: {name}: {rgba.shape[1]}x{rgba.shape[0]}, ours {img_ours.shape[1]}x{img_ours.shape[0]}")
        img = final(air, rgba)
        a_c = rgba[..., 3]
        m = measure(img, a_c, region, near, rank=box3(luminance(img)))
        both = region & (a_ours > CLOUD) & (a_c > CLOUD)
        y_o, y_c = luminance(img_ours), luminance(img)
        if both.sum() >= 20:
            rel = (y_o[both] - y_c[both]) / y_c[both]
            m["error"] = float(np.abs(rel).mean())
            m["signed_error"] = float(rel.mean())
            m["error_pixels"] = int(both.sum())
            o_op, c_op = region & (a_ours > OPAQUE), region & (a_c > OPAQUE)
            m["opaque_iou"] = float((o_op & c_op).sum() / max((o_op | c_op).sum(), 1))
        r = result["ours"]
        if "ratio" in m and "ratio" in r:
            m["ratio_error"] = r["ratio"] / m["ratio"] - 1.0
            m["hue_difference_deg"] = hue_difference(r["lit_hue_deg"], m["lit_hue_deg"])
            if "row_ratio" in m and "row_ratio" in r:
                m["row_ratio_error"] = r["row_ratio"] / m["row_ratio"] - 1.0
            if "near_ratio" in m and "near_ratio" in r:
                m["near_ratio_error"] = r["near_ratio"] / m["near_ratio"] - 1.0
                m["near_hue_difference_deg"] = hue_difference(r["near_lit_hue_deg"], m["near_lit_hue_deg"])
            m["goals"] = {"ratio": abs(m["ratio_error"]) <= GOAL_RATIO,
                          "error": m.get("error", 1.0) <= GOAL_ERROR,
                          "hue": abs(m["hue_difference_deg"]) <= GOAL_HUE_DEG}
        result["cycles"][world] = m
        panels[world] = img
        if world == "sky" and both.sum() >= 20:
            rel_img = np.zeros_like(y_c)
            rel_img[both] = (y_o[both] - y_c[both]) / y_c[both]
            panels["error"] = (rel_img, both)
    result["skies"] = sky_check(directory, scene, meta, d, above)

    if images is not None:
        y_all = np.concatenate([luminance(p)[above] for k, p in panels.items() if k != "error"])
        exposure = 0.8 / float(np.quantile(y_all, 0.98))
        h = img_ours.shape[0]
        gap = np.ones((h, 4, 3))
        row = []
        for k in ("ours", "sky", "nishita"):
            if k in panels:
                row += [srgb(panels[k] * exposure), gap]
        if "error" in panels:
            row.append(error_panel(*panels["error"]))
        else:
            row = row[:-1]
        images.mkdir(parents=True, exist_ok=True)
        out = images / f"{scene}.png"
        write_png(out, np.concatenate(row, axis=1))
        result["image"] = str(out)
        result["exposure"] = exposure
    return result


def pct(x):
    return "" if x is None else f"{100 * x:+.1f} %"


def markdown(results):
    lines = ["| scene | sun | compared px | renderer | opaque px | cloud/sky ratio | ratio vs ours "
             "| mean rel. error | signed | lit hue | hue ours - this | lit B/R | goals missed |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        sun = f"{r['sun_elevation_deg']:.0f}° az {r['sun_azimuth_deg']:.0f}"
        o = r["ours"]
        lines.append(f"| {r['scene']} | {sun} | {r['compared_pixels']} | ours | {o['opaque_pixels']} | "
                     f"{o.get('ratio', float('nan')):.3f} | | | | {o.get('lit_hue_deg', float('nan')):.1f}° | | "
                     f"{o.get('lit_blue_red', float('nan')):.2f} | |")
        for world, m in r["cycles"].items():
            missed = [k for k, v in m.get("goals", {}).items() if not v]
            name = "Cycles, our sky" if world == "sky" else "Cycles, Nishita"
            lines.append(
                f"| | | | {name} | {m['opaque_pixels']} | {m.get('ratio', float('nan')):.3f} | "
                f"{pct(m.get('ratio_error'))} | {100 * m.get('error', float('nan')):.1f} % | "
                f"{pct(m.get('signed_error'))} | {m.get('lit_hue_deg', float('nan')):.1f}° | "
                f"{m.get('hue_difference_deg', float('nan')):+.1f}° | {m.get('lit_blue_red', float('nan')):.2f} | "
                f"{', '.join(missed) if missed else 'none'} |")
    lines += ["", f"Against the sky beside them (row ratio: each row's opaque clouds over its clear sky, "
              f"weighted by its cloud pixels), and the clouds nearer than {NEAR_M / 1000:.0f} km (by our "
              "clouds' depth) alone: their cloud-to-sky ratio (over the frame's clear sky) and lit hue:", "",
              "| scene | renderer | row ratio | row ratio vs ours | near opaque px | near ratio | vs ours "
              "| near lit hue | hue ours - this | near lit B/R |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        rows = [("ours", r["ours"])] + [("Cycles, our sky" if w == "sky" else "Cycles, Nishita", m)
                                        for w, m in r["cycles"].items()]
        for name, m in rows:
            lines.append(f"| {r['scene']} | {name} | {m.get('row_ratio', float('nan')):.3f} | "
                         f"{pct(m.get('row_ratio_error'))} | {m.get('near_opaque_pixels', 0)} | "
                         f"{m.get('near_ratio', float('nan')):.3f} | {pct(m.get('near_ratio_error'))} | "
                         f"{m.get('near_lit_hue_deg', float('nan')):.1f}° | "
                         f"{m.get('near_hue_difference_deg', float('nan')):+.1f}° | "
                         f"{m.get('near_lit_blue_red', float('nan')):.2f} |")
    skies = [r for r in results if r.get("skies")]
    if skies:
        lines += ["", "The skies, toward the view's heading (within 15°), seen from the clouds' altitude: "
                  "luminance (renderer units) and blue/red, ours, Cycles' view of our equirectangular sky "
                  "(the check: should equal ours) and of Blender's Nishita sky:", "",
                  "| scene | elevation | Y ours | Y our world | Y Nishita | Nishita / ours | B/R ours "
                  "| B/R our world | B/R Nishita |", "|---|---|---|---|---|---|---|---|---|"]
        for r in skies:
            for b in r["skies"]["bands"] + [dict(r["skies"]["frame"], elevation_deg="frame")]:
                e = b["elevation_deg"]
                nis = b.get("nishita_luminance")
                lines.append(
                    f"| {r['scene']} | {e if e == 'frame' else str(e) + '°'} | {b['ours_luminance']:.4f} | "
                    f"{b.get('sky_luminance', float('nan')):.4f} | {nis if nis is not None else float('nan'):.4f} | "
                    f"{(nis / b['ours_luminance']) if nis else float('nan'):.2f} | {b['ours_blue_red']:.2f} | "
                    f"{b.get('sky_blue_red', float('nan')):.2f} | {b.get('nishita_blue_red', float('nan')):.2f} |")
    lines += ["", "The air in front (field_compare.py): largest change of our alpha between the two renders, "
              "share of our cloud pixels where T and S were solved, and our own clouds recomposited "
              "through them against our beauty (0 but for the filled pixels):", "",
              "| scene | alpha moved | solved | recomposite error | T (luminance) on cloud | least row factor |",
              "|---|---|---|---|---|---|"]
    for r in results:
        a = r["air"]
        lines.append(f"| {r['scene']} | {a['alpha_moved_by_ms0']:.2g} | {100 * (a['solved_share_of_cloud'] or 0):.1f} % | "
                     f"{100 * (a['recomposite_error'] or 0):.2f} % | {a['transmittance_luminance_on_cloud'] or 0:.3f} | "
                     f"{a['row_factor_min']:.3f} |")
    return "\n".join(lines) + "\n"


def reference(results, samples, sun_profile="layers"):
    """The committed Cycles numbers (tests/data/pathtrace/field_cycles.json) later tests hold our
    ratios against: per scene, each world's cloud-to-sky ratio and lit hue, the compared
    region, and ours when they were made."""
    scenes = {}
    for r in results:
        entry = {"size": r["size"], "sun_elevation_deg": r["sun_elevation_deg"],
                 "sun_azimuth_deg": r["sun_azimuth_deg"],
                 "range_box_m": {"min": r["boxes"][-1]["min_m"], "max": r["boxes"][-1]["max_m"]},
                 "compared_pixels": r["compared_pixels"]}
        for who, m in [("ours_when_made", r["ours"])] + [(f"cycles_{w}", m) for w, m in r["cycles"].items()]:
            entry[who] = {k: m[k] for k in ("ratio", "lit_hue_deg", "lit_blue_red", "opaque_pixels",
                                             "cloud_luminance", "sky_luminance") if k in m}
            for k in ("error", "signed_error"):
                if k in m:
                    entry[who][k] = m[k]
        scenes[r["scene"]] = entry
    return {"what": "Cycles (Blender 3.4) on the field scenes of configs/pathtrace/field_*.yaml: "
                    "the cloud-to-sky luminance ratio (opaque cloud, alpha > 0.95, over clear sky, "
                    "alpha < 0.02, in the final image with Cycles' clouds over our sky through our "
                    "air in front) and the HSV hue of the brightest quarter of the opaque cloud "
                    "pixels, over the pixels above the horizon whose ray leaves the cloud layer "
                    "inside range_box_m (docs/cloud-model.md, 'A path-traced field'; "
                    "scripts/pathtrace/field_compare.py). cycles_sky: lit by our sky and sun; "
                    "cycles_nishita: by Blender's Nishita sky and our sun. sun_profile layers: "
                    "the sun's light at each altitude is the raymarch's (scripts/pathtrace/"
                    "sun_profile.py); flat: one illuminance, the layer middle's.",
            "sun_profile": sun_profile,
            "goals": {"ratio_within": GOAL_RATIO, "error_at_most": GOAL_ERROR,
                      "hue_within_deg": GOAL_HUE_DEG},
            "samples": samples, "scenes": scenes}
