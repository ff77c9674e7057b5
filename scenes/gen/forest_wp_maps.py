#!/usr/bin/env python3
"""Writes scenes/forest-wp-maps.rib: scenes/forest-wp.rib with the sun's shadows from a depth map.

forest-wp.rib traces the sun's shadow rays, and the ray tracer expands every tree with its swaying
leaves up front: about 40 CPU s and 5 GB a frame at 1280x720 (docs/results/forests.md). This is
the same shot as exporters write a shadow-mapped sun: per frame a depth frame rendered from the sun
(an orthographic view along its direction over the forest), MakeShadow, then the picture, whose
sunlight reads the map with a blur for the soft edge. Every depth frame is one spacetime job and
every picture another, each picture reading its own frame's map; the trees' wind keys are at fixed
times (every keystep frames), so the map and the picture see the same tree at the same time.

    python3 scenes/gen/forest_wp_maps.py [frames] [map_size]
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
from ribgen import camera_transform, cross, dot, fmt, unit  # noqa: E402

OUT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "forest-wp-maps.rib")

SUN_FROM = (-0.6, 0.45, -0.66)  # forest-wp.rib's: the sun lies from - to, to = the origin
FOREST = ('Procedural "DynamicLoad" ["forest" "count=250 seed=11 area=300,300 model=weberpenn '
          'presets=quaking_aspen,black_tupelo,ca_black_oak wind=0.5 keystep=16 detail=0.35 cell=64"] '
          '[-235 235 -58 58 -235 235]\n')
# What may cast a shadow: the trees' area grown by their crowns' reach, up to their tallest top.
CASTERS = ((-190.0, 190.0), (0.0, 45.0), (-190.0, 190.0))


def sun_view():
    """The sun's camera: looking along to - from from 1000 m out; its Transform, ScreenWindow and
    Clipping cover the casters' box exactly (orthographic: camera units are metres)."""
    z = unit(tuple(-c for c in SUN_FROM))
    x = unit(cross((0, 1, 0), z))
    y = cross(z, x)
    eye = tuple(-1000 * c for c in z)
    corners = [(a, b, c) for a in CASTERS[0] for b in CASTERS[1] for c in CASTERS[2]]
    cam = [tuple(dot(tuple(p[i] - eye[i] for i in range(3)), axis) for axis in (x, y, z)) for p in corners]
    lo = [min(c[i] for c in cam) for i in range(3)]
    hi = [max(c[i] for c in cam) for i in range(3)]
    return camera_transform(eye, x, y, z), (lo[0], hi[0], lo[1], hi[1]), (lo[2] - 1, hi[2] + 1)


def main():
    frames = int(sys.argv[1]) if len(sys.argv) > 1 else 64
    map_size = int(sys.argv[2]) if len(sys.argv) > 2 else 2048
    transform, window, clip = sun_view()
    aspect = (window[1] - window[0]) / (window[3] - window[2])
    mw, mh = (map_size, max(1, round(map_size / aspect))) if aspect >= 1 else (max(1, round(map_size * aspect)), map_size)
    depth = ('FrameBegin FRAME\nDisplay "forest-wp-sun.z" "zfile" "z"\nFormat ' + "%d %d 1\n" % (mw, mh) +
             'PixelSamples 1 1\nPixelFilter "box" 1 1\nShutter 0 0.5\nProjection "orthographic"\n' +
             "ScreenWindow %s\nClipping %s\n" % (" ".join(fmt(round(v, 3)) for v in window),
                                                 " ".join(fmt(round(v, 3)) for v in clip)) +
             transform + 'WorldBegin\nAttributeBegin\nAttribute "identifier" "name" ["forest"]\nSurface "matte"\n' +
             FOREST + "AttributeEnd\nWorldEnd\nFrameEnd\n"
             'MakeShadow "forest-wp-sun.z" "forest-wp-sun.shd"\n')
    sun = " ".join(fmt(c) for c in SUN_FROM)
    # The blur: the sun's penumbra (its 0.27 degree radius) behind a crown about 10 m up, as a
    # share of the map's width (0.8 b of the map's texels from 10% to 90%: docs/SCENE-FORMAT.md).
    blur = 2 * 10 * math.tan(math.radians(0.27)) / (window[1] - window[0]) / 0.8
    picture = ('FrameBegin FRAME\nDisplay "forest-wp-maps.####.exr" "openexr" "rgbaz"\nFormat 1280 720 1\n'
               'Projection "perspective" "fov" [40]\nClipping 0.5 5000\nShutter 0 0.5\nPixelSamples 2 2\n'
               'PixelFilter "gaussian" 2 2\n'
               'Option "environment:sky" "string shader" ["preethamsky"] "float turbidity" [3] '
               '"float intensity" [0.06]\n       "point from" [%s] "point to" [0 0 0]\n' % sun +
               "Rotate 6 1 0 0\nTranslate 0 -5 230\nWorldBegin\n"
               'LightSource "ambientlight" 1 "intensity" [0.25] "lightcolor" [0.6 0.75 1]\n'
               'LightSource "sunlight" 2 "intensity" [1.5] "turbidity" [3] "from" [%s] "to" [0 0 0] '
               '"angle" [0.27]\n       "shadowname" ["forest-wp-sun.shd"] "blur" [%s]\n' % (sun, fmt(round(blur, 7))) +
               'AttributeBegin\n  Attribute "identifier" "name" ["sky"]\n'
               '  Surface "preethamsky" "turbidity" [3] "intensity" [0.06] "from" [%s] "to" [0 0 0]\n' % sun +
               '  Patch "bilinear" "P" [-3000 2500 1500  3000 2500 1500  -3000 -50 1500  3000 -50 1500]\n'
               'AttributeEnd\nAttributeBegin\n  Attribute "identifier" "name" ["ground"]\n  Surface "ground"\n'
               '  Color [0.8 0.85 0.6]\n'
               '  Patch "bilinear" "P" [-2000 0 -400  2000 0 -400  -2000 0 1500  2000 0 1500]\n'
               'AttributeEnd\nAttributeBegin\n  Attribute "identifier" "name" ["forest"]\n  Surface "matte"\n  ' +
               FOREST + "AttributeEnd\nWorldEnd\nFrameEnd\n")
    out = ["# Generated by scenes/gen/forest_wp_maps.py: scenes/forest-wp.rib's shot (250 Weber-Penn trees\n"
           "# in the wind, the sun and the Preetham sky) with the sun's shadows from a depth map rendered\n"
           "# from the sun each frame (%dx%d, orthographic over the trees), as exporters write a\n"
           "# shadow-mapped light: per frame a depth frame, MakeShadow, the picture. %d frames.\n"
           % (mw, mh, frames)]
    for f in range(1, frames + 1):
        out.append(depth.replace("FRAME", str(f)))
        out.append(picture.replace("FRAME", str(f)))
    with open(OUT, "w") as fh:
        fh.write("".join(out))


if __name__ == "__main__":
    main()
