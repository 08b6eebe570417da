#!/usr/bin/python3
"""Compares skyrender's clouds with the Cycles reference of the same field and camera
(scripts/pathtrace/compare.sh runs it; docs/cloud-model.md "Path-traced reference").

    /usr/bin/python3 scripts/pathtrace/compare.py --dir out/pathtrace [--images DIR] SCENE...

For each SCENE it reads DIR/SCENE.exr (skyrender's render: the `clouds` layer, premultiplied
radiance and opacity before the atmosphere) and DIR/SCENE_cycles.exr (Cycles, transparent
film: the same quantities) and reports, over the cloud pixels (both opacities above 0.5):
- mean relative luminance error: mean over those pixels of |Y_ours - Y_cycles| / Y_cycles,
  Y = Rec.709 luminance of the premultiplied radiance;
- lit/shadowed ratio: the mean luminance of the lit pixels over that of the shadowed ones,
  for each renderer on the same pixels. Lit = the brightest tenth of the cloud pixels in the
  path tracer's image, shadowed = its darkest tenth (ranked on the image smoothed over 3x3
  pixels so the path tracer's noise does not pick them). For a cumulus seen from the side
  these are its sunlit top and its base;
- ratio error: ours / cycles - 1 of that ratio.
Writes DIR/results.json and DIR/results.md, and for each scene IMAGES/SCENE.png: ours | Cycles
| signed relative error (blue: ours darker, red: ours brighter, full colour at 50 %).
Needs numpy and OpenImageIO's Python module (scripts/install-deps.sh --pathtracer).
"""
import argparse
import json
import pathlib
import sys

import numpy as np
import OpenImageIO as oiio

GOAL_ERROR = 0.15   # issue 14: mean relative error at most 15 %
GOAL_RATIO = 0.20   # top/base ratio within 20 % of the path tracer's
CLOUD_ALPHA = 0.5


def read_channels(path, names):
    buf = oiio.ImageBuf(str(path))
    if buf.has_error:
        sys.exit(f"error: {path}: {buf.geterror()}")
    spec = buf.spec()
    channels = list(spec.channelnames)
    pixels = buf.get_pixels(oiio.FLOAT).reshape(spec.height, spec.width, spec.nchannels)
    try:
        return np.stack([pixels[:, :, channels.index(n)] for n in names], axis=-1)
    except ValueError:
        sys.exit(f"error: {path}: needs channels {names}, has {channels}")


def luminance(rgb):
    return rgb[..., 0] * 0.2126 + rgb[..., 1] * 0.7152 + rgb[..., 2] * 0.0722


def box3(img):
    p = np.pad(img, 1, mode="edge")
    h, w = img.shape
    return sum(p[y:y + h, x:x + w] for y in range(3) for x in range(3)) / 9.0


def srgb(linear):
    x = np.clip(linear, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)


def panel(rgba, background, exposure):
    # Premultiplied cloud over a flat sky colour, one exposure for both renderers.
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


def compare(directory, scene, images):
    ours = read_channels(directory / f"{scene}.exr", ["clouds.R", "clouds.G", "clouds.B", "clouds.A"])
    ref = read_channels(directory / f"{scene}_cycles.exr", ["R", "G", "B", "A"])
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
    smooth = box3(y_ref)[mask]
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
    result = {
        "scene": scene,
        "size": [int(ours.shape[1]), int(ours.shape[0])],
        "cloud_pixels": n,
        "silhouette_iou": float((opaque_ours & opaque_ref).sum() / max(union, 1)),
        "mean_relative_error": float(np.abs(rel[mask]).mean()),
        "mean_signed_error": float(rel[mask].mean()),
        "mean_luminance_ours": float(y_ours[mask].mean()),
        "mean_luminance_cycles": float(y_ref[mask].mean()),
        "lit_shadowed_ratio_ours": ratio_ours,
        "lit_shadowed_ratio_cycles": ratio_ref,
        "ratio_error": ratio_ours / ratio_ref - 1.0,
    }
    result["meets_goal"] = bool(result["mean_relative_error"] <= GOAL_ERROR and
                                abs(result["ratio_error"]) <= GOAL_RATIO)
    if images:
        background = np.array([0.32, 0.45, 0.7], dtype=np.float32) * float(np.quantile(y_ref[mask], 0.5))
        exposure = 0.85 / float(np.quantile(np.concatenate([y_ref[mask], y_ours[mask]]), 0.99))
        gap = np.ones((ours.shape[0], 4, 3), dtype=np.float32)
        side = np.concatenate([panel(ours, background, exposure), gap,
                               panel(ref, background, exposure), gap, error_panel(rel, mask)], axis=1)
        images.mkdir(parents=True, exist_ok=True)
        out = images / f"{scene}.png"
        spec = oiio.ImageSpec(side.shape[1], side.shape[0], 3, oiio.UINT8)
        buf = oiio.ImageBuf(spec)
        buf.set_pixels(oiio.ROI(0, side.shape[1], 0, side.shape[0], 0, 1, 0, 3),
                       np.ascontiguousarray(side.astype(np.float32)))
        if not buf.write(str(out)):
            sys.exit(f"error: {out}: {buf.geterror()}")
        result["image"] = str(out)
    return result


def markdown(results):
    lines = ["| scene | cloud px | mean rel. error | signed | lit/shadowed ours | Cycles | ratio error | goal |",
             "|---|---|---|---|---|---|---|---|"]
    for r in results:
        lines.append(f"| {r['scene']} | {r['cloud_pixels']} | {100 * r['mean_relative_error']:.1f} % | "
                     f"{100 * r['mean_signed_error']:+.1f} % | {r['lit_shadowed_ratio_ours']:.2f} | "
                     f"{r['lit_shadowed_ratio_cycles']:.2f} | {100 * r['ratio_error']:+.1f} % | "
                     f"{'met' if r['meets_goal'] else 'missed'} |")
    return "\n".join(lines) + "\n"


def main():
    p = argparse.ArgumentParser(prog="compare.py")
    p.add_argument("--dir", required=True, type=pathlib.Path)
    p.add_argument("--images", type=pathlib.Path)
    p.add_argument("scenes", nargs="+")
    args = p.parse_args()
    results = [compare(args.dir, s, args.images) for s in args.scenes]
    (args.dir / "results.json").write_text(json.dumps(results, indent=2) + "\n")
    table = markdown(results)
    (args.dir / "results.md").write_text(table)
    print(table, end="")


if __name__ == "__main__":
    main()
