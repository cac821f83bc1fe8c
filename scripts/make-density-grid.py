#!/usr/bin/python3
"""Writes the veined-marble density grid of docs/examples/marble.json (docs/scene-format.md, "Grid
media"):

    python3 scripts/make-density-grid.py [OUTPUT.vol]

The grid is 40 x 40 x 40 voxels over [-1, 1]^3, in Mitsuba's .vol format (version 3, float32,
one channel). Its density is a clear stone of density 0.1 crossed by dense veins (up to 4)
along a turbulent sine of x + y / 2, the classic procedural marble: the turbulence is a sum of
four octaves of trilinear value noise over a lattice hashed from integer coordinates, so the file
is the same bytes on every run and needs nothing beyond the standard library.
"""

import math
import struct
import sys

N = 40


def lattice(i, j, k):
    """A value in [0, 1) fixed by the integer point (i, j, k)."""
    h = (i * 73856093) ^ (j * 19349663) ^ (k * 83492791)
    h = (h ^ (h >> 13)) * 1274126177 & 0xFFFFFFFF
    return (h ^ (h >> 16)) / 2.0**32


def value_noise(x, y, z):
    i, j, k = math.floor(x), math.floor(y), math.floor(z)
    fx, fy, fz = x - i, y - j, z - k
    sx, sy, sz = (f * f * (3 - 2 * f) for f in (fx, fy, fz))
    total = 0.0
    for di in (0, 1):
        for dj in (0, 1):
            for dk in (0, 1):
                w = (sx if di else 1 - sx) * (sy if dj else 1 - sy) * (sz if dk else 1 - sz)
                total += w * lattice(i + di, j + dj, k + dk)
    return total


def turbulence(x, y, z):
    return sum(abs(2 * value_noise(x * 2**o * 2, y * 2**o * 2, z * 2**o * 2) - 1) / 2**o
               for o in range(4))


def density(x, y, z):
    phase = 5.0 * (x + 0.5 * y) + 6.0 * turbulence(x, y, z)
    vein = abs(math.sin(phase)) ** 4  # thin bands where the sine peaks
    return 0.1 + 3.9 * vein


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "docs/examples/marble/veins.vol"
    values = []
    for k in range(N):
        for j in range(N):
            for i in range(N):
                x, y, z = ((c + 0.5) / N * 2 - 1 for c in (i, j, k))
                values.append(density(x, y, z))
    with open(out, "wb") as f:
        f.write(b"VOL" + bytes([3]))
        f.write(struct.pack("<i", 1))
        f.write(struct.pack("<3i", N, N, N))
        f.write(struct.pack("<i", 1))
        f.write(struct.pack("<6f", -1, -1, -1, 1, 1, 1))
        f.write(struct.pack("<%df" % len(values), *values))
    print(f"wrote {out}: {N}^3 voxels, density {min(values):.3f} to {max(values):.3f}")


if __name__ == "__main__":
    main()
