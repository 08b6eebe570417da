#!/usr/bin/env python3
"""The grain on lit cloud faces of skyrender EXRs against a reference render of the same view
(docs/clouds.md, "Grain"; CloudGrainTest measures the same in C++).

  scripts/lit-face-grain.py REFERENCE.exr OTHER.exr [OTHER.exr ...]

Lit faces: pixels whose 3 x 3 neighbourhood is opaque in the reference (clouds.A > 0.95) and
brighter than the opaque pixels' median. For each file: the relative high-frequency energy of
the beauty's luminance there (the RMS of each pixel less its 3 x 3 mean, over the mean) and the
RMS error against the reference over the opaque pixels, over the reference's mean. Needs
OpenImageIO's Python module (scripts/install-deps.sh --pathtracer).
"""
import sys

import numpy as np
import OpenImageIO as oiio


def load(path):
    inp = oiio.ImageInput.open(path)
    if not inp:
        sys.exit(f"{path}: {oiio.geterror()}")
    names = list(inp.spec().channelnames)
    px = inp.read_image(format="float")
    inp.close()
    for c in ("R", "G", "B", "clouds.A"):
        if c not in names:
            sys.exit(f"{path}: no channel {c} (a skyrender EXR with its clouds layer)")
    ch = lambda n: px[..., names.index(n)]
    return 0.2126 * ch("R") + 0.7152 * ch("G") + 0.0722 * ch("B"), ch("clouds.A")


def neighbours(a):
    """The nine 3 x 3 neighbours of every pixel (edges repeated), stacked on axis 0."""
    p = np.pad(a, 1, mode="edge")
    h, w = a.shape
    return np.stack([p[1 + j:1 + j + h, 1 + i:1 + i + w] for j in (-1, 0, 1) for i in (-1, 0, 1)])


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    ref_l, ref_a = load(sys.argv[1])
    opaque = neighbours(ref_a).min(axis=0) > 0.95
    if not opaque.any():
        sys.exit(f"{sys.argv[1]}: no opaque cloud")
    lit = opaque & (ref_l > np.median(ref_l[opaque]))
    for path in sys.argv[1:]:
        lum, _ = load(path)
        if lum.shape != ref_l.shape:
            sys.exit(f"{path}: {lum.shape[1]}x{lum.shape[0]}, the reference is "
                     f"{ref_l.shape[1]}x{ref_l.shape[0]}")
        hp = lum - neighbours(lum).mean(axis=0)
        energy = np.sqrt((hp[lit] ** 2).mean()) / lum[lit].mean()
        error = np.sqrt(((lum - ref_l)[opaque] ** 2).mean()) / ref_l[opaque].mean()
        print(f"{path}: lit faces {lit.sum()} px, high-frequency energy {energy:.4f}, "
              f"error against the reference {100 * error:.1f} %")


if __name__ == "__main__":
    main()
