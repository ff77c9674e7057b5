#!/usr/bin/env python3
"""Writes scenes/sequence/: an animation as RenderMan pipelines write it (issue 14).

Eight frames, each a complete scene (options, camera, lights, world, its own MotionBegin blocks
within the frame's shutter), written twice: one file per frame (shot.0001.rib ... shot.0008.rib)
and all frames in one file (shot.rib), each frame a FrameBegin n ... FrameEnd block in both. Objects are named with
Attribute "identifier" "name" so that streyes can match them across frames:

- a still set (floor tiles, a back wall, a pillar), the same in every frame;
- a rigid mover (a box sliding right, motion-blurred within each frame), lit by a point light of
  its own whose intensity changes every frame;
- a deforming subdivision mesh (a cube breathing, two motion keys per frame);
- an object that appears in frame 4 (a sphere);
- one whose topology changes in frame 5 (a quad that becomes two triangles);
- a torus whose shader parameter (plastic Kd) changes every frame;
- a camera that pans (motion-blurred) over frames 1-3 and stands still from frame 4 on.

A headlight is declared before WorldBegin (in camera space), as PRMan and Aqsis allow.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
from ribgen import box, fmt, motion, patch, points  # noqa: E402

FRAMES = 8
OPEN, CLOSE = 0.0, 0.5


def camera_x(t):
    """The camera pans until frame 4, then stops."""
    return -1.5 + 0.5 * min(t, 4.0)


def cube_points(t):
    s = 0.6 * (1 + 0.15 * math.sin(1.3 * t))
    return [(x * s, y * s * (2 - s / 0.6), z * s) for (x, y, z) in
            [(-1, -1, 1), (1, -1, 1), (-1, 1, 1), (1, 1, 1), (-1, 1, -1), (1, 1, -1), (-1, -1, -1), (1, -1, -1)]]


CUBE = ("[4 4 4 4 4 4] [0 1 3 2  2 3 5 4  4 5 7 6  6 7 1 0  1 7 5 3  6 0 2 4] "
        '["interpolateboundary"] [0 0] [] []')


def frame(f):
    out = []
    w = out.append
    w("Format 160 90 1\n")
    w('Projection "perspective" "fov" [40]\n')
    w('LightSource "distantlight" 1 "intensity" [0.35] "from" [0 0 0] "to" [0 0 1]\n')  # a headlight
    w("Clipping 0.1 100\n")
    w("Shutter %s %s\n" % (fmt(OPEN), fmt(CLOSE)))
    w("PixelSamples 3 3\n")
    w('PixelFilter "gaussian" 2 2\n')
    w('Display "shot.%04d.exr" "openexr" "rgba"\n' % f)
    w("Rotate -12 1 0 0\n")
    if f < 4:
        w(motion([f + OPEN, f + CLOSE], ["Translate %s -2.2 9" % fmt(-camera_x(t)) for t in (f + OPEN, f + CLOSE)]))
    else:
        w("Translate %s -2.2 9\n" % fmt(-camera_x(f)))
    w("WorldBegin\n")
    w('LightSource "ambientlight" 2 "intensity" [0.15]\n')
    w('LightSource "distantlight" 3 "intensity" [0.7] "from" [-3 6 -4] "to" [0 0 0]\n')

    # The still set.
    w('AttributeBegin\nAttribute "identifier" "name" ["floor"]\nSurface "matte"\n')
    for j in range(6):
        for i in range(6):
            x0, z0 = -6 + 2 * i, -4 + 2 * j
            w("Color [%s]\n" % ("0.7 0.68 0.62" if (i + j) % 2 else "0.35 0.38 0.45"))
            w(patch((x0, 0, z0), (x0 + 2, 0, z0), (x0, 0, z0 + 2), (x0 + 2, 0, z0 + 2)))
    w("AttributeEnd\n")
    w('AttributeBegin\nAttribute "identifier" "name" ["wall"]\nSurface "plastic" "Ks" [0.3]\nColor [0.6 0.5 0.4]\n')
    w(patch((-6, 0, 8), (6, 0, 8), (-6, 5, 8), (6, 5, 8)))
    w("AttributeEnd\n")
    w('AttributeBegin\nAttribute "identifier" "name" ["pillar"]\nSurface "matte"\nColor [0.8 0.8 0.75]\n')
    w("Translate -3.5 0 3\nRotate -90 1 0 0\nCylinder 0.4 0 3 360\n")
    w("AttributeEnd\n")

    # A rigid mover with a light of its own that changes.
    w('AttributeBegin\nAttribute "identifier" "name" ["mover"]\n')
    w('LightSource "pointlight" 4 "intensity" [%s] "lightcolor" [1 0.8 0.6] "from" [0 2.5 -1.5]\n' % fmt(2.0 + 1.5 * f))
    w('Surface "plastic" "Ks" [0.5]\nColor [0.8 0.2 0.15]\n')
    w(motion([f + OPEN, f + CLOSE], ["Translate %s 0.5 0" % fmt(-2.5 + 0.45 * t) for t in (f + OPEN, f + CLOSE)]))
    w(box(0, 0, 0, 1, 1, 1))
    w("AttributeEnd\n")

    # A deforming subdivision mesh.
    w('AttributeBegin\nAttribute "identifier" "name" ["blob"]\nSurface "plastic"\nColor [0.2 0.5 0.8]\n')
    w("Translate 2.5 1 1\n")
    keys = ['SubdivisionMesh "catmull-clark" %s "P" [%s]' % (CUBE, points(cube_points(t))) for t in (f + OPEN, f + CLOSE)]
    w(motion([f + OPEN, f + CLOSE], keys))
    w("AttributeEnd\n")

    # An object that appears in frame 4.
    if f >= 4:
        w('AttributeBegin\nAttribute "identifier" "name" ["newcomer"]\nSurface "matte"\nColor [0.3 0.8 0.3]\n')
        w("Translate 0.5 0.7 4\nSphere 0.7 -0.7 0.7 360\nAttributeEnd\n")

    # One whose topology changes in frame 5.
    w('AttributeBegin\nAttribute "identifier" "name" ["changer"]\nSurface "matte"\nColor [0.9 0.8 0.2]\n')
    if f < 5:
        w('PointsPolygons [4] [0 1 2 3] "P" [-5 0.01 -3  -3 0.01 -3  -3 0.01 -1  -5 0.01 -1]\n')
    else:
        w('PointsPolygons [3 3] [0 1 2  0 2 3] "P" [-5 0.01 -3  -3 0.01 -3.5  -2.5 0.01 -1  -5 0.01 -1]\n')
    w("AttributeEnd\n")

    # A shader parameter that changes.
    w('AttributeBegin\nAttribute "identifier" "name" ["statue"]\n')
    w('Surface "plastic" "Kd" [%s]\nColor [0.7 0.7 0.9]\n' % fmt(0.2 + 0.1 * f))
    w("Translate 4 0.5 4\nRotate 60 1 0 0\nTorus 0.6 0.2 0 360 360\nAttributeEnd\n")
    w("WorldEnd\n")
    return "".join(out)


HEADER = "# Frame %s of the sequence test shot: generated by scenes/gen/sequence.py (edit that).\n"


def main():
    folder = os.path.join(os.path.dirname(__file__), "..", "sequence")
    os.makedirs(folder, exist_ok=True)
    whole = ["# The sequence test shot, frames 1-%d as FrameBegin blocks: generated by scenes/gen/sequence.py.\n"
             % FRAMES]
    for f in range(1, FRAMES + 1):
        text = frame(f)
        with open(os.path.join(folder, "shot.%04d.rib" % f), "w") as out:
            out.write(HEADER % f + "FrameBegin %d\n%sFrameEnd\n" % (f, text))
        whole.append("FrameBegin %d\n%sFrameEnd\n" % (f, text))
    with open(os.path.join(folder, "shot.rib"), "w") as out:
        out.write("".join(whole))


if __name__ == "__main__":
    main()
