"""Helpers for the tests that run inside Blender (blender -b --python TEST.py -- ARGS).

ARGS: --source DIR (the repository), --streyes PATH (the command under test), --work DIR (a
folder of the test's own, emptied first). The add-on is registered from DIR/blender by putting
that folder on sys.path and calling register(), as a user's script may.
"""

import argparse
import os
import shutil
import sys

import bpy
import numpy as np


def args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser()
    p.add_argument("--source", required=True)
    p.add_argument("--streyes", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--report", default="", help="write the measured figures here (JSON)")
    a, _ = p.parse_known_args(argv)
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    os.environ["STREYES_BIN"] = a.streyes
    return a


def register_addon(source):
    path = os.path.join(source, "blender")
    if path not in sys.path:
        sys.path.insert(0, path)
    import streyes_blender
    try:
        streyes_blender.register()
    except ValueError:  # registered already (a second scene in one test)
        pass
    return streyes_blender


def empty_scene(xres, yres, frames=(1, 1)):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = xres, yres
    scene.render.resolution_percentage = 100
    scene.frame_start, scene.frame_end = frames
    scene.frame_set(frames[0])
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
    scene.world = world
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.color_mode = "RGBA"
    scene.view_settings.view_transform = "Standard"
    scene.cycles.device = "CPU"
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = 0  # direct light only
    scene.cycles.caustics_reflective = False
    scene.cycles.caustics_refractive = False
    return scene


def diffuse(name, color):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    d = nt.nodes.new("ShaderNodeBsdfDiffuse")
    d.inputs["Color"].default_value = tuple(color) + (1,)
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(d.outputs[0], out.inputs["Surface"])
    return mat


def mesh_object(name, verts, faces, material=None, location=(0, 0, 0)):
    me = bpy.data.meshes.new(name)
    me.from_pydata(verts, [], faces)
    me.update()
    ob = bpy.data.objects.new(name, me)
    ob.location = location
    bpy.context.scene.collection.objects.link(ob)
    if material:
        me.materials.append(material)
    return ob


def render(scene, engine, folder, animation=True, samples=16):
    """Renders the scene's frames with `engine` into FOLDER/frame.####.exr; returns the pattern."""
    scene.render.engine = engine
    scene.cycles.samples = samples
    if engine == "STREYES":
        scene.streyes.samples = samples
    os.makedirs(folder, exist_ok=True)
    # A still (F12) is written under the name as given: numbered here as the animation's are.
    scene.render.filepath = os.path.join(folder, "frame.####" if animation else "frame.%04d" % scene.frame_current)
    bpy.ops.render.render(animation=animation, write_still=not animation)
    return os.path.join(folder, "frame.####.exr")


def frame_file(pattern, frame):
    return pattern.replace("####", "%04d" % frame)


def read_exr(path):
    """RGBA as float32 (height, width, 4), rows from the top; raises if the file lacks them."""
    import OpenImageIO as oiio
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise AssertionError("cannot read %s: %s" % (path, oiio.geterror()))
    spec = inp.spec()
    names = list(spec.channelnames)
    pixels = inp.read_image(0, 0, 0, spec.nchannels, oiio.FLOAT)
    inp.close()
    pixels = np.asarray(pixels, dtype=np.float32).reshape(spec.height, spec.width, spec.nchannels)
    want = ["R", "G", "B", "A"]
    for c in want:
        if c not in names:
            raise AssertionError("%s has no channel %s (channels %s)" % (path, c, names))
    return np.stack([pixels[:, :, names.index(c)] for c in want], axis=-1)


def quarter(img):
    """The mean of each 4 x 4 block (a quarter of the size on each side)."""
    h, w = img.shape[0] // 4 * 4, img.shape[1] // 4 * 4
    return img[:h, :w].reshape(h // 4, 4, w // 4, 4, -1).mean(axis=(1, 3))


def check_finite(name, img):
    bad = int(np.count_nonzero(~np.isfinite(img)))
    if bad:
        raise AssertionError("%s: %d values are NaN or infinite" % (name, bad))


class Failures:
    def __init__(self):
        self.items = []

    def check(self, ok, text):
        print(("ok      " if ok else "FAILED  ") + text)
        if not ok:
            self.items.append(text)

    def finish(self):
        if self.items:
            raise AssertionError("%d check(s) failed:\n  " % len(self.items) + "\n  ".join(self.items))
        print("all checks passed")
