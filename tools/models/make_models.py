#!/usr/bin/env python3
"""Writes the example puppets' meshes as OBJ + MTL into host/scenes/models/.

    python3 tools/models/make_models.py [OUT_DIR]

Every mesh is authored here from ellipsoids, surfaces of revolution and
sheets, so the files are ours to ship and can be made again byte for byte
(tests/models checks that the committed files are this script's output).
Coordinates: metres, y up, the puppet faces +z. Smooth normals; front
faces counter-clockwise seen from outside; sheets (wings, the ghost) are
two-sided, their back a copy 1 mm behind with its faces turned round.

The meshes, their origin and size (x by y by z, metres):

  stick_head.obj      a ball head with two dot eyes. Origin: the head's
                      centre. 0.20 x 0.22 x 0.20.
  stick_torso.obj     a slender rod, thicker at the shoulders. Origin: its
                      middle; runs along y from -0.20 to +0.20, 0.06 across.
  humanoid_head.obj   a head with hair, nose, ears and eyes, for a rigid
                      group (orientation: initial). Origin: the skull's
                      centre; chin at y = -0.095, crown (hair) at +0.10,
                      nose tip at z = +0.10. About 0.17 x 0.20 x 0.20.
  humanoid_torso.obj  chest, waist and hips with a short neck, oval in
                      section, for a rigid group. Origin: mid-chest
                      height; hips' bottom at y = -0.26, neck top at
                      +0.30, shoulders 0.34 across at y = +0.18, 0.21 deep.
  dragon_head.obj     a horned head with a long snout along +z and yellow
                      eyes. Origin: the skull's centre; snout tip at
                      z = +0.26, back of the skull at -0.12, horns up to
                      y = +0.18. About 0.20 x 0.27 x 0.38.
  dragon_wing.obj     a left wing's membrane (the puppet's left is +x),
                      spread flat in the x-z plane with an arched leading
                      edge up to y = +0.06: root along the z axis at x = 0
                      (z from +0.12 to -0.30; the scalloped trailing edge
                      reaches -0.32), tip at x = +0.45. 16 x 8 quads a
                      side, to bend when skinned. Mirror it (scale x by
                      -1) for the right.
  bird_body.obj       body, head, beak, eyes and a fanned tail. Origin:
                      the body's centre; beak tip at z = +0.20, tail end at
                      z = -0.20, head top at y = +0.085. About 0.14 x 0.14
                      x 0.40 (the tail fans out to 0.14 across).
  bird_wing.obj       a left wing, flat in the x-z plane: root along z at
                      x = 0 (z from +0.05 to -0.07), tapering to a tip at
                      x = +0.25. 12 x 6 quads a side. Mirror for the right.
  ghost.obj           the ghost's cloth for the freeform display mode: a
                      bell-shaped sheet facing +z, a round head widening
                      to a wavy hem, bulging 5 cm forward in the middle,
                      with two eyes. 24 x 16 quads a side. Origin: the
                      crown (top middle); hangs down to y = -0.50 (the
                      hem's waves reach -0.52), 0.26 wide at the head and
                      0.44 at the hem. Placed with its crown at
                      (0, 0.97, 0) it covers the ghost scene's 5 x 6
                      particle sheet (x +-0.18, y 0.95 .. 0.50).
"""
import math
import os
import sys

HEADER = "# {name}: made by tools/models/make_models.py; edit the script, not this file.\n"


class Part:
    """One named group of triangles wearing one material."""

    def __init__(self, name, material):
        self.name, self.material = name, material
        self.v, self.vt, self.f = [], [], []

    def moved(self, fn):
        self.v = [fn(p) for p in self.v]
        return self


def surface(name, material, point, nu, nv):
    """A grid surface point(u, v) for u, v in 0..1; faces whose corners
    coincide (poles) are left out."""
    part = Part(name, material)
    for j in range(nv + 1):
        for i in range(nu + 1):
            part.v.append(point(i / nu, j / nv))
            part.vt.append((i / nu, 1 - j / nv))
    row = nu + 1
    for j in range(nv):
        for i in range(nu):
            a, b = j * row + i, j * row + i + 1
            c, d = b + row, a + row
            for tri in ((a, b, c), (a, c, d)):
                if area(part.v, tri) > 1e-12:
                    part.f.append(tri)
    return part


def area(v, tri):
    n = cross(sub(v[tri[1]], v[tri[0]]), sub(v[tri[2]], v[tri[0]]))
    return math.sqrt(dot(n, n))


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def revolve(name, material, profile, centre=(0, 0, 0), sx=1.0, sz=1.0, nu=24, nv=16):
    """A surface of revolution about y through centre: profile(t) gives
    (radius, height) for t from 0 (bottom) to 1 (top). The angle runs from
    +z towards +x, so faces are counter-clockwise seen from outside."""
    def point(u, t):
        r, y = profile(t)
        a = 2 * math.pi * u
        return (centre[0] + sx * r * math.sin(a), centre[1] + y, centre[2] + sz * r * math.cos(a))

    return surface(name, material, point, nu, nv)


def ellipsoid(name, material, centre, radii, nu=24, nv=12):
    def profile(t):
        phi = math.pi * t
        return math.sin(phi), -radii[1] * math.cos(phi)

    return revolve(name, material, profile, centre, radii[0], radii[2], nu, nv)


def cap(name, material, centre, radii, top=0.55):
    """The top `top` of an ellipsoid's height as an open shell (hair)."""
    def profile(t):
        phi = math.pi * (1 - top * (1 - t))
        return math.sin(phi), -radii[1] * math.cos(phi)

    return revolve(name, material, profile, centre, radii[0], radii[2])


def cone_z(name, material, base, radius, length, nu=12):
    """A cone from base along +z, closed at its base."""
    def profile(t):
        if t < 0.25:
            return radius * t / 0.25, 0.0
        return radius * (1 - t) / 0.75, length * (t - 0.25) / 0.75

    part = revolve(name, material, profile, (0, 0, 0), 1, 1, nu, 8)
    # Turn y to +z (a quarter turn about x: (x, y, z) -> (x, -z, y)), then move.
    return part.moved(lambda p: (base[0] + p[0], base[1] - p[2], base[2] + p[1]))


def turn_x(deg, about):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))

    def fn(p):
        y, z = p[1] - about[1], p[2] - about[2]
        return (p[0], about[1] + c * y - s * z, about[2] + s * y + c * z)

    return fn


def two_sided(front):
    """A sheet's back: its faces turned round, 1 mm behind the front."""
    normals = smooth_normals(front)
    back = Part(front.name + "_back", front.material)
    back.v = [sub(p, tuple(0.001 * x for x in n)) for p, n in zip(front.v, normals)]
    back.vt = list(front.vt)
    back.f = [(a, c, b) for a, b, c in front.f]
    return [front, back]


def smooth_normals(part):
    """Area-weighted face normals summed at each position (so seams and
    poles, whose vertices repeat, are smooth too), made unit."""
    acc = {}
    key = [tuple(round(x, 6) for x in p) for p in part.v]
    for tri in part.f:
        n = cross(sub(part.v[tri[1]], part.v[tri[0]]), sub(part.v[tri[2]], part.v[tri[0]]))
        for k in tri:
            s = acc.setdefault(key[k], [0.0, 0.0, 0.0])
            for i in range(3):
                s[i] += n[i]
    out = []
    for k in key:
        s = acc.get(k, [0.0, 1.0, 0.0])
        length = math.sqrt(dot(s, s)) or 1.0
        out.append(tuple(x / length for x in s))
    return out


# ----------------------------------------------------------------- puppets

MATERIALS = {
    "ink": ((0.12, 0.12, 0.14), 20),
    "paper": ((0.92, 0.9, 0.84), 10),
    "skin": ((0.86, 0.68, 0.55), 16),
    "hair": ((0.3, 0.18, 0.1), 8),
    "eye": ((0.03, 0.03, 0.04), 120),
    "shirt": ((0.2, 0.35, 0.65), 8),
    "scales": ((0.2, 0.45, 0.22), 40),
    "horn": ((0.9, 0.86, 0.72), 60),
    "gold_eye": ((0.95, 0.75, 0.1), 120),
    "membrane": ((0.55, 0.12, 0.1), 12),
    "feather": ((0.85, 0.35, 0.15), 12),
    "beak": ((0.95, 0.7, 0.15), 40),
    "sheet": ((0.93, 0.93, 0.97), 6),
}


def eyes(material, x, y, z, radii):
    return [ellipsoid(f"eye_{side}", material, (sx * x, y, z), radii, 8, 5)
            for side, sx in (("l", 1), ("r", -1))]


def stick_head():
    return [ellipsoid("head", "paper", (0, 0, 0), (0.1, 0.11, 0.1))] + \
        eyes("eye", 0.035, 0.02, 0.092, (0.012, 0.014, 0.01))


def stick_torso():
    def profile(t):
        y = -0.2 + 0.4 * t
        r = 0.022 + 0.008 * t  # thicker at the shoulders
        end = min(t, 1 - t) / 0.06  # rounded ends
        return (r * math.sqrt(max(0.0, 1 - (1 - end) ** 2)) if end < 1 else r), y

    return [revolve("torso", "ink", profile, nu=16)]


def humanoid_head():
    return [
        ellipsoid("skull", "skin", (0, 0, 0), (0.075, 0.095, 0.085)),
        # The hair: the top of a slightly larger ellipsoid, tipped back so
        # it clears the brow in front and comes down behind.
        cap("hair", "hair", (0, 0.004, -0.004), (0.08, 0.098, 0.09), 0.38)
        .moved(turn_x(-25, (0, 0.004, -0.004))),
        ellipsoid("nose", "skin", (0, -0.01, 0.087), (0.012, 0.02, 0.014), 10, 6),
        ellipsoid("ear_l", "skin", (0.075, 0, 0), (0.012, 0.025, 0.018), 10, 6),
        ellipsoid("ear_r", "skin", (-0.075, 0, 0), (0.012, 0.025, 0.018), 10, 6),
    ] + eyes("eye", 0.028, 0.015, 0.074, (0.011, 0.011, 0.008))


def humanoid_torso():
    # (radius, height) from the hips' bottom to the neck's top.
    pts = [(0.0, -0.26), (0.12, -0.25), (0.14, -0.18), (0.125, -0.05), (0.15, 0.08),
           (0.17, 0.18), (0.15, 0.235), (0.05, 0.26), (0.045, 0.30), (0.0, 0.30)]

    def profile(t):
        x = t * (len(pts) - 1)
        k = min(int(x), len(pts) - 2)
        f = x - k
        return tuple(pts[k][i] + f * (pts[k + 1][i] - pts[k][i]) for i in range(2))

    return [revolve("torso", "shirt", profile, sz=0.62, nu=28, nv=3 * (len(pts) - 1))]


def dragon_head():
    horns = [cone_z(f"horn_{side}", "horn", (sx * 0.055, 0.06, -0.04), 0.022, 0.14)
             .moved(turn_x(-60, (0, 0.06, -0.04))) for side, sx in (("l", 1), ("r", -1))]
    return [
        ellipsoid("skull", "scales", (0, 0, 0), (0.1, 0.09, 0.12)),
        ellipsoid("snout", "scales", (0, -0.02, 0.14), (0.065, 0.055, 0.12)),
    ] + horns + eyes("gold_eye", 0.062, 0.035, 0.075, (0.018, 0.016, 0.014))


def wing(span, root_front, root_back, arch, scallops, nu, nv, material):
    """A wing flat in the x-z plane, root along z at x = 0: u runs out along
    the span (+x), v back from the leading edge; du x dv is +y, so the
    front faces up."""
    def point(u, v):
        lead = root_front * (1 - 0.6 * u)
        trail = root_back * (1 - u) ** 0.7 + scallops[1] * abs(math.sin(scallops[0] * math.pi * u))
        y = arch * math.sin(math.pi * u) * (1 - v)
        return (span * u, y, lead + v * (trail - lead))

    return two_sided(surface("membrane", material, point, nu, nv))


def bird_body():
    def tail_point(u, v):  # a fan spreading back from the body
        half = 0.02 + 0.05 * v
        return (half * (2 * u - 1), 0.01 + 0.03 * v, -0.08 - 0.12 * v)

    # u across (+x), v back (-z): du x dv is +y, the fan's front faces up.
    tail = two_sided(surface("tail", "feather", tail_point, 6, 4))
    return [
        ellipsoid("body", "feather", (0, 0, 0), (0.05, 0.05, 0.1)),
        ellipsoid("head", "feather", (0, 0.045, 0.1), (0.04, 0.04, 0.04)),
        cone_z("beak", "beak", (0, 0.04, 0.135), 0.014, 0.065),
    ] + tail + eyes("eye", 0.03, 0.055, 0.122, (0.008, 0.008, 0.006))


def ghost():
    def half_width(v):
        if v < 0.3:  # the round head
            return 0.13 * math.sqrt(max(0.0, 1 - (1 - v / 0.3) ** 2))
        if v < 0.5:  # a slight neck
            return 0.13 - 0.02 * math.sin(math.pi * (v - 0.3) / 0.2)
        return 0.13 + 0.09 * ((v - 0.5) / 0.5) ** 1.2

    def point(u, v):
        # u runs across towards -x and v down, so du x dv is +z: the front.
        s = 1 - 2 * u
        hem = 0.02 * v ** 4 * (0.5 - 0.5 * math.cos(2 * math.pi * 5 * u))
        return (half_width(v) * s, -0.5 * v - hem, 0.05 * math.cos(0.5 * math.pi * s))

    return two_sided(surface("cloth", "sheet", point, 24, 16)) + \
        eyes("eye", 0.045, -0.09, 0.044, (0.018, 0.026, 0.006))


MESHES = [
    ("stick_head", stick_head),
    ("stick_torso", stick_torso),
    ("humanoid_head", humanoid_head),
    ("humanoid_torso", humanoid_torso),
    ("dragon_head", dragon_head),
    ("dragon_wing", lambda: wing(0.45, 0.12, -0.30, 0.06, (3, -0.05), 16, 8, "membrane")),
    ("bird_body", bird_body),
    ("bird_wing", lambda: wing(0.25, 0.05, -0.07, 0.02, (0, 0.0), 12, 6, "feather")),
    ("ghost", ghost),
]

# ------------------------------------------------------------------ output


def num(x, digits):
    s = f"{x:.{digits}f}"
    return s[1:] if s.startswith("-") and float(s) == 0 else s


def obj_text(name, parts):
    out = [HEADER.format(name=name + ".obj"), f"mtllib {name}.mtl\n"]
    base = 1
    for part in parts:
        normals = smooth_normals(part)
        out.append(f"o {part.name}\n")
        out += [f"v {num(p[0], 4)} {num(p[1], 4)} {num(p[2], 4)}\n" for p in part.v]
        out += [f"vt {num(t[0], 3)} {num(t[1], 3)}\n" for t in part.vt]
        out += [f"vn {num(n[0], 3)} {num(n[1], 3)} {num(n[2], 3)}\n" for n in normals]
        out.append(f"usemtl {part.material}\n")
        for tri in part.f:
            out.append("f " + " ".join(f"{k + base}/{k + base}/{k + base}" for k in tri) + "\n")
        base += len(part.v)
    return "".join(out)


def mtl_text(name, parts):
    out = [HEADER.format(name=name + ".mtl")]
    seen = []
    for part in parts:
        if part.material in seen:
            continue
        seen.append(part.material)
        rgb, shininess = MATERIALS[part.material]
        out.append(f"\nnewmtl {part.material}\n")
        out.append("Kd " + " ".join(num(c, 3) for c in rgb) + "\n")
        out.append(f"Ka 0.000 0.000 0.000\nKs 0.200 0.200 0.200\nNs {shininess}\nd 1\nillum 2\n")
    return "".join(out)


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    out_dir = argv[1] if len(argv) > 1 else os.path.join(here, "..", "..", "host", "scenes",
                                                          "models")
    os.makedirs(out_dir, exist_ok=True)
    for name, make in MESHES:
        parts = make()
        for ext, text in (("obj", obj_text(name, parts)), ("mtl", mtl_text(name, parts))):
            with open(os.path.join(out_dir, f"{name}.{ext}"), "w", newline="\n") as f:
                f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
