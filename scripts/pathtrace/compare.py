#!/usr/bin/python3
"""Compares skyrender's clouds with the Cycles reference of the same field and camera
(scripts/pathtrace/compare.sh runs it; docs/cloud-model.md "Path-traced reference").

    /usr/bin/python3 scripts/pathtrace/compare.py --dir out/pathtrace [--images DIR] SCENE...

For each SCENE it reads DIR/SCENE.exr (skyrender's render: the `clouds` layer, premultiplied
radiance and opacity before the atmosphere), DIR/SCENE_cycles.exr (Cycles, transparent film:
the same quantities) and DIR/SCENE.vdb (the scene's camera and sun), and reports:

- over the cloud pixels (both opacities above 0.5): the mean relative luminance error, mean
  of |Y_ours - Y_cycles| / Y_cycles with Y the Rec.709 luminance of the premultiplied
  radiance, and its signed mean; the lit/shadowed ratio, the mean luminance of the lit pixels
  over that of the shadowed ones for each renderer on the same pixels (lit = the path
  tracer's brightest tenth, shadowed = its darkest tenth, ranked on its image smoothed over
  3x3 pixels so its noise does not pick them) and its error ours / cycles - 1;
- the core's colour (issue 30): over the opaque cloud pixels (both opacities above 0.9),
  each renderer's darker half by its own luminance (Cycles' ranked on its smoothed image),
  the ratio of the mean blue to the mean red there. Blue-grey shadow is 0.8 and more
  backlit, 0.95 and more at noon (issue 30's goals for ours);
- the silver rim: the cloud pixels (opacity above 0.5 in both) within RIM_PX pixels of the
  silhouette, the thin edge. rim/core is the rim's mean luminance over the core's (the darker
  half above); backlit, a real cloud's rim is brighter than its core (> 1). The brightest
  tenth of the opaque pixels over the core (the cloud's contrast) is reported too;
- with DIR/SCENE_cycles_sun.exr and DIR/SCENE_cycles_sky.exr (compare.sh SPLIT=...): Cycles'
  light split into sunlight and skylight on the core (Cycles' darker half), the rim and the
  whole cloud: each one's share of the luminance and its blue/red, and how far sun + sky
  misses the full render (noise); with DIR/SCENE_cycles_ground.exr too, the part of the
  skylight that comes from below the horizontal (the ground and the air in front of it);
- with DIR/SCENE_clear.exr and DIR/SCENE_world_check.exr (compare.sh with WORLD=sky): the
  check of Cycles' world, skyrender's view of the clear sky against Cycles' view of the
  equirectangular sky it was given, mean relative luminance error and blue/red of each.

The field_* scenes (issue 46, a whole field of clouds to the horizon) are measured by
field_compare.py on the final image (its docstring): the cloud-to-sky ratio, the per-pixel
error and the lit hue, ours against Cycles under our sky and under Blender's Nishita sky.

Backlit means the sun is ahead of the camera (its azimuth within 90 degrees of the view's);
noon means the sun higher than 45 degrees. Writes DIR/results.json and DIR/results.md, and
for each scene IMAGES/SCENE.png: ours | Cycles | signed relative error (blue: ours darker, red:
ours brighter, full colour at 50 %); the clouds over our clear sky (the render's `sky` layer),
one exposure for both. Needs numpy and the Python modules of OpenImageIO and OpenVDB
(scripts/install-deps.sh --pathtracer).
"""
import argparse
import json
import math
import pathlib
import sys

import numpy as np
import OpenImageIO as oiio
import pyopenvdb

import field_compare

GOAL_ERROR = 0.25          # issue 30: mean relative error at most 25 % on every scene
STRETCH_ERROR = 0.15       # issue 30's stretch (issue 14's goal)
GOAL_RATIO = 0.20          # issue 14: lit/shadowed ratio within 20 % of the path tracer's
GOAL_CORE_BACKLIT = 0.8    # issue 30: blue/red of the darker half of the cloud, backlit
GOAL_CORE_NOON = 0.95      # ... and at noon
CLOUD_ALPHA = 0.5          # the compared pixels (issue 14)
OPAQUE_ALPHA = 0.9         # the pixels whose colour is the cloud's own (issue 30)
RIM_PX = 2                 # the thin edge: this many pixels in from the silhouette


def grid_metadata(path):
    for grid in pyopenvdb.readAllGridMetadata(str(path)):
        if grid.name == "density":
            return dict(grid.metadata)
    sys.exit(f"error: {path}: no grid named 'density'")


def luminance(rgb):
    return rgb[..., 0] * 0.2126 + rgb[..., 1] * 0.7152 + rgb[..., 2] * 0.0722


def box3(img):
    p = np.pad(img, 1, mode="edge")
    h, w = img.shape
    return sum(p[y:y + h, x:x + w] for y in range(3) for x in range(3)) / 9.0


def erode(mask, steps):
    # 8-connected erosion; outside the image counts as not cloud.
    m = mask
    for _ in range(steps):
        p = np.pad(m, 1, constant_values=False)
        h, w = m.shape
        m = np.logical_and.reduce([p[y:y + h, x:x + w] for y in range(3) for x in range(3)])
    return m


def blue_red(rgb, where):
    return float(rgb[..., 2][where].mean() / max(rgb[..., 0][where].mean(), 1e-30))


def darker_half(y, where):
    out = np.zeros_like(where)
    out[where] = y[where] <= np.median(y[where])
    return out


def srgb(linear):
    x = np.clip(linear, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)


def panel(rgba, background, exposure):
    # Premultiplied cloud over our clear sky, one exposure for both renderers.
    over = rgba[..., :3] + (1.0 - rgba[..., 3:4]) * background
    return srgb(over * exposure)


def error_panel(rel, mask):
    img = np.full(rel.shape + (3,), 0.15, dtype=np.float32)
    t = np.clip(rel / 0.5, -1.0, 1.0)
    red = np.stack([np.ones_like(t), 1 - t, 1 - t], axis=-1)
    blue = np.stack([1 + t, 1 + t, np.ones_like(t)], axis=-1)
    colour = np.where((t >= 0)[..., None], red, blue)
    img[mask] = colour[mask]
    return img


def write_png(path, img):
    spec = oiio.ImageSpec(img.shape[1], img.shape[0], 3, oiio.UINT8)
    buf = oiio.ImageBuf(spec)
    buf.set_pixels(oiio.ROI(0, img.shape[1], 0, img.shape[0], 0, 1, 0, 3),
                   np.ascontiguousarray(img.astype(np.float32)))
    if not buf.write(str(path)):
        sys.exit(f"error: {path}: {buf.geterror()}")


def lighting(meta):
    sun = np.array(meta["sun_direction"])
    forward = np.array(meta["camera_forward"])
    ahead = float(sun[0] * forward[0] + sun[1] * forward[1])
    elevation = float(meta["sun_elevation_deg"])
    return {"sun_elevation_deg": elevation,
            "sun_illuminance": [float(c) for c in meta["sun_illuminance"]],
            "light_altitude_m": float(meta["light_altitude_m"]),
            "sky_model": str(meta.get("sky_model", "?")),
            "backlit": ahead > 0.0, "noon": elevation > 45.0}


def split(directory, scene, ref, y_ref_smooth, core_ref, rim, opaque):
    paths = [directory / f"{scene}_cycles_{k}.exr" for k in ("sun", "sky")]
    if not all(p.exists() for p in paths):
        return None
    sun, sky = (field_compare.read(p, ["R", "G", "B", "A"]) for p in paths)
    ground_path = directory / f"{scene}_cycles_ground.exr"
    ground = field_compare.read(ground_path, ["R", "G", "B", "A"]) if ground_path.exists() else None
    out = {}
    for name, where in (("core", core_ref), ("rim", rim), ("cloud", opaque)):
        y_sun, y_sky, y_all = (float(luminance(x)[where].mean()) for x in (sun, sky, ref))
        out[name] = {
            "sky_share": y_sky / (y_sun + y_sky),
            "sun_share": y_sun / (y_sun + y_sky),
            "blue_red_sun": blue_red(sun, where),
            "blue_red_sky": blue_red(sky, where),
            "blue_red_both": blue_red(ref, where),
            "closure": (y_sun + y_sky) / y_all - 1.0,
        }
        if ground is not None:
            # The world below the horizontal: the ground and the air in front of it.
            out[name]["ground_share"] = float(luminance(ground)[where].mean()) / (y_sun + y_sky)
            out[name]["blue_red_ground"] = blue_red(ground, where)
    return out


def world_check(directory, scene):
    ours_path, cycles_path = directory / f"{scene}_clear.exr", directory / f"{scene}_world_check.exr"
    if not (ours_path.exists() and cycles_path.exists()):
        return None
    ours = field_compare.read(ours_path, ["R", "G", "B"])
    ref = field_compare.read(cycles_path, ["R", "G", "B"])
    y_ours, y_ref = luminance(ours), luminance(ref)
    ok = y_ours > 0
    every = np.ones(y_ref.shape, dtype=bool)
    return {"mean_relative_error": float(np.abs(y_ref[ok] / y_ours[ok] - 1.0).mean()),
            "mean_signed_error": float((y_ref[ok] / y_ours[ok] - 1.0).mean()),
            "blue_red_ours": blue_red(ours, every), "blue_red_cycles": blue_red(ref, every)}


def compare(directory, scene, images):
    ours = field_compare.read(directory / f"{scene}.exr", ["clouds.R", "clouds.G", "clouds.B", "clouds.A"])
    ref = field_compare.read(directory / f"{scene}_cycles.exr", ["R", "G", "B", "A"])
    meta = grid_metadata(directory / f"{scene}.vdb")
    if ours.shape != ref.shape:
        sys.exit(f"error: {scene}: skyrender is {ours.shape[1]}x{ours.shape[0]}, Cycles "
                 f"{ref.shape[1]}x{ref.shape[0]}")
    y_ours, y_ref = luminance(ours), luminance(ref)
    mask = (ours[..., 3] > CLOUD_ALPHA) & (ref[..., 3] > CLOUD_ALPHA) & (y_ref > 0)
    n = int(mask.sum())
    if n < 20:
        sys.exit(f"error: {scene}: only {n} pixels are cloud in both images")
    rel = np.zeros_like(y_ref)
    rel[mask] = (y_ours[mask] - y_ref[mask]) / y_ref[mask]
    y_ref_smooth = box3(y_ref)
    smooth = y_ref_smooth[mask]
    lo, hi = np.quantile(smooth, [0.1, 0.9])
    lit = np.zeros_like(mask)
    dark = np.zeros_like(mask)
    lit[mask] = smooth >= hi
    dark[mask] = smooth <= lo
    ratio_ours = float(y_ours[lit].mean() / y_ours[dark].mean())
    ratio_ref = float(y_ref[lit].mean() / y_ref[dark].mean())
    opaque_ours = (ours[..., 3] > CLOUD_ALPHA)
    opaque_ref = (ref[..., 3] > CLOUD_ALPHA)
    union = int((opaque_ours | opaque_ref).sum())

    # The core and the rim (issue 30).
    opaque = (ours[..., 3] > OPAQUE_ALPHA) & (ref[..., 3] > OPAQUE_ALPHA)
    core_ours = darker_half(y_ours, opaque)
    core_ref = darker_half(y_ref_smooth, opaque)
    rim = mask & ~erode(mask, RIM_PX)
    bright_ours = np.zeros_like(opaque)
    bright_ref = np.zeros_like(opaque)
    bright_ours[opaque] = y_ours[opaque] >= np.quantile(y_ours[opaque], 0.9)
    bright_ref[opaque] = y_ref_smooth[opaque] >= np.quantile(y_ref_smooth[opaque], 0.9)

    light = lighting(meta)
    result = {
        "scene": scene,
        "size": [int(ours.shape[1]), int(ours.shape[0])],
        **light,
        "cloud_pixels": n,
        "opaque_pixels": int(opaque.sum()),
        "rim_pixels": int(rim.sum()),
        "silhouette_iou": float((opaque_ours & opaque_ref).sum() / max(union, 1)),
        "mean_relative_error": float(np.abs(rel[mask]).mean()),
        "mean_signed_error": float(rel[mask].mean()),
        "mean_luminance_ours": float(y_ours[mask].mean()),
        "mean_luminance_cycles": float(y_ref[mask].mean()),
        "lit_shadowed_ratio_ours": ratio_ours,
        "lit_shadowed_ratio_cycles": ratio_ref,
        "ratio_error": ratio_ours / ratio_ref - 1.0,
        "core_blue_red_ours": blue_red(ours, core_ours),
        "core_blue_red_cycles": blue_red(ref, core_ref),
        "core_luminance_ours": float(y_ours[core_ours].mean()),
        "core_luminance_cycles": float(y_ref[core_ref].mean()),
        # Ours on Cycles' core pixels: the same pixels, so a per-pixel comparison.
        "core_signed_error_on_cycles_core": float(y_ours[core_ref].mean() / y_ref[core_ref].mean() - 1.0),
        "rim_core_ours": float(y_ours[rim].mean() / y_ours[core_ours].mean()),
        "rim_core_cycles": float(y_ref[rim].mean() / y_ref[core_ref].mean()),
        "rim_blue_red_ours": blue_red(ours, rim),
        "rim_blue_red_cycles": blue_red(ref, rim),
        "brightest_core_ours": float(y_ours[bright_ours].mean() / y_ours[core_ours].mean()),
        "brightest_core_cycles": float(y_ref[bright_ref].mean() / y_ref[core_ref].mean()),
    }
    core_goal = GOAL_CORE_BACKLIT if light["backlit"] else (GOAL_CORE_NOON if light["noon"] else None)
    result["core_goal"] = core_goal
    goals = {"error": result["mean_relative_error"] <= GOAL_ERROR,
             "error_stretch": result["mean_relative_error"] <= STRETCH_ERROR}
    if core_goal is not None:
        goals["core_blue_red"] = result["core_blue_red_ours"] >= core_goal
    if light["backlit"]:
        goals["rim_brighter"] = result["rim_core_ours"] > 1.0
    result["goals"] = {k: bool(v) for k, v in goals.items()}
    result["split"] = split(directory, scene, ref, y_ref_smooth, core_ref, rim, opaque)
    result["world_check"] = world_check(directory, scene)

    if images:
        sky = field_compare.read(directory / f"{scene}.exr", ["sky.R", "sky.G", "sky.B"])
        exposure = 0.85 / float(np.quantile(np.concatenate([y_ref[mask], y_ours[mask]]), 0.99))
        gap = np.ones((ours.shape[0], 4, 3), dtype=np.float32)
        side = np.concatenate([panel(ours, sky, exposure), gap,
                               panel(ref, sky, exposure), gap, error_panel(rel, mask)], axis=1)
        images.mkdir(parents=True, exist_ok=True)
        out = images / f"{scene}.png"
        write_png(out, side)
        result["image"] = str(out)
    return result


def pct(x):
    return f"{100 * x:.1f} %"


def markdown(results):
    lines = ["| scene | sun | sky | cloud px | mean rel. error | signed | lit/shadowed ours | Cycles "
             "| core B/R ours | Cycles | rim/core ours | Cycles | goals missed |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        where = "ahead" if r["backlit"] else "behind"
        missed = [k for k, v in r["goals"].items() if not v]
        lines.append(
            f"| {r['scene']} | {r['sun_elevation_deg']:.0f}° {where} | {r['sky_model']} | "
            f"{r['cloud_pixels']} | {pct(r['mean_relative_error'])} | "
            f"{100 * r['mean_signed_error']:+.1f} % | {r['lit_shadowed_ratio_ours']:.2f} | "
            f"{r['lit_shadowed_ratio_cycles']:.2f} | {r['core_blue_red_ours']:.2f} | "
            f"{r['core_blue_red_cycles']:.2f} | {r['rim_core_ours']:.2f} | {r['rim_core_cycles']:.2f} | "
            f"{', '.join(missed) if missed else 'none'} |")
    splits = [r for r in results if r["split"]]
    if splits:
        lines += ["", "Cycles' light split into sunlight and skylight (share of the luminance, blue/red "
                  "of each; closure: (sun + sky) / full - 1):", "",
                  "| scene | part | sky share | from below | sun share | B/R sky | B/R below "
                  "| B/R sun | B/R both | closure |",
                  "|---|---|---|---|---|---|---|---|---|---|"]
        for r in splits:
            for part, s in r["split"].items():
                below = (pct(s["ground_share"]), f"{s['blue_red_ground']:.2f}") if "ground_share" in s else ("", "")
                lines.append(f"| {r['scene']} | {part} | {pct(s['sky_share'])} | {below[0]} | "
                             f"{pct(s['sun_share'])} | {s['blue_red_sky']:.2f} | {below[1]} | "
                             f"{s['blue_red_sun']:.2f} | {s['blue_red_both']:.2f} | {100 * s['closure']:+.1f} % |")
    checks = [r for r in results if r["world_check"]]
    if checks:
        lines += ["", "Check of Cycles' world (Cycles' view of our equirectangular sky against our own "
                  "view of it):", "",
                  "| scene | mean rel. error | signed | B/R ours | B/R Cycles |", "|---|---|---|---|---|"]
        for r in checks:
            c = r["world_check"]
            lines.append(f"| {r['scene']} | {pct(c['mean_relative_error'])} | "
                         f"{100 * c['mean_signed_error']:+.1f} % | {c['blue_red_ours']:.3f} | "
                         f"{c['blue_red_cycles']:.3f} |")
    return "\n".join(lines) + "\n"


def main():
    p = argparse.ArgumentParser(prog="compare.py")
    p.add_argument("--dir", required=True, type=pathlib.Path)
    p.add_argument("--images", type=pathlib.Path)
    p.add_argument("--reference", type=pathlib.Path,
                   help="write the field scenes' Cycles numbers here (tests/data/pathtrace/field_cycles.json)")
    p.add_argument("--samples", type=int, help="Cycles' samples per pixel, for --reference")
    p.add_argument("--sun-profile", choices=("layers", "flat"), default="layers",
                   help="the Cycles renders' sun (render_cycles.py --sun-profile), for --reference")
    p.add_argument("scenes", nargs="+")
    args = p.parse_args()
    fields = [s for s in args.scenes if s.startswith("field_")]
    results = [compare(args.dir, s, args.images) for s in args.scenes if s not in fields]
    field_results = [field_compare.compare_field(args.dir, s, args.images, write_png) for s in fields]
    (args.dir / "results.json").write_text(json.dumps(results + field_results, indent=2) + "\n")
    if args.reference and field_results:
        args.reference.write_text(json.dumps(field_compare.reference(field_results, args.samples, args.sun_profile), indent=2) + "\n")
    table = "\n".join(t for t in (markdown(results) if results else "",
                                  field_compare.markdown(field_results) if field_results else "") if t)
    (args.dir / "results.md").write_text(table)
    print(table, end="")


if __name__ == "__main__":
    main()
