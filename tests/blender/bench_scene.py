"""The acceptance scene (acceptance_scene.py) rendered for tools/blender-bench, inside Blender:
    blender -b --python bench_scene.py -- --source DIR --engine STREYES|CYCLES|NONE
            --samples N --res WxH --out DIR [--bounces N] [--no-shadows]
NONE builds the scene and renders nothing: what Blender costs before any renderer runs."""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402

import acceptance_scene  # noqa: E402

p = argparse.ArgumentParser()
p.add_argument("--source", required=True)
p.add_argument("--engine", required=True)
p.add_argument("--samples", type=int, default=64)
p.add_argument("--res", default="240x136")
p.add_argument("--out", required=True)
p.add_argument("--bounces", type=int, default=0)
p.add_argument("--no-shadows", action="store_true", help="no light casts shadows (in both renderers)")
a = p.parse_args(sys.argv[sys.argv.index("--") + 1:])
sys.path.insert(0, os.path.join(a.source, "blender"))
import streyes_blender  # noqa: E402

streyes_blender.register()
w, h = (int(v) for v in a.res.split("x"))
scene = acceptance_scene.build(w, h)
scene.cycles.max_bounces = a.bounces
if a.bounces:
    scene.cycles.diffuse_bounces = a.bounces
if a.no_shadows:
    for light in bpy.data.lights:
        light.cycles.cast_shadow = False
scene.cycles.samples = a.samples
scene.streyes.samples = a.samples
scene.render.filepath = os.path.join(a.out, "frame.####")
if a.engine != "NONE":
    scene.render.engine = a.engine
    bpy.ops.render.render(animation=True)
