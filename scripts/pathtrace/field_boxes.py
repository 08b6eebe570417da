#!/usr/bin/python3
"""The nested boxes a path-traced field exports (issue 46; docs/cloud-model.md "A path-traced
field"): the clouds the camera sees, to the horizon, on voxels that grow with distance as the
raymarch's level of detail does.

    skyrender validate SCENE > settings.yaml
    /usr/bin/python3 scripts/pathtrace/field_boxes.py settings.yaml [--range-km 100] \
        [--shells-km 3,7,16,40] [--min-voxel-m 10]

prints the arguments for `skyrender export-volume` (one line): `--box E0,N0,U0,E1,N1,U1` for
each box, nested, finest first, then `--voxel-m M` for each, and `--lod view`.

- The camera's rays (a grid over the image, edges included) are followed through the layers
  that have cover (straight, over a sphere of the renderer's Earth radius, stopping at the
  ground); box k is the bounding box of the points in a layer whose distance along the ground
  from the camera is within shell k (`--shells-km`, the last shell `--range-km`), grown by one
  of its voxels on every side (a grid's values fade over the half voxel at its faces), then
  joined with the box inside it so the boxes nest. All boxes then take the outermost's near
  side, bottom and top (where they would differ only by the Earth's curvature and their
  margins), so they hand the field over only across their far and side faces.
- `--shadow`: instead, the boxes of the clouds outside those that shadow them, one line of
  `--box ... --voxel-m M --lod view` for each (a file each: they do not nest). The sun's light
  reaches a cloud in the view boxes through the layer toward the sun, which at 3 degrees runs
  some 28 km across the ground: where it leaves the view boxes (behind the camera with the
  sun behind it) Cycles saw no cloud, and lit the view's clouds as if the sky toward a low
  sun were clear past their near side. Each is the slab beyond a face of the outermost view
  box that the layers' depth, swept toward the sun, crosses: as deep as that sweep, as wide
  as the box and the sweep together, at the outermost box's voxel; behind the near side,
  which all the view's boxes share, nested as they are, at their voxels but no finer than
  50 m.
- Box k's voxel is the width of one of the camera's pixels at the inner edge of its shell,
  2 tan(vfov / 2) / height x that distance (the raymarch's footprint, docs/clouds.md, "Level of
  detail by footprint"), and the first box's `--min-voxel-m`: the export evaluates each voxel
  at the footprint of its own distance (`--lod view`), never finer than the voxel, so a box's
  voxel is at most the footprint anywhere in it.
"""
import argparse
import math
import sys

import numpy as np
import yaml

EARTH_RADIUS_M = 6371000.0  # GEO_EARTH_RADIUS_M (shaders/common/geo_shared.h): the export's frame


def camera_rays(cam, width, height, nu=97, nv=55):
    h, p = math.radians(cam["heading"]), math.radians(cam["pitch"])
    forward = np.array([math.sin(h) * math.cos(p), math.cos(h) * math.cos(p), math.sin(p)])
    right = np.array([math.cos(h), -math.sin(h), 0.0])
    up = np.cross(right, forward)
    tan_v = math.tan(0.5 * math.radians(cam["vertical_fov"]))
    tan_h = tan_v * width / height
    u, v = np.meshgrid(np.linspace(0.0, 1.0, nu), np.linspace(0.0, 1.0, nv))
    d = (forward[None, None, :] + ((2 * u - 1) * tan_h)[..., None] * right +
         (-(2 * v - 1) * tan_v)[..., None] * up)
    return (d / np.linalg.norm(d, axis=-1, keepdims=True)).reshape(-1, 3)


def layer_points(settings, range_m):
    """Points (ENU, m) in a layer with cover along the camera's rays, and their distance along
    the ground from the camera."""
    cam = settings["camera"]
    out = settings["output"]
    clouds, weather = settings["clouds"], settings["weather"]
    procedural = weather.get("source", "procedural") == "procedural"
    layers = []
    if not procedural or float(weather.get("cover_low", 0)) > 0:
        layers.append((clouds["low"]["base_m"], clouds["low"]["top_m"]))
    if not procedural or float(weather.get("cover_mid", 0)) > 0:
        layers.append((clouds["mid"]["base_m"], clouds["mid"]["top_m"]))
    if not layers:
        sys.exit("error: field_boxes.py: the scene has no low or mid cover")
    rays = camera_rays(cam, out["width"], out["height"])
    t = np.concatenate([[0.0], np.geomspace(1.0, 6.0 * range_m, 4000)])
    centre = np.array([0.0, 0.0, EARTH_RADIUS_M + cam["altitude_m"]])
    found, distance = [], []
    for chunk in np.array_split(rays, max(1, len(rays) // 256)):
        points = chunk[:, None, :] * t[None, :, None]
        altitude = np.linalg.norm(points + centre, axis=-1) - EARTH_RADIUS_M
        ground = np.maximum.accumulate(altitude < 0.0, axis=1)  # past the ground: not seen
        inside = np.zeros_like(ground)
        for base, top in layers:
            inside |= (altitude >= base) & (altitude <= top)
        along = np.hypot(points[..., 0], points[..., 1])
        keep = inside & ~ground & (along <= range_m)
        found.append(points[keep])
        distance.append(along[keep])
    return np.concatenate(found), np.concatenate(distance)


def main():
    ap = argparse.ArgumentParser(prog="field_boxes.py")
    ap.add_argument("settings", help="the scene's effective settings (skyrender validate)")
    ap.add_argument("--range-km", type=float, default=100.0)
    ap.add_argument("--shells-km", default="3,7,16,40")
    ap.add_argument("--min-voxel-m", type=float, default=10.0)
    ap.add_argument("--shadow", action="store_true",
                    help="print the boxes toward the sun outside the view's, one line each")
    args = ap.parse_args()
    with open(args.settings) as f:
        settings = yaml.safe_load(f)
    range_m = 1000.0 * args.range_km
    shells = [1000.0 * float(s) for s in args.shells_km.split(",") if s] + [range_m]
    if sorted(shells) != shells or shells[0] <= 0:
        sys.exit("error: field_boxes.py: --shells-km must rise, and stay below --range-km")
    points, along = layer_points(settings, range_m)
    if len(points) == 0:
        sys.exit("error: field_boxes.py: the camera sees no cloud layer within --range-km")
    out = settings["output"]
    per_m = 2.0 * math.tan(0.5 * math.radians(settings["camera"]["vertical_fov"])) / out["height"]
    boxes, voxels = [], []
    for k, reach in enumerate(shells):
        voxel = args.min_voxel_m if k == 0 else max(args.min_voxel_m, per_m * shells[k - 1])
        voxel = float(f"{voxel:.3g}")
        near = points[along <= reach]
        lo, hi = near.min(axis=0) - voxel, near.max(axis=0) + voxel
        if boxes:
            lo, hi = np.minimum(lo, boxes[-1][0]), np.maximum(hi, boxes[-1][1])
        boxes.append((np.floor(lo), np.ceil(hi)))
        voxels.append(voxel)
    # A box hands the field over to the next only across faces the next reaches well past
    # (cloudVolumeShare, docs/outputs.md): its far and side faces. The near side and the
    # bottom and top, where the boxes differ only by the Earth's curvature and their margins,
    # are the outermost box's for every box: faces of the field, so no coarse grid takes a
    # share of the cloud bases and tops there.
    outer_lo, outer_hi = boxes[-1]
    for k, (lo, hi) in enumerate(boxes):
        lo, hi = lo.copy(), hi.copy()
        lo[1], lo[2], hi[2] = outer_lo[1], outer_lo[2], outer_hi[2]
        boxes[k] = (lo, hi)
    if args.shadow:
        shadow_boxes(settings, boxes, voxels)
        return
    words = []
    for lo, hi in boxes:
        words += ["--box", ",".join(f"{v:.0f}" for v in (*lo, *hi))]
    for v in voxels:
        words += ["--voxel-m", f"{v:g}"]
    print(" ".join(words + ["--lod", "view"]))
    total = 0
    for (lo, hi), v in zip(boxes, voxels):
        n = np.ceil((hi - lo) / v)
        total += int(np.prod(n))
        print(f"box {lo.astype(int).tolist()}..{hi.astype(int).tolist()} at {v:g} m: "
              f"{int(n[0])}x{int(n[1])}x{int(n[2])}", file=sys.stderr)
    print(f"{total} voxels in all", file=sys.stderr)


SHADOW_MIN_VOXEL_M = 50.0  # finer than a cumulus' billows: a coarser one smears the clouds


def shadow_boxes(settings, boxes, voxels):
    """One line of export-volume arguments for each slab beyond the outermost view box that
    the light toward the sun crosses (see --shadow above)."""
    sun = settings["sun"]
    el, az = math.radians(float(sun["elevation"])), math.radians(float(sun["azimuth"]))
    lo, hi = boxes[-1]
    voxel = voxels[-1]
    if el <= 0.0:
        return  # no sunlight reaches the layer's clouds from above the horizon
    # How far across the ground the light rises through the cloud layers, and which way
    # (at most the raymarch's far reach, CLOUD_LIGHT_FAR_REACH_M).
    clouds = settings["clouds"]
    base = min(clouds["low"]["base_m"], clouds["mid"]["base_m"])
    top = max(clouds["low"]["top_m"], clouds["mid"]["top_m"]) if float(
        settings["weather"].get("cover_mid", 0)) > 0 else clouds["low"]["top_m"]
    reach = min((top - base) / math.tan(el), 60000.0)
    step = np.array([math.sin(az), math.cos(az)]) * reach
    swept_lo = np.minimum(lo[:2], lo[:2] + step)
    swept_hi = np.maximum(hi[:2], hi[:2] + step)
    lines = []
    # The slab across x takes the sweep's whole y; those across y only the box's x, so they
    # never overlap (Cycles adds the densities of overlapping volumes).
    if step[0] < -voxel:
        lines.append([(([swept_lo[0], swept_lo[1]], [lo[0], swept_hi[1]]), voxel)])
    elif step[0] > voxel:
        lines.append([(([hi[0], swept_lo[1]], [swept_hi[0], swept_hi[1]]), voxel)])
    if step[1] < -voxel:
        # Behind the near side every view box shares: the near clouds' light crosses it, so
        # the slab nests as the view's boxes do, each as wide as one and at its voxel (no
        # finer than SHADOW_MIN_VOXEL_M).
        lines.append([(([blo[0], swept_lo[1]], [bhi[0], lo[1]]), max(v, SHADOW_MIN_VOXEL_M))
                      for (blo, bhi), v in zip(boxes, voxels)])
    elif step[1] > voxel:
        lines.append([(([lo[0], hi[1]], [hi[0], swept_hi[1]]), voxel)])
    for parts in lines:
        words = []
        for (x0, y0), (x1, y1) in (b for b, _ in parts):
            box = (np.floor(x0), np.floor(y0), lo[2], np.ceil(x1), np.ceil(y1), hi[2])
            words += ["--box", ",".join(f"{v:.0f}" for v in box)]
            print(f"shadow box {[int(v) for v in box]}", file=sys.stderr)
        for _, v in parts:
            words += ["--voxel-m", f"{v:g}"]
        print(" ".join(words + ["--lod", "view"]))

if __name__ == "__main__":
    main()
