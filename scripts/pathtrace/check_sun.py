#!/usr/bin/python3
"""Checks the colour of the sunlight that export-volume hands the path tracer (and the
raymarch lights the cloud with: light::illuminanceAtAltitude at the layer's middle) against a
transmittance integrated along the curved path through the same air, for a low sun where the
air reddens the light most (docs/cloud-model.md "Path-traced reference").

    /usr/bin/python3 scripts/pathtrace/check_sun.py out/pathtrace/SCENE.vdb...

The lighting model takes exp(-tau m) with one air mass m (Kasten & Young 1989, for the
Rayleigh scale height) for every constituent. The integral here follows the straight ray from
the layer's altitude at the sun's elevation through a spherical Earth (radius 6371 km) to
100 km, with the same columns (engine/lighting/light_model.cpp): Rayleigh (Hansen & Travis)
with scale height 8434 m, aerosols of optical depth turbidity x (lambda / 550 nm)^-1.3 with
scale height 1200 m, and the Chappuis ozone column in a layer 15-35 km up. The turbidity is
read from the metadata's sun colour at no cost: it is the scene's lighting.turbidity
(default 0.1), passed with --turbidity. No refraction in either (the ephemeris' refraction is
already in the elevation). The last column does the integral per wavelength over the visible
band (a 5778 K sun, the CIE 1931 observer, Rec.709), which says how far three wavelengths
(680, 550, 440 nm) miss the colour of broadband light when the air reddens it strongly.
The "model" and "integrated" columns are that three-wavelength model, which the renderer used
until issue 30; since then the renderer integrates over the spectrum itself (its columns:
"its B/R" and the R/G, to compare with the last column's spectral one).
"""
import argparse
import math

import numpy as np
import pyopenvdb

R_EARTH = 6371000.0
WAVELENGTHS_NM = (680.0, 550.0, 440.0)   # R, G, B of the lighting model before issue 30


def rayleigh_depth(nm):
    l2 = (nm * 1e-3) ** 2
    return 0.008569 / (l2 * l2) * (1.0 + 0.0113 / l2 + 0.00013 / (l2 * l2))


def ozone_depth(nm):
    return 8.07e18 * (0.2e-21 if nm < 500 else 3.3e-21 if nm < 600 else 2.0e-21)


def air_mass(elevation_deg):
    h = max(elevation_deg, -1.0)
    return 1.0 / (math.sin(math.radians(h)) + 0.50572 * (h + 6.07995) ** -1.6364)


def model(elevation_deg, altitude_m, turbidity):
    m = air_mass(elevation_deg)
    out = []
    for nm in WAVELENGTHS_NM:
        tau = (rayleigh_depth(nm) * math.exp(-altitude_m / 8434.0) + ozone_depth(nm) +
               turbidity * (nm / 550.0) ** -1.3 * math.exp(-altitude_m / 1200.0))
        out.append(math.exp(-tau * m))
    return np.array(out)


def columns(elevation_deg, altitude_m, steps=200000):
    # The straight ray from altitude_m at elevation_deg to 100 km up, in the midpoint rule
    # along it: the Rayleigh, aerosol and ozone columns it crosses, in vertical columns.
    r0 = R_EARTH + altitude_m
    mu = math.sin(math.radians(elevation_deg))
    top = R_EARTH + 100e3
    length = -r0 * mu + math.sqrt(r0 * r0 * mu * mu - r0 * r0 + top * top)
    s = (np.arange(steps) + 0.5) * length / steps
    z = np.sqrt(r0 * r0 + s * s + 2 * r0 * s * mu) - R_EARTH
    ds = length / steps
    rayleigh = np.exp(-z / 8434.0).sum() * ds / 8434.0
    aerosol = np.exp(-z / 1200.0).sum() * ds / 1200.0
    ozone = ((z > 15e3) & (z < 35e3)).sum() * ds / 20e3
    return rayleigh, aerosol, ozone


def integrated(elevation_deg, altitude_m, turbidity):
    rayleigh, aerosol, ozone = columns(elevation_deg, altitude_m)
    return np.array([math.exp(-(rayleigh_depth(nm) * rayleigh + ozone_depth(nm) * ozone +
                                turbidity * (nm / 550.0) ** -1.3 * aerosol))
                     for nm in WAVELENGTHS_NM])


def cie_1931(nm):
    # Wyman, Sloan & Shirley (2013), the multi-lobe fit of the CIE 1931 2-degree observer.
    def g(x, mu, s1, s2):
        return np.exp(-0.5 * ((x - mu) / np.where(x < mu, s1, s2)) ** 2)
    x = 1.056 * g(nm, 599.8, 37.9, 31.0) + 0.362 * g(nm, 442.0, 16.0, 26.7) - 0.065 * g(nm, 501.1, 20.4, 26.2)
    y = 0.821 * g(nm, 568.8, 46.9, 40.5) + 0.286 * g(nm, 530.9, 16.3, 31.1)
    z = 1.217 * g(nm, 437.0, 11.8, 36.0) + 0.681 * g(nm, 459.0, 26.0, 13.8)
    return np.stack([x, y, z], axis=-1)


XYZ_TO_REC709 = np.array([[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]])


def spectral(elevation_deg, altitude_m, turbidity):
    # The same air per wavelength over the visible band, the sun as a 5778 K black body, the
    # transmitted light in Rec.709 over the light above the air (which the renderer takes as
    # white): what three wavelengths stand for. Ozone's Chappuis band interpolated through
    # 1e-21 cm^2 at 400, 440, 500, 550, 600, 680, 750 nm: 0.02, 0.2, 1.4, 3.3, 4.8, 2.0, 1.0.
    nm = np.arange(380.0, 781.0, 1.0)
    planck = 1.0 / (nm * 1e-9) ** 5 / (np.exp(6.626e-34 * 2.998e8 / (nm * 1e-9 * 1.381e-23 * 5778.0)) - 1.0)
    o3 = 8.07e18 * 1e-21 * np.interp(nm, [400, 440, 500, 550, 600, 680, 750], [0.02, 0.2, 1.4, 3.3, 4.8, 2.0, 1.0])
    rayleigh, aerosol, ozone = columns(elevation_deg, altitude_m)
    tau = (np.array([rayleigh_depth(l) for l in nm]) * rayleigh + o3 * ozone +
           turbidity * (nm / 550.0) ** -1.3 * aerosol)
    cmf = cie_1931(nm)
    above = XYZ_TO_REC709 @ (cmf * planck[:, None]).sum(axis=0)
    below = XYZ_TO_REC709 @ (cmf * (planck * np.exp(-tau))[:, None]).sum(axis=0)
    return below / above


def main():
    p = argparse.ArgumentParser(prog="check_sun.py")
    p.add_argument("--turbidity", type=float, default=0.1)
    p.add_argument("vdb", nargs="+")
    args = p.parse_args()
    print("| grid | sun elevation | altitude | illuminance (R, G, B) | its B/R | model's B/R | "
          "integrated B/R | integrated / model (R, G, B) | spectral B/R | its R/G | R/G model | "
          "R/G spectral |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for path in args.vdb:
        meta = next(dict(g.metadata) for g in pyopenvdb.readAllGridMetadata(path) if g.name == "density")
        e = np.array(meta["sun_illuminance"])
        elevation, altitude = meta["sun_elevation_deg"], meta["light_altitude_m"]
        t_model = model(elevation, altitude, args.turbidity)
        t_path = integrated(elevation, altitude, args.turbidity)
        ratio = t_path / t_model
        t_spectral = spectral(elevation, altitude, args.turbidity)
        print(f"| {path.split('/')[-1]} | {elevation:.1f}° | {altitude:.0f} m | "
              f"{e[0]:.3f}, {e[1]:.3f}, {e[2]:.3f} | {e[2] / e[0]:.3f} | "
              f"{t_model[2] / t_model[0]:.3f} | {t_path[2] / t_path[0]:.3f} | "
              f"{ratio[0]:.3f}, {ratio[1]:.3f}, {ratio[2]:.3f} | {t_spectral[2] / t_spectral[0]:.3f} | "
              f"{e[0] / e[1]:.2f} | {t_model[0] / t_model[1]:.2f} | {t_spectral[0] / t_spectral[1]:.2f} |")


if __name__ == "__main__":
    main()
