#!/usr/bin/env python3
"""Writes scenes/creature.rib: a four-legged Catmull-Clark creature walking over 48 frames.

One closed quad cage (torso, neck and head, four legs, tail, ears) made by extruding faces of a
box, so it has extraordinary vertices where limbs leave the body. Creases: a semi-sharp ridge
along the spine, sharp claws at the feet, sharp tips on the ears. The cage deforms every frame
(legs swing in a walk cycle, the head nods, the tail wags, the body bobs): a SubdivisionMesh per
motion key, the same topology with new points.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
from ribgen import attribute_block, fmt, patch, points, write_scene  # noqa: E402

FRAMES = 48


class Cage:
    """A quad mesh grown by extruding faces; each vertex remembers the limb it belongs to."""

    def __init__(self):
        self.v = []      # rest positions
        self.limb = []   # (limb name, weight 0..1 along the limb), or None for the torso
        self.faces = []

    def vert(self, p, limb=None):
        self.v.append(list(p))
        self.limb.append(limb)
        return len(self.v) - 1

    def box(self, x0, x1, y0, y1, z0, z1, nx, ny, nz):
        """A box of nx x ny x nz quads per side, faces facing out; returns faces by side."""
        idx = {}

        def at(i, j, k):
            key = (i, j, k)
            if key not in idx:
                idx[key] = self.vert((x0 + (x1 - x0) * i / nx, y0 + (y1 - y0) * j / ny, z0 + (z1 - z0) * k / nz))
            return idx[key]

        sides = {}

        def grid(name, n1, n2, f, flip):
            out = {}
            for a in range(n1):
                for b in range(n2):
                    q = [f(a, b), f(a + 1, b), f(a + 1, b + 1), f(a, b + 1)]
                    if flip:
                        q.reverse()
                    self.faces.append(q)
                    out[(a, b)] = len(self.faces) - 1
            sides[name] = out

        grid("bottom", nx, nz, lambda a, b: at(a, 0, b), False)
        grid("top", nx, nz, lambda a, b: at(a, ny, b), True)
        grid("back", ny, nz, lambda a, b: at(0, a, b), True)
        grid("front", ny, nz, lambda a, b: at(nx, a, b), False)
        grid("left", nx, ny, lambda a, b: at(a, b, 0), True)
        grid("right", nx, ny, lambda a, b: at(a, b, nz), False)
        return sides

    def extrude(self, face, offsets, limb, scales):
        """Pushes a face out in segments: segment i is the face moved by offsets[i] and scaled by
        scales[i] about its centre."""
        ring = base = self.faces[face]
        centre = [sum(self.v[i][c] for i in ring) / 4 for c in range(3)]
        n = len(offsets)
        for s, (off, sc) in enumerate(zip(offsets, scales)):
            new = []
            for i in base:
                p = [centre[c] + (self.v[i][c] - centre[c]) * sc + off[c] for c in range(3)]
                new.append(self.vert(p, (limb, (s + 1) / n)))
            for a in range(4):
                b = (a + 1) % 4
                self.faces.append([ring[a], ring[b], new[b], new[a]])
            ring = new
        self.faces[face] = ring
        return ring


def build():
    c = Cage()
    sides = c.box(-1.6, 1.6, 0.0, 1.2, -0.75, 0.75, 4, 2, 3)
    bottom, front, back, top = (sides[k] for k in ("bottom", "front", "back", "top"))
    legs = {}
    for name, key in (("hind_l", (0, 0)), ("hind_r", (0, 2)), ("fore_l", (3, 0)), ("fore_r", (3, 2))):
        legs[name] = c.extrude(bottom[key], [(0, -0.55, 0), (0, -1.1, 0), (0.12, -1.5, 0)], name, [0.85, 0.7, 0.8])
    head = c.extrude(front[(1, 1)], [(0.45, 0.35, 0), (0.85, 0.8, 0), (1.35, 1.0, 0), (1.95, 0.95, 0)],
                     "head", [0.9, 0.95, 1.55, 1.1])
    c.extrude(back[(1, 1)], [(-0.6, 0.15, 0), (-1.2, 0.4, 0), (-1.8, 0.75, 0), (-2.3, 1.2, 0)],
              "tail", [0.7, 0.5, 0.35, 0.2])
    # A crest on top of the head: the upward side face of the head's last segment, pulled up.
    last = [f for f in range(len(c.faces)) if sum(1 for i in c.faces[f] if c.limb[i] == ("head", 1.0)) == 2
            and any(c.limb[i] == ("head", 0.75) for i in c.faces[f])]
    crest_face = max(last, key=lambda f: sum(c.v[i][1] for i in c.faces[f]))
    crest = c.extrude(crest_face, [(-0.05, 0.5, 0)], "head", [0.3])
    # Creases: the spine (the top middle row of edges), the claws (the cap of each foot), the
    # crest's tip and the snout's rim.
    creases = []
    ridge = sorted({i for f in top.values() for i in c.faces[f] if abs(c.v[i][2] - 0.25) < 1e-9},
                   key=lambda i: c.v[i][0])
    for a, b in zip(ridge, ridge[1:]):
        creases.append(((a, b), 1.5))
    for ring, sharpness in [(r, 10.0) for r in legs.values()] + [(crest, 10.0), (head, 2.0)]:
        for a in range(4):
            creases.append(((ring[a], ring[(a + 1) % 4]), sharpness))
    return c, creases


def look_at(eye, target):
    """World-to-camera matrix (row vectors, RenderMan's camera looking down +z, y up)."""
    def sub(a, b):
        return [a[i] - b[i] for i in range(3)]

    def cross(a, b):
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    def unit(a):
        n = math.sqrt(sum(x * x for x in a))
        return [x / n for x in a]

    def dot(a, b):
        return sum(a[i] * b[i] for i in range(3))

    f = unit(sub(target, eye))
    r = unit(cross((0, 1, 0), f))
    u = cross(f, r)
    return [r[0], u[0], f[0], 0, r[1], u[1], f[1], 0, r[2], u[2], f[2], 0,
            -dot(eye, r), -dot(eye, u), -dot(eye, f), 1]


def rotate_about(p, pivot, axis, angle):
    x, y, z = (p[i] - pivot[i] for i in range(3))
    s, co = math.sin(angle), math.cos(angle)
    if axis == "z":
        x, y = x * co - y * s, x * s + y * co
    elif axis == "y":
        x, z = x * co + z * s, -x * s + z * co
    return [x + pivot[0], y + pivot[1], z + pivot[2]]


def pose(c, t):
    """Vertex positions at time t (frames): a walk cycle of 24 frames."""
    ph = 2 * math.pi * t / 24
    out = []
    for p, limb in zip(c.v, c.limb):
        q = list(p)
        if limb:
            name, w = limb
            if name.startswith(("hind", "fore")):
                x = -1.2 if name.startswith("hind") else 1.2
                z = -0.3 if name.endswith("_l") else 0.3
                phase = ph + (0 if (name in ("hind_l", "fore_r")) else math.pi)
                q = rotate_about(q, (x, 0.0, z), "z", 0.45 * math.sin(phase) * min(1.0, 0.4 + w))
            elif name == "head":
                q = rotate_about(q, (1.6, 0.9, 0.0), "z", 0.15 * math.sin(2 * ph) * w)
            elif name == "tail":
                q = rotate_about(q, (-1.6, 0.6, 0.0), "y", 0.7 * math.sin(ph * 1.5) * w * w)
        bob = 0.08 * math.cos(2 * ph)
        out.append([q[0] + 0.11 * t, q[1] + 1.5 + bob, q[2]])  # walks forward, feet on the floor
    return out


def main():
    c, creases = build()
    nverts = [len(f) for f in c.faces]
    verts = [i for f in c.faces for i in f]
    keys = list(range(1, FRAMES + 2))  # keys at every frame: the window is [1, 48.5]
    out = []
    w = out.append
    w("# streyes creature: generated by scenes/gen/creature.py (edit that, not this file).\n")
    w("# A Catmull-Clark creature (%d faces, %d vertices, %d crease edges) walking over %d frames:\n"
      % (len(c.faces), len(c.v), len(creases), FRAMES))
    w("# one SubdivisionMesh per frame inside a motion block, the same topology with new points.\n")
    w('Option "streyes" "int frames" [1 %d]\n' % FRAMES)
    w("Format 640 360 1\n")
    w('Projection "perspective" "fov" [32]\n')
    w("Clipping 0.1 1000\n")
    w("Shutter 0 0.5\n")
    w("PixelSamples 4 4\n")
    w('PixelFilter "gaussian" 2 2\n')
    w('Display "creature.####.exr" "openexr" "rgbaz"\n')
    w("Transform [%s]  # looking at the middle of the walk from the front left\n"
      % " ".join(fmt(round(x, 6)) for x in look_at((-3.5, 4.6, -14.0), (3.0, 1.3, 0.0))))
    w("WorldBegin\n")
    w('LightSource "ambientlight" 1 "intensity" [0.25]\n')
    w('LightSource "distantlight" 2 "intensity" [0.95] "from" [-3 8 -6] "to" [0 0 0]\n')
    w('LightSource "pointlight" 3 "intensity" [25] "lightcolor" [1 0.85 0.7] "from" [6 5 -4]\n')
    w(attribute_block('Surface "matte"', (0.55, 0.6, 0.5), patch((-20, 0, -14), (30, 0, -14), (-20, 0, 30), (30, 0, 30))))
    w("AttributeBegin\n")
    w('Surface "plastic" "Ks" [0.45] "roughness" [0.12]\n')
    w("Color [0.85 0.45 0.2]\n")
    # One "crease" tag per edge, each with its own sharpness.
    tag_names = " ".join('"crease"' for _ in creases)
    nargs = " ".join("2 1" for _ in creases)
    intargs = " ".join("%d %d" % e for e, _ in creases)
    floatargs = " ".join(fmt(s) for _, s in creases)
    w("MotionBegin [%s]\n" % " ".join(str(k) for k in keys))
    topo = "[%s] [%s] [%s] [%s] [%s] [%s]" % (" ".join(map(str, nverts)), " ".join(map(str, verts)),
                                             tag_names, nargs, intargs, floatargs)
    for t in keys:
        w('SubdivisionMesh "catmull-clark" %s "P" [%s]\n' % (topo, points(pose(c, t))))
    w("MotionEnd\n")
    w("AttributeEnd\n")
    w("WorldEnd\n")
    write_scene("creature.rib", "".join(out))


if __name__ == "__main__":
    main()
