#!/usr/bin/env python3
"""Writes configs/pathtrace/cumulus_map.png, the weather map of the isolated cumulus scenes:
one round cell of cumulus (B = 1) in a clear map, cover 0.9 within 0.9 km of the centre
falling smoothly to 0 at 1.8 km, density scale 1. The scenes stretch it over a 6 km square
(weather.region), so a texel is about 95 m. Pure Python (zlib), no imaging library needed.

    python3 scripts/pathtrace/make_cumulus_map.py
"""
import math
import pathlib
import struct
import zlib

SIZE = 64           # texels on a side
SIDE_KM = 6.0       # the region's size in the scenes (about: lat 0.054 deg, lon 0.08 deg)
INNER_KM, OUTER_KM, COVER = 0.9, 1.8, 0.9


def cover_at(x, y):
    r = math.hypot(x, y)
    if r <= INNER_KM:
        return COVER
    if r >= OUTER_KM:
        return 0.0
    t = (r - INNER_KM) / (OUTER_KM - INNER_KM)
    return COVER * (1.0 - t * t * (3.0 - 2.0 * t))  # smoothstep down


def main():
    rows = []
    for j in range(SIZE):
        row = bytearray([0])  # filter type 0
        for i in range(SIZE):
            x = ((i + 0.5) / SIZE - 0.5) * SIDE_KM
            y = (0.5 - (j + 0.5) / SIZE) * SIDE_KM
            row += bytes([round(255 * cover_at(x, y)), 0, 255, 255])
        rows.append(bytes(row))

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    png = (b"\x89PNG\r\n\x1a\n" +
           chunk(b"IHDR", struct.pack(">IIBBBBB", SIZE, SIZE, 8, 6, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(b"".join(rows), 9)) + chunk(b"IEND", b""))
    out = pathlib.Path(__file__).resolve().parents[2] / "configs" / "pathtrace" / "cumulus_map.png"
    out.write_bytes(png)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
