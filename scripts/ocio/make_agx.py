#!/usr/bin/env python3
"""Builds the `AgX` view of configs/ocio/config.ocio from AgX's published formula.

AgX (Troy Sobotka, github.com/sobotka/AgX) is the display transform Blender 4 and takram
three-clouds use. Its base is, per pixel:

  1. linear Rec.2020 -> the "inset" matrix, which pulls each primary a little toward the others
     (and rotates it), so that a saturated colour's channels reach the top of the curve together
     instead of one at a time: the hue holds where a per-channel curve alone skews orange to
     yellow and blue to cyan;
  2. log2 encoding over [-12.47393, 4.026069] EV around 0.18 (middle grey at 0.606);
  3. the same sigmoid per channel (the "default contrast"), giving display code values meant
     for a 2.2 power;
  4. the "outset" matrix, which gives back part of the saturation the inset took;
  5. the 2.2 power back to light, linear Rec.2020 on the display.

The matrices and the curve are those of Blender 4.0's AgX as three.js ships it (r162 and
later, `AgXToneMapping` in tonemapping_pars_fragment.glsl.js, the version takram's
postprocessing pass runs), the curve being the 6th-order polynomial fit of AgX's
default-contrast LUT (B. Wrensch, "Minimal AgX implementation", iolite-engine.com, 2023;
mean squared error 3.7e-6). So a scene shown through our AgX view and the peer's frames go
through one transform.

OCIO 2.1 has no sigmoid operator and this curve is not invertible in closed form, so the
curve is a 1D LUT file (4096 entries over [0, 1], linear interpolation: within 2e-7 of the
polynomial). Everything else is an OCIO matrix, allocation or exponent transform. The script
writes the LUT and the generated part of config.ocio (between its BEGIN/END markers); with
--check it only says whether both are up to date (a ctest runs that).

    scripts/ocio/make_agx.py            # write configs/ocio/luts/agx_base_contrast.spi1d and the view
    scripts/ocio/make_agx.py --check    # exit 1 if either is stale
"""
import argparse
import pathlib
import sys

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
CONFIG = ROOT / "configs" / "ocio" / "config.ocio"
LUT = ROOT / "configs" / "ocio" / "luts" / "agx_base_contrast.spi1d"
LUT_SIZE = 4096

MIN_EV = -12.47393
MAX_EV = 4.026069

# three.js writes its mat3s column by column; these are the rows of the matrices it applies
# (M * rgb, rgb linear Rec.2020).
INSET = np.array([
    [0.856627153315983, 0.0951212405381588, 0.0482516061458583],
    [0.137318972929847, 0.761241990602591, 0.101439036467562],
    [0.11189821299995, 0.0767994186031903, 0.811302368396859],
])
OUTSET = np.array([
    [1.1271005818144368, -0.11060664309660323, -0.016493938717834573],
    [-0.1413297634984383, 1.157823702216272, -0.016493938717834257],
    [-0.14132976349843826, -0.11060664309660294, 1.2519364065950405],
])


def contrast(x):
    """AgX's default contrast, the polynomial fit (x: log-encoded, clamped to [0, 1])."""
    x2 = x * x
    x4 = x2 * x2
    return (15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2
            + 0.1191 * x - 0.00232)


def rgb_to_xyz(primaries, white):
    """The RGB -> CIE XYZ matrix of a space with these xy primaries and white."""
    def xyz(xy):
        x, y = xy
        return np.array([x / y, 1.0, (1.0 - x - y) / y])
    p = np.stack([xyz(c) for c in primaries], axis=1)
    s = np.linalg.solve(p, xyz(white))
    return p * s


D65 = (0.3127, 0.3290)
REC2020_TO_XYZ = rgb_to_xyz([(0.708, 0.292), (0.170, 0.797), (0.131, 0.046)], D65)
XYZ_TO_REC2020 = np.linalg.inv(REC2020_TO_XYZ)
REC709_TO_XYZ = rgb_to_xyz([(0.64, 0.33), (0.30, 0.60), (0.15, 0.06)], D65)


def agx_rec709(rgb):
    """The whole view on linear Rec.709 values (N x 3): display-linear Rec.709, clipped. The
    reference the tests hold the OCIO view to."""
    rgb = np.asarray(rgb, dtype=np.float64).reshape(-1, 3)
    c = rgb @ (XYZ_TO_REC2020 @ REC709_TO_XYZ).T
    c = c @ INSET.T
    c = np.clip((np.log2(np.maximum(c, 1e-10)) - MIN_EV) / (MAX_EV - MIN_EV), 0.0, 1.0)
    c = contrast(c) @ OUTSET.T
    c = np.power(np.maximum(c, 0.0), 2.2)
    c = c @ (np.linalg.inv(REC709_TO_XYZ) @ REC2020_TO_XYZ).T
    return np.clip(c, 0.0, 1.0)


def matrix16(m):
    """An OCIO MatrixTransform's 16 numbers (row major, 4 x 4) for a 3 x 3 matrix."""
    rows = [list(m[i]) + [0.0] for i in range(3)] + [[0.0, 0.0, 0.0, 1.0]]
    return "[" + ", ".join(f"{v:.12g}" for row in rows for v in row) + "]"


def lut_text():
    x = np.linspace(0.0, 1.0, LUT_SIZE)
    lines = ["Version 1", "From 0 1", f"Length {LUT_SIZE}", "Components 1", "{"]
    lines += [f"  {v:.9f}" for v in contrast(x)]
    lines.append("}")
    return "\n".join(lines) + "\n"


def view_text():
    # From the scene reference (ACES2065-1) to the display reference (CIE XYZ D65). The
    # allocation is lg2 over [MIN_EV, MAX_EV]; values at or below 0 after the inset go to the
    # LUT's bottom (the LUT clamps its input to [0, 1], as AgX clamps the encoded value).
    return f"""  # BEGIN generated by scripts/ocio/make_agx.py: do not edit by hand
  - !<ViewTransform>
    name: AgX
    description: AgX base (Blender 4 / three.js), Rec.2020 inset, log2 -12.47..+4.03 EV, default contrast, outset, 2.2 power; ending in display-referred CIE XYZ
    from_scene_reference: !<GroupTransform>
      children:
        - !<BuiltinTransform> {{style: UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD}}
        - !<MatrixTransform> {{matrix: {matrix16(INSET @ XYZ_TO_REC2020)}}}
        - !<AllocationTransform> {{allocation: lg2, vars: [{MIN_EV}, {MAX_EV}]}}
        - !<FileTransform> {{src: agx_base_contrast.spi1d, interpolation: linear}}
        - !<MatrixTransform> {{matrix: {matrix16(OUTSET)}}}
        - !<ExponentTransform> {{value: [2.2, 2.2, 2.2, 1]}}
        - !<MatrixTransform> {{matrix: {matrix16(REC2020_TO_XYZ)}}}
  # END generated by scripts/ocio/make_agx.py
"""


def config_text(old):
    begin = old.find("  # BEGIN generated by scripts/ocio/make_agx.py")
    end_marker = "  # END generated by scripts/ocio/make_agx.py\n"
    end = old.find(end_marker)
    if begin < 0 or end < 0:
        raise SystemExit(f"error: {CONFIG}: no BEGIN/END markers of scripts/ocio/make_agx.py")
    return old[:begin] + view_text() + old[end + len(end_marker):]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--check", action="store_true", help="exit 1 if the LUT or the view is stale")
    p.add_argument("--print", metavar="R,G,B", help="print the view of one linear Rec.709 colour")
    a = p.parse_args()
    if a.print:
        print(" ".join(f"{v:.6f}" for v in agx_rec709([float(v) for v in a.print.split(",")])[0]))
        return 0
    old_config = CONFIG.read_text()
    new_config = config_text(old_config)
    new_lut = lut_text()
    if a.check:
        stale = [str(f) for f, new in ((LUT, new_lut), (CONFIG, new_config))
                 if not f.exists() or f.read_text() != new]
        if stale:
            print("stale (run scripts/ocio/make_agx.py): " + ", ".join(stale), file=sys.stderr)
            return 1
        return 0
    LUT.parent.mkdir(exist_ok=True)
    LUT.write_text(new_lut)
    CONFIG.write_text(new_config)
    print(f"wrote {LUT.relative_to(ROOT)} and the AgX view of {CONFIG.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
