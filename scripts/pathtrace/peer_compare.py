#!/usr/bin/python3
"""The peer's field against ours on display-referred images (issue 46; docs/cloud-model.md
"A path-traced field"): takram three-clouds renders the four low-sun views of
../shared/peers/takram/README.md as PNGs through AgX, with no alpha. Both renderers are
measured the same way on their PNGs:

- **Segmentation** against each renderer's own clear sky of the same view: the peer rendered
  again with COVERAGE=0 (its clouds off: run.sh with the view's EXTRA_QUERY), ours with no low,
  mid or high clouds. A pixel above the horizon (half a degree up, from the camera; not the
  peer's black blocks near it) is cloud where it differs from its clear sky by more than CLOUD_DIFF of the clear
  sky's (the largest relative change of a channel of the display-decoded RGB, both images
  smoothed over 3x3 pixels against 8-bit steps and the peer's dithering), clear sky where it
  differs by less than CLEAR_DIFF, and left out between (thin edges, haze). The sun's disc
  and the pixels around it are left out of the clear sky. On ours the segmentation is held
  against our alpha (the EXR's clouds.A): the share of our cloud pixels that are opaque and
  of our clear-sky pixels that are clear.
- **Values**: the PNG decoded by the sRGB curve to display-linear RGB: the peer's through AgX;
  ours through compare.sh's PEER_VIEW (AgX, with main's OCIO config, for the figures in the
  docs: the same transform; with 'Un-tone-mapped', the scene-linear image times the exposure,
  clipped at 1, which is not).
- **ratio**: mean luminance of the cloud pixels over that of the clear-sky pixels; **lit
  hue**: the HSV hue of the mean RGB of the brightest quarter of the cloud pixels.

    /usr/bin/python3 scripts/pathtrace/peer_compare.py --dir DIR --peer PEER_RESULTS \\
        [--peer-clear DIR] [--images DIR] VIEW...

VIEW is toward, away, backlit or noon; DIR holds ours (peer_VIEW.exr/.png and
peer_VIEW_clear.png, written by compare.sh PEER=1), PEER_RESULTS the peer's
2026-12-07_takram_640x360_sun_VIEW.png and --peer-clear its peer_clear_VIEW.png.
"""
import argparse
import colorsys
import json
import pathlib
import sys

import numpy as np
import OpenImageIO as oiio

CLOUD_DIFF = 0.25
CLEAR_DIFF = 0.06
SUN_EXCLUDE_PX = 12
LIT_SHARE = 0.25


def read(path, names=None):
    buf = oiio.ImageBuf(str(path))
    if buf.has_error:
        sys.exit(f"error: {path}: {buf.geterror()}")
    spec = buf.spec()
    pixels = buf.get_pixels(oiio.FLOAT).reshape(spec.height, spec.width, spec.nchannels)
    if names is None:
        return pixels[..., :3].astype(np.float64)
    channels = list(spec.channelnames)
    return np.stack([pixels[..., channels.index(n)] for n in names], axis=-1).astype(np.float64)


def decode(srgb):
    return np.where(srgb <= 0.04045, srgb / 12.92, ((srgb + 0.055) / 1.055) ** 2.4)


def luminance(rgb):
    return rgb[..., 0] * 0.2126 + rgb[..., 1] * 0.7152 + rgb[..., 2] * 0.0722


def hue_deg(rgb):
    m = float(max(rgb))
    return float("nan") if m <= 0 else 360.0 * colorsys.rgb_to_hsv(*(float(c) / m for c in rgb))[0]


def box3(img):
    p = np.pad(img, ((1, 1), (1, 1), (0, 0)), mode="edge")
    h, w = img.shape[:2]
    return sum(p[y:y + h, x:x + w] for y in range(3) for x in range(3)) / 9.0


def elevation_deg(pitch_deg, width, height, vfov_deg=60.0):
    """Each pixel centre's elevation for the peer's camera (heading 0, the given pitch)."""
    p = np.radians(pitch_deg)
    tan_v = np.tan(np.radians(vfov_deg) / 2)
    tan_h = tan_v * width / height
    u = (np.arange(width) + 0.5) / width
    v = (np.arange(height) + 0.5) / height
    f = np.array([0.0, np.cos(p), np.sin(p)])
    r = np.array([1.0, 0.0, 0.0])
    up = np.cross(r, f)
    d = f + ((2 * u - 1) * tan_h)[None, :, None] * r - ((2 * v - 1) * tan_v)[:, None, None] * up
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    return np.degrees(np.arcsin(d[..., 2]))


def segment(img, clear, pitch_deg):
    """cloud and clear-sky masks of a display-linear image against its clear sky."""
    y_clear = luminance(clear)
    # Above the horizon (from the camera, with a margin of a few pixels for the peer's
    # horizon line), and not the peer's black blocks near the horizon (dark in its clear sky).
    above = elevation_deg(pitch_deg, img.shape[1], img.shape[0]) > 0.5
    above &= y_clear > 0.05 * np.median(y_clear[above])
    # Each channel's change relative to the clear sky's, on both images smoothed over 3x3
    # pixels (the 8-bit steps and the peer's dithering are a few per cent a pixel).
    diff = (np.abs(box3(img) - box3(clear)) / np.maximum(box3(clear), 1e-6)).max(axis=-1)
    # The sun's disc (the brightest spot of the clear sky, when it is in view).
    j, i = np.unravel_index(np.argmax(np.where(above, y_clear, 0)), y_clear.shape)
    yy, xx = np.mgrid[: y_clear.shape[0], : y_clear.shape[1]]
    near_sun = ((yy - j) ** 2 + (xx - i) ** 2 < SUN_EXCLUDE_PX ** 2) & (y_clear[j, i] > 0.9)
    cloud = above & (diff > CLOUD_DIFF) & ~near_sun
    sky = above & (diff < CLEAR_DIFF) & ~near_sun
    return cloud, sky, above


def measure(img, cloud, sky):
    y = luminance(img)
    out = {"cloud_pixels": int(cloud.sum()), "sky_pixels": int(sky.sum()),
           "clipped_cloud_share": float((img[cloud].max(axis=-1) >= 0.999).mean()) if cloud.any() else 0.0}
    if cloud.sum() < 20 or sky.sum() < 20:
        return out
    out["ratio"] = float(y[cloud].mean() / y[sky].mean())
    lit = np.zeros_like(cloud)
    lit[cloud] = y[cloud] >= np.quantile(y[cloud], 1.0 - LIT_SHARE)
    mean = img[lit].mean(axis=0)
    out["lit_hue_deg"] = hue_deg(mean)
    out["lit_blue_red"] = float(mean[2] / max(mean[0], 1e-30))
    return out


PITCH = {"toward": 10.0, "away": 10.0, "backlit": 20.0, "noon": 20.0}


def compare(directory, peer_dir, peer_clear_dir, view, images):
    peer = decode(read(peer_dir / f"2026-12-07_takram_640x360_sun_{view}.png"))
    peer_clear = decode(read(peer_clear_dir / f"peer_clear_{view}.png"))
    ours = decode(read(directory / f"peer_{view}.png"))
    ours_clear = decode(read(directory / f"peer_{view}_clear.png"))
    alpha = read(directory / f"peer_{view}.exr", ["clouds.A"])[..., 0]
    result = {"view": view}
    p_cloud, p_sky, _ = segment(peer, peer_clear, PITCH[view])
    result["peer"] = measure(peer, p_cloud, p_sky)
    o_cloud, o_sky, above = segment(ours, ours_clear, PITCH[view])
    result["ours"] = measure(ours, o_cloud, o_sky)
    # How the segmentation fares where the alpha is known (ours).
    result["ours"]["segmentation"] = {
        "cloud_pixels_opaque": float((alpha[o_cloud] > 0.95).mean()) if o_cloud.any() else None,
        "cloud_pixels_over_half": float((alpha[o_cloud] > 0.5).mean()) if o_cloud.any() else None,
        "sky_pixels_clear": float((alpha[o_sky] < 0.02).mean()) if o_sky.any() else None,
        "opaque_pixels_found": float(o_cloud[above & (alpha > 0.95)].mean()) if (above & (alpha > 0.95)).any() else None,
    }
    # The same metric on our scene-linear EXR with our alpha (no display transform).
    exr = read(directory / f"peer_{view}.exr", ["R", "G", "B"])
    result["ours"]["scene_linear"] = measure(exr, above & (alpha > 0.95), above & (alpha < 0.02) & o_sky)
    if images is not None:
        def panel(img, cloud, sky):
            shown = np.clip(img, 0, 1) ** (1 / 2.2)
            shown = shown.copy()
            shown[cloud] = 0.6 * shown[cloud] + 0.4 * np.array([1.0, 0.3, 0.3])
            shown[sky] = 0.7 * shown[sky] + 0.3 * np.array([0.2, 0.5, 1.0])
            return shown
        gap = np.ones((peer.shape[0], 4, 3))
        row = np.concatenate([np.clip(ours, 0, 1) ** (1 / 2.2), gap, np.clip(peer, 0, 1) ** (1 / 2.2)], axis=1)
        masks = np.concatenate([panel(ours, o_cloud, o_sky), gap, panel(peer, p_cloud, p_sky)], axis=1)
        img = np.concatenate([row, np.ones((4, row.shape[1], 3)), masks], axis=0)
        spec = oiio.ImageSpec(img.shape[1], img.shape[0], 3, oiio.UINT8)
        buf = oiio.ImageBuf(spec)
        buf.set_pixels(oiio.ROI(0, img.shape[1], 0, img.shape[0], 0, 1, 0, 3),
                       np.ascontiguousarray(img.astype(np.float32)))
        images.mkdir(parents=True, exist_ok=True)
        out = images / f"peer_{view}.png"
        if not buf.write(str(out)):
            sys.exit(f"error: {out}: {buf.geterror()}")
        result["image"] = str(out)
    return result


def markdown(results):
    lines = ["| view | renderer | cloud px | sky px | cloud/sky ratio | lit hue | lit B/R | clipped cloud |",
             "|---|---|---|---|---|---|---|---|"]
    for r in results:
        for who in ("ours", "peer"):
            m = r[who]
            lines.append(f"| {r['view']} | {who} | {m['cloud_pixels']} | {m['sky_pixels']} | "
                         f"{m.get('ratio', float('nan')):.3f} | {m.get('lit_hue_deg', float('nan')):.1f}° | "
                         f"{m.get('lit_blue_red', float('nan')):.2f} | {100 * m['clipped_cloud_share']:.1f} % |")
        s = r["ours"]["scene_linear"]
        lines.append(f"| {r['view']} | ours, scene-linear, alpha | {s['cloud_pixels']} | {s['sky_pixels']} | "
                     f"{s.get('ratio', float('nan')):.3f} | {s.get('lit_hue_deg', float('nan')):.1f}° | "
                     f"{s.get('lit_blue_red', float('nan')):.2f} | |")
    lines += ["", "The segmentation on ours, against our alpha: share of the pixels it calls cloud that "
              "are opaque (> 0.95) and more than half covered, share of those it calls clear sky that "
              "are clear (< 0.02), share of the opaque pixels it finds:", "",
              "| view | cloud opaque | cloud > 0.5 | sky clear | opaque found |", "|---|---|---|---|---|"]
    for r in results:
        s = r["ours"]["segmentation"]
        f = lambda x: "" if x is None else f"{100 * x:.1f} %"
        lines.append(f"| {r['view']} | {f(s['cloud_pixels_opaque'])} | {f(s['cloud_pixels_over_half'])} | "
                     f"{f(s['sky_pixels_clear'])} | {f(s['opaque_pixels_found'])} |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(prog="peer_compare.py")
    ap.add_argument("--dir", required=True, type=pathlib.Path)
    ap.add_argument("--peer", required=True, type=pathlib.Path)
    ap.add_argument("--peer-clear", type=pathlib.Path)
    ap.add_argument("--images", type=pathlib.Path)
    ap.add_argument("views", nargs="+", choices=("toward", "away", "backlit", "noon"))
    args = ap.parse_args()
    results = [compare(args.dir, args.peer, args.peer_clear or args.dir, v, args.images) for v in args.views]
    (args.dir / "peer_results.json").write_text(json.dumps(results, indent=2) + "\n")
    table = markdown(results)
    (args.dir / "peer_results.md").write_text(table)
    print(table, end="")


if __name__ == "__main__":
    main()
