#!/usr/bin/python3
"""Writes the glTF showcase asset docs/examples/showcase/ (issue 14).

    /usr/bin/python3 scripts/make-showcase.py [OUTPUT_DIR]

All geometry and textures are generated here (no third-party meshes), and the output is the
same bytes on every run: showcase.gltf (glTF 2.0 JSON), showcase.bin (its one buffer) and the
two base colour textures floor.png and vase.png. The scene file docs/examples/showcase.json
includes the asset and adds a dim sky.

Content, every mesh with smooth NORMALs (y up, the floor at y = 0; glTF material names in
quotes):
  * floor      - a 40 x 40 quad, "floor": a repeating tile texture (diffuse, 0.25 tiles);
  * vase       - a turned, hollow vase 0.78 high, "ceramic": a painted band texture (diffuse,
                 TEXCOORD_0);
  * gold-torus - an upright torus, "gold": metallic, roughness 0.3;
  * jade-knot  - a closed trefoil-knot tube, "jade": KHR_materials_transmission, _ior (1.5),
                 _volume and _volume_scatter, green, roughness 0.3;
  * wax-candle - a closed pillar candle with a melted top, "wax": the same extensions (ior
                 1.45), ivory, roughness 0.2;
  * a perspective camera and a KHR_lights_punctual spot light (the key light, behind left).
The translucent meshes are topologically closed (no duplicated seam or pole vertices) and stand
a millimetre above the floor, so that no volume touches another shape with a whole face.
"""

import json
import math
import os
import struct
import sys
import zlib

import numpy as np

GAP = 1e-3  # height of the translucent objects above the floor (see the docstring)


# --------------------------------------------------------------------------------------------
# PNG (8-bit RGB, no dependencies beyond zlib)


def write_png(path, rgb):
    """rgb: uint8 array (height, width, 3). Declares sRGB (glTF base colours are sRGB)."""
    h, w, _ = rgb.shape
    raw = b"".join(b"\x00" + rgb[y].tobytes() for y in range(h))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n"
    png += chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"sRGB", b"\x00")
    png += chunk(b"IDAT", zlib.compress(raw, 9))
    png += chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def to_srgb8(linear):
    c = np.clip(linear, 0.0, 1.0)
    s = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)
    return np.round(s * 255.0).astype(np.uint8)


def smoothstep(e0, e1, x):
    t = np.clip((x - e0) / (e1 - e0), 0.0, 1.0)
    return t * t * (3 - 2 * t)


def value_noise(h, w, cells, seed):
    """Smooth tileable value noise in [0, 1] (bilinear-smoothstep between lattice values)."""
    rng = np.random.RandomState(seed)
    lattice = rng.random_sample((cells, cells))
    y = (np.arange(h) + 0.5) / h * cells
    x = (np.arange(w) + 0.5) / w * cells
    y0 = np.floor(y).astype(int)
    x0 = np.floor(x).astype(int)
    fy = smoothstep(0, 1, y - y0)[:, None]
    fx = smoothstep(0, 1, x - x0)[None, :]
    a = lattice[y0 % cells][:, x0 % cells]
    b = lattice[y0 % cells][:, (x0 + 1) % cells]
    c = lattice[(y0 + 1) % cells][:, x0 % cells]
    d = lattice[(y0 + 1) % cells][:, (x0 + 1) % cells]
    return (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy


def floor_texture(size=256):
    """2 x 2 stone tiles in two warm greys with grout lines; tiles seamlessly (REPEAT)."""
    px = (np.arange(size) + 0.5) / size
    u, v = np.meshgrid(px, px)
    tile = ((np.floor(u * 2) + np.floor(v * 2)) % 2)[..., None]
    light = np.array([0.42, 0.38, 0.33])
    dark = np.array([0.35, 0.32, 0.28])
    base = light * (1 - tile) + dark * tile
    mottle = 0.6 * value_noise(size, size, 8, 1) + 0.4 * value_noise(size, size, 32, 2)
    base = base * (0.88 + 0.24 * mottle[..., None])
    # Grout: distance to the nearest tile edge, in tile units.
    fu = (u * 2) % 1
    fv = (v * 2) % 1
    edge = np.minimum(np.minimum(fu, 1 - fu), np.minimum(fv, 1 - fv))
    grout = 1 - smoothstep(0.008, 0.022, edge)
    base = base * (1 - grout[..., None]) + np.array([0.16, 0.15, 0.14]) * grout[..., None]
    return to_srgb8(base)


def vase_texture(w=512, h=256):
    """Cream glaze with cobalt bands and a zigzag band; u around the vase, v down its profile
    (0 at the bottom's centre, 1 at the inner bottom's centre; the outer wall is v < 0.5)."""
    u, v = np.meshgrid((np.arange(w) + 0.5) / w, (np.arange(h) + 0.5) / h)
    cream = np.array([0.80, 0.72, 0.58])
    cobalt = np.array([0.05, 0.10, 0.38])
    terracotta = np.array([0.55, 0.20, 0.08])
    col = np.broadcast_to(cream, (h, w, 3)).copy()
    col *= (0.93 + 0.14 * value_noise(h, w, 16, 3))[..., None]

    def band(v0, v1, colour, soft=0.002):
        m = smoothstep(v0 - soft, v0 + soft, v) * (1 - smoothstep(v1 - soft, v1 + soft, v))
        col[:] = col * (1 - m[..., None]) + colour * m[..., None]

    # The outer wall runs from about v = 0.06 (foot) to about v = 0.46 (lip).
    band(0.075, 0.095, cobalt)
    band(0.105, 0.112, terracotta)
    # Zigzag: 12 teeth around, between two thin lines.
    zig_centre = 0.20 + 0.03 * (2 * np.abs((u * 12) % 1 - 0.5) * 2 - 1)
    m = 1 - smoothstep(0.006, 0.010, np.abs(v - zig_centre))
    col[:] = col * (1 - m[..., None]) + cobalt * m[..., None]
    band(0.160, 0.166, cobalt)
    band(0.234, 0.240, cobalt)
    # Dots between the zigzag teeth.
    du = (u * 24) % 1 - 0.5
    dots = 1 - smoothstep(0.16, 0.22, np.hypot(du, (v - 0.27) * 24 * 2.2))
    col[:] = col * (1 - dots[..., None]) + terracotta * dots[..., None]
    band(0.300, 0.330, cobalt)
    band(0.400, 0.430, cobalt)
    band(0.345, 0.352, terracotta)
    return to_srgb8(col)


# --------------------------------------------------------------------------------------------
# Geometry


def normalize(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


class Profile:
    """A 2D curve (r, y), r >= 0, traversed from the bottom pole (r = 0) so that the solid lies
    to its left; the outward normal is the tangent turned clockwise, (dy, -dr)."""

    def __init__(self, start, normal_degrees):
        self.points = [np.array(start, float)]
        self.normals = [unit(normal_degrees)]

    def _add(self, pts, nrms):
        for p, n in zip(pts, nrms):
            self.points.append(np.array(p, float))
            self.normals.append(np.array(n, float) / np.linalg.norm(n))

    def normal_degrees(self):
        n = self.normals[-1]
        return math.degrees(math.atan2(n[1], n[0]))

    def line(self, end, n):
        a = self.points[-1]
        b = np.array(end, float)
        t = b - a
        normal = np.array([t[1], -t[0]])
        self._add([a + (b - a) * i / n for i in range(1, n + 1)], [normal] * n)

    def turn(self, radius, to_degrees, n):
        """Round corner of the given radius from the current point and normal to the normal
        to_degrees: convex (the normal turns counter-clockwise, the centre inside the solid)
        when to_degrees is above the current normal's angle, else concave."""
        a0 = self.normal_degrees()
        sign = 1.0 if to_degrees > a0 else -1.0
        centre = self.points[-1] - sign * radius * unit(a0)
        angles = np.linspace(a0, to_degrees, n + 1)[1:]
        self._add([centre + sign * radius * unit(a) for a in angles], [unit(a) for a in angles])

    def curve(self, f, t0, t1, n):
        """Parametric (r(t), y(t)) from t0 (the current point) to t1; derivatives by central
        differences."""
        h = 1e-6
        ts = np.linspace(t0, t1, n + 1)[1:]
        pts = [np.array(f(t)) for t in ts]
        tans = [np.array(f(t + h)) - np.array(f(t - h)) for t in ts]
        self._add(pts, [np.array([d[1], -d[0]]) for d in tans])

    def arrays(self):
        p = np.array(self.points)
        n = np.array(self.normals)
        p[np.abs(p[:, 0]) < 1e-12, 0] = 0.0
        return p, n


def unit(degrees):
    a = math.radians(degrees)
    return np.array([math.cos(a), math.sin(a)])


def hermite(xs, ys, slope0, slope1):
    """C1 cubic through (xs, ys) with Catmull-Rom slopes inside and the given end slopes;
    returns f(x) and f'(x)."""
    xs, ys = np.asarray(xs, float), np.asarray(ys, float)
    m = np.empty_like(ys)
    m[1:-1] = (ys[2:] - ys[:-2]) / (xs[2:] - xs[:-2])
    m[0], m[-1] = slope0, slope1

    def f(x):
        i = int(np.clip(np.searchsorted(xs, x) - 1, 0, len(xs) - 2))
        h = xs[i + 1] - xs[i]
        t = (x - xs[i]) / h
        return ((2 * t**3 - 3 * t**2 + 1) * ys[i] + (t**3 - 2 * t**2 + t) * h * m[i]
                + (-2 * t**3 + 3 * t**2) * ys[i + 1] + (t**3 - t**2) * h * m[i + 1])

    return f


def lathe(profile, segments, with_uv):
    """Surface of revolution about +y. Points with r = 0 are poles. Without texture coordinates
    every ring is shared all the way round and each pole is one vertex, so a profile from pole to
    pole gives a topologically closed mesh; with them the seam column (u = 1) and the poles (one
    vertex per segment) are duplicated."""
    pts, nrm = profile.arrays()
    arclen = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    vcoord = arclen / arclen[-1]
    positions, normals, uvs, rows = [], [], [], []
    for (r, y), (nr, ny), v in zip(pts, nrm, vcoord):
        pole = r == 0.0
        if pole:
            nr, ny = 0.0, math.copysign(1.0, ny)
        count = (segments if with_uv else 1) if pole else (segments + 1 if with_uv else segments)
        row = []
        for j in range(count):
            u = (j + 0.5) / segments if pole else j / segments
            a = 2 * math.pi * u
            # Angle measured so that u grows counter-clockwise seen from above (+y), starting at
            # +z: x = sin a, z = cos a.
            s, c = math.sin(a), math.cos(a)
            row.append(len(positions))
            positions.append((r * s, y, r * c))
            normals.append((nr * s, ny, nr * c))
            uvs.append((u, v))
        rows.append((pole, row))
    tris = []
    for (pole0, r0), (pole1, r1) in zip(rows[:-1], rows[1:]):
        for j in range(segments):
            j1 = (j + 1) % len(r0) if not pole0 else None
            k1 = (j + 1) % len(r1) if not pole1 else None
            if pole0:
                tris.append((r0[j % len(r0)], r1[j], r1[k1]))
            elif pole1:
                tris.append((r0[j], r1[j % len(r1)], r0[j1]))
            else:
                tris.append((r0[j], r1[j], r1[k1]))
                tris.append((r0[j], r1[k1], r0[j1]))
    # Seen from outside a profile going up on the +z side with u growing toward +x: (a, b, c) =
    # (lower, upper, upper-next) runs clockwise; flip to glTF's counter-clockwise.
    tris = [(a, c, b) for a, b, c in tris]
    mesh = {"positions": np.array(positions), "normals": normalize(np.array(normals)),
            "indices": np.array(tris, dtype=np.uint32)}
    if with_uv:
        mesh["uvs"] = np.array(uvs)
    return mesh


def torus(major, minor, n_major, n_minor):
    """Torus about +y, closed (indices wrap; no seam vertices)."""
    i = np.arange(n_major)[:, None]
    j = np.arange(n_minor)[None, :]
    a = 2 * np.pi * i / n_major
    b = 2 * np.pi * j / n_minor
    ring = np.stack([np.cos(a) * np.ones_like(b), np.zeros_like(a * b), np.sin(a) * np.ones_like(b)], -1)
    normal = ring * np.cos(b)[..., None] + np.array([0.0, 1.0, 0.0]) * np.sin(b)[..., None]
    pos = ring * major + normal * minor
    return tube_mesh(pos.reshape(-1, 3), normal.reshape(-1, 3), n_major, n_minor)


def tube_mesh(pos, nrm, n_along, n_around):
    tris = []
    for i in range(n_along):
        i1 = (i + 1) % n_along
        for j in range(n_around):
            j1 = (j + 1) % n_around
            a, b = i * n_around + j, i1 * n_around + j
            c, d = i1 * n_around + j1, i * n_around + j1
            tris.append((a, b, c))
            tris.append((a, c, d))
    mesh = {"positions": pos, "normals": normalize(nrm), "indices": np.array(tris, dtype=np.uint32)}
    return orient_outward(mesh)


def torus_knot(p, q, radius, amplitude, tube, n_along, n_around):
    """Closed tube around the (p, q) torus knot, axis +z. Frenet frames are periodic on the
    closed curve, so the tube closes without a twist seam."""
    t = 2 * np.pi * np.arange(n_along) / n_along

    def curve(t):
        rr = radius + amplitude * np.cos(q * t)
        return np.stack([rr * np.cos(p * t), rr * np.sin(p * t), amplitude * np.sin(q * t)], -1)

    h = 1e-4
    c = curve(t)
    d1 = (curve(t + h) - curve(t - h)) / (2 * h)
    d2 = (curve(t + h) - 2 * c + curve(t - h)) / (h * h)
    tangent = normalize(d1)
    binormal = normalize(np.cross(d1, d2))
    normal = np.cross(binormal, tangent)
    # Curvature radius must exceed the tube radius, and distant parts of the curve must stay
    # more than a tube diameter apart, or the tube would intersect itself.
    curvature = np.linalg.norm(np.cross(d1, d2), axis=1) / np.linalg.norm(d1, axis=1) ** 3
    assert 1 / curvature.max() > tube * 1.2, "tube too thick for the knot's curvature"
    dist = np.linalg.norm(c[:, None, :] - c[None, :, :], axis=-1)
    idx = np.arange(n_along)
    sep = np.abs(idx[:, None] - idx[None, :])
    sep = np.minimum(sep, n_along - sep)
    far = sep > n_along // 8
    assert dist[far].min() > 2.4 * tube, "knot strands too close: %g" % dist[far].min()
    phi = 2 * np.pi * np.arange(n_around) / n_around
    rad = normal[:, None, :] * np.cos(phi)[None, :, None] + binormal[:, None, :] * np.sin(phi)[None, :, None]
    pos = c[:, None, :] + tube * rad
    return tube_mesh(pos.reshape(-1, 3), rad.reshape(-1, 3), n_along, n_around)


def signed_volume(mesh):
    p = mesh["positions"][mesh["indices"]]
    return np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2])).sum() / 6


def orient_outward(mesh):
    if signed_volume(mesh) < 0:
        mesh["indices"] = mesh["indices"][:, [0, 2, 1]].copy()
    return mesh


def check_closed(mesh, name):
    """Every edge, vertices welded by position, is shared by exactly two triangles in opposite
    directions (an oriented closed 2-manifold)."""
    keys = {}
    weld = []
    for p in np.round(mesh["positions"], 9):
        weld.append(keys.setdefault(tuple(p), len(keys)))
    edges = {}
    for tri in mesh["indices"]:
        w = [weld[i] for i in tri]
        assert len(set(w)) == 3, name + ": degenerate triangle"
        for a, b in ((w[0], w[1]), (w[1], w[2]), (w[2], w[0])):
            edges[(a, b)] = edges.get((a, b), 0) + 1
    for (a, b), n in edges.items():
        assert n == 1 and edges.get((b, a)) == 1, name + ": not closed at edge %d-%d" % (a, b)
    assert signed_volume(mesh) > 0, name + ": inward winding"


def check_normals(mesh, name):
    """Vertex normals agree with the faces around them (smooth shading that fits the winding)."""
    p = mesh["positions"][mesh["indices"]]
    fn = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    agree = np.einsum("ij,ij->i", normalize(fn), mesh["normals"][mesh["indices"]].mean(axis=1))
    assert agree.min() > 0.5, name + ": vertex normals disagree with the winding (%g)" % agree.min()


def rotation(axis, degrees):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    half = math.radians(degrees) / 2
    q = np.concatenate([axis * math.sin(half), [math.cos(half)]])  # x, y, z, w (glTF order)
    x, y, z, w = q
    m = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    return q, m


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return np.array([aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw,
                     aw * bw - ax * bx - ay * by - az * bz])


def look_at_matrix(eye, target, up=(0, 1, 0)):
    """glTF node matrix (column-major) of a camera or spot light at eye looking at target: its
    local -z points at the target, local +y is up."""
    eye = np.asarray(eye, float)
    back = normalize(eye - np.asarray(target, float))
    right = normalize(np.cross(up, back))
    upv = np.cross(back, right)
    m = np.identity(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = right, upv, back, eye
    return [float(x) for x in m.T.reshape(-1)]


# --------------------------------------------------------------------------------------------
# The objects


def vase_profile():
    """Baluster vase 0.62 high: foot, belly, narrow neck, flared lip, 12 mm walls, hollow."""
    wall = 0.006  # lip radius; the wall is twice as thick
    ys = [0.015, 0.05, 0.14, 0.22, 0.33, 0.44, 0.52, 0.62]
    rs = [0.115, 0.13, 0.19, 0.205, 0.17, 0.095, 0.088, 0.125]
    r_of_y = hermite(ys, rs, 0.0, 0.6)
    y_top = ys[-1]

    def outer(y):
        return (r_of_y(y), y)

    def outer_normal(y):
        h = 1e-6
        d = (r_of_y(y + h) - r_of_y(y - h)) / (2 * h)
        return np.array([1.0, -d]) / math.hypot(1.0, d)

    def inner(t):  # the outer wall offset inward by 2 * wall, from the top down
        y = y_top - t
        return tuple(np.array(outer(y)) - 2 * wall * outer_normal(y))

    pr = Profile((0.0, 0.0), -90)
    pr.line((0.1, 0.0), 4)
    pr.turn(0.015, 0, 4)
    pr.curve(outer, ys[0], y_top, 28)
    n_top = pr.normal_degrees()
    pr.turn(wall, n_top + 180, 6)
    pr.curve(inner, 0.0, y_top - 0.09, 16)
    pr.turn(0.03, 90, 6)
    pr.line((0.0, pr.points[-1][1]), 5)
    return pr


def candle_profile():
    """Pillar candle 0.4 wide and 0.52 high with rounded edges and a melted pool on top."""
    radius, height, edge = 0.2, 0.52, 0.045
    pr = Profile((0.0, 0.0), -90)
    pr.line((radius - 0.02, 0.0), 4)
    pr.turn(0.02, 0, 5)
    pr.line((radius, height - edge), 3)
    pr.turn(edge, 90, 10)
    r0 = radius - edge

    def pool(t):  # the top sinks 4 cm toward the centre, level at the rim and at the centre
        return (r0 * (1 - t), height - 0.04 * math.sin(math.pi / 2 * t) ** 2)

    pr.curve(pool, 0.0, 1.0, 12)
    return pr


def place(mesh, rotations, xz, lift):
    """Rotates the mesh (node rotation), returns the node translation that puts its lowest point
    at y = lift over the floor at x, z."""
    q = np.array([0.0, 0.0, 0.0, 1.0])
    m = np.identity(3)
    for axis, degrees in rotations:
        qi, mi = rotation(axis, degrees)
        q = quat_mul(qi, q)
        m = mi @ m
    lowest = (mesh["positions"] @ m.T)[:, 1].min()
    return q, [xz[0], lift - lowest, xz[1]], m


# --------------------------------------------------------------------------------------------
# glTF writer


class Gltf:
    def __init__(self):
        self.bin = bytearray()
        self.doc = {"asset": {"version": "2.0", "generator": "snee scripts/make-showcase.py"},
                    "scene": 0, "scenes": [{"name": "showcase", "nodes": []}], "nodes": [],
                    "meshes": [], "materials": [], "accessors": [], "bufferViews": [],
                    "buffers": []}

    def view(self, data, target):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin),
                                        "byteLength": len(data), "target": target})
        self.bin += data
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, array, kind, target, minmax=False):
        if kind == "SCALAR":
            data = np.ascontiguousarray(array, dtype="<u4")
            ctype = 5125
        else:
            data = np.ascontiguousarray(array, dtype="<f4")
            ctype = 5126
        acc = {"bufferView": self.view(data.tobytes(), target), "componentType": ctype,
               "count": int(data.shape[0]), "type": kind}
        if minmax:
            acc["min"] = [float(x) for x in data.min(axis=0)]
            acc["max"] = [float(x) for x in data.max(axis=0)]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def mesh(self, name, mesh, material):
        attributes = {"POSITION": self.accessor(mesh["positions"], "VEC3", 34962, True),
                      "NORMAL": self.accessor(mesh["normals"], "VEC3", 34962)}
        if "uvs" in mesh:
            attributes["TEXCOORD_0"] = self.accessor(mesh["uvs"], "VEC2", 34962)
        indices = self.accessor(mesh["indices"].reshape(-1), "SCALAR", 34963)
        self.doc["meshes"].append({"name": name, "primitives": [
            {"attributes": attributes, "indices": indices, "material": material, "mode": 4}]})
        return len(self.doc["meshes"]) - 1

    def node(self, node):
        self.doc["nodes"].append(node)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)
        return len(self.doc["nodes"]) - 1


def rounded(x, digits=6):
    if isinstance(x, float):
        return round(x, digits)
    if isinstance(x, (list, tuple)):
        return [rounded(v, digits) for v in x]
    return x


def translucent(name, ior, roughness, sigma_t, multiscatter, anisotropy):
    """A glTF material for a scattering solid: sigma_t per unit is stored as the attenuation
    colour after attenuationDistance (Beer-Lambert), the colour as the multiple-scattering
    albedo of KHR_materials_volume_scatter."""
    distance = 0.1
    attenuation = [round(math.exp(-s * distance), 6) for s in sigma_t]
    return {"name": name,
            "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0.0,
                                     "roughnessFactor": roughness},
            "extensions": {
                "KHR_materials_transmission": {"transmissionFactor": 1.0},
                "KHR_materials_ior": {"ior": ior},
                "KHR_materials_volume": {"thicknessFactor": 0.2, "attenuationColor": attenuation,
                                         "attenuationDistance": distance},
                "KHR_materials_volume_scatter": {"multiscatterColor": multiscatter,
                                                 "scatterAnisotropy": anisotropy}}}


def build(out_dir):
    os.makedirs(out_dir, exist_ok=True)
    write_png(os.path.join(out_dir, "floor.png"), floor_texture())
    write_png(os.path.join(out_dir, "vase.png"), vase_texture())

    g = Gltf()
    doc = g.doc
    doc["images"] = [{"name": "floor", "uri": "floor.png"}, {"name": "vase", "uri": "vase.png"}]
    doc["samplers"] = [{"wrapS": 10497, "wrapT": 10497},   # floor: repeat
                       {"wrapS": 10497, "wrapT": 33071}]   # vase: repeat around, clamp along
    doc["textures"] = [{"sampler": 0, "source": 0}, {"sampler": 1, "source": 1}]
    doc["materials"] = [
        {"name": "floor", "pbrMetallicRoughness": {
            "baseColorTexture": {"index": 0}, "metallicFactor": 0.0, "roughnessFactor": 1.0}},
        {"name": "ceramic", "pbrMetallicRoughness": {
            "baseColorTexture": {"index": 1}, "metallicFactor": 0.0, "roughnessFactor": 0.6}},
        {"name": "gold", "pbrMetallicRoughness": {
            "baseColorFactor": [1.0, 0.766, 0.336, 1.0], "metallicFactor": 1.0,
            "roughnessFactor": 0.3}},
        translucent("jade", 1.5, 0.3, sigma_t=[22.0, 18.0, 21.0],
                    multiscatter=[0.20, 0.66, 0.36], anisotropy=0.2),
        translucent("wax", 1.45, 0.2, sigma_t=[12.0, 13.0, 14.0],
                    multiscatter=[0.95, 0.80, 0.55], anisotropy=0.3),
    ]

    # Floor: 40 x 40 at y = 0, 0.25-unit tiles (the texture holds 2 x 2 tiles per repeat).
    half, repeats = 20.0, 80.0
    floor = {"positions": np.array([[-half, 0, -half], [-half, 0, half], [half, 0, half], [half, 0, -half]]),
             "normals": np.array([[0.0, 1.0, 0.0]] * 4),
             "uvs": np.array([[0, 0], [0, repeats], [repeats, repeats], [repeats, 0]], float),
             "indices": np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32)}

    vase = lathe(vase_profile(), 48, with_uv=True)
    vase["positions"] *= 1.25  # 0.78 high
    gold = torus(0.26, 0.075, 64, 24)
    jade = torus_knot(2, 3, 0.19, 0.095, 0.06, 192, 16)
    wax = lathe(candle_profile(), 64, with_uv=False)

    check_closed(gold, "gold")
    check_closed(jade, "jade")
    check_closed(wax, "wax")
    for name, m in (("vase", vase), ("gold", gold), ("jade", jade), ("wax", wax), ("floor", floor)):
        check_normals(m, name)

    objects = [
        # name, mesh, material, rotations (applied in order), (x, z), lift
        ("floor", floor, 0, [], (0.0, 0.0), 0.0),
        ("vase", vase, 1, [((0, 1, 0), 200)], (-1.0, -0.45), 0.0),
        ("gold-torus", gold, 2, [((1, 0, 0), 90), ((0, 1, 0), -35)], (1.05, -0.4), 0.0),
        ("jade-knot", jade, 3, [((0, 1, 0), -20)], (-0.25, 0.2), GAP),
        ("wax-candle", wax, 4, [], (0.45, 0.45), GAP),
    ]
    world = {}
    for name, mesh, material, rots, xz, lift in objects:
        index = g.mesh(name, mesh, material)
        node = {"name": name, "mesh": index}
        if name != "floor":
            q, t, m = place(mesh, rots, xz, lift)
            if rots:
                node["rotation"] = rounded([float(x) for x in q], 9)
            node["translation"] = rounded([float(x) for x in t], 9)
            world[name] = mesh["positions"] @ m.T + np.array(t)
        g.node(node)

    # Objects must stay apart (disjoint volumes; the floor only touched).
    names = sorted(world)
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            lo = np.maximum(world[a].min(0), world[b].min(0))
            hi = np.minimum(world[a].max(0), world[b].max(0))
            assert not np.all(lo < hi), "bounding boxes of %s and %s overlap" % (a, b)

    aspect = 16 / 9
    doc["cameras"] = [{"name": "camera", "type": "perspective", "perspective": {
        "yfov": round(math.radians(28.0), 9), "aspectRatio": round(aspect, 9),
        "znear": 0.05, "zfar": 100.0}}]
    g.node({"name": "camera", "camera": 0,
            "matrix": rounded(look_at_matrix((0.0, 1.55, 3.3), (0.0, 0.3, -0.1)), 9)})

    doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "key", "type": "spot", "color": [1.0, 0.95, 0.88], "intensity": 60.0,
         "spot": {"innerConeAngle": round(math.radians(18.0), 9),
                  "outerConeAngle": round(math.radians(30.0), 9)}}]}}
    g.node({"name": "key-light", "extensions": {"KHR_lights_punctual": {"light": 0}},
            "matrix": rounded(look_at_matrix((-2.2, 3.0, -2.0), (0.0, 0.25, 0.0)), 9)})

    doc["extensionsUsed"] = ["KHR_lights_punctual", "KHR_materials_ior",
                             "KHR_materials_transmission", "KHR_materials_volume",
                             "KHR_materials_volume_scatter"]
    doc["buffers"] = [{"uri": "showcase.bin", "byteLength": len(g.bin)}]

    with open(os.path.join(out_dir, "showcase.bin"), "wb") as f:
        f.write(bytes(g.bin))
    with open(os.path.join(out_dir, "showcase.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")

    for name, mesh, *_ in objects:
        print("%-11s %6d triangles %6d vertices" % (name, len(mesh["indices"]), len(mesh["positions"])))
    total = sum(os.path.getsize(os.path.join(out_dir, f)) for f in
                ("showcase.gltf", "showcase.bin", "floor.png", "vase.png"))
    print("wrote %s (%d bytes in all)" % (out_dir, total))


if __name__ == "__main__":
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    build(sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "docs", "examples", "showcase"))
