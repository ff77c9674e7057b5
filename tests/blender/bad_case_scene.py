"""One bad case for bad_cases_test.py, run inside Blender: a small scene rendered by the add-on.

--case missing     streyes is nowhere (no preference, STREYES_BIN names no file, not on PATH)
--case node        a material with a node the add-on does not support (a Noise Texture on the
                   base colour, a Glass BSDF): warnings, and the frame is rendered
--case refused     a setting streyes refuses (a 20-pixel filter: PixelFilter wider than 32)
--case cancel      a heavier 24-frame animation, to be interrupted with SIGINT by the driver
--case zoom        a camera whose focal length changes over frames 1-3 (per-frame projections are
                   not in streyes yet: a warning, and every frame takes frame 1's)
Prints "RENDER-ERROR: <message>" when the render operator reports an error.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402

import blender_test_util as util  # noqa: E402


def scene_with_cube(frames=(1, 1), xres=64, yres=48):
    scene = util.empty_scene(xres, yres, frames)
    util.mesh_object("Floor", [(-4, -4, 0), (4, -4, 0), (4, 4, 0), (-4, 4, 0)], [(0, 1, 2, 3)],
                     util.diffuse("FloorMat", (0.5, 0.5, 0.5)))
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3
    scene.collection.objects.link(sun)
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.location = (0, -6, 3)
    cam.rotation_euler = (1.1, 0, 0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    return scene


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    case = argv[argv.index("--case") + 1]
    source = argv[argv.index("--source") + 1]
    work = argv[argv.index("--work") + 1]
    util.register_addon(source)
    os.makedirs(work, exist_ok=True)
    if case == "cancel":
        scene = scene_with_cube((1, 24), 640, 360)
        bpy.ops.mesh.primitive_uv_sphere_add(segments=128, ring_count=64, location=(0, 0, 1))
        ball = bpy.context.object
        ball.keyframe_insert("location", frame=1)
        ball.location.x = 2
        ball.keyframe_insert("location", frame=24)
        scene.render.use_motion_blur = True
        scene.streyes.samples = 256
    elif case == "zoom":
        scene = scene_with_cube((1, 3))
        cam = scene.camera.data
        cam.lens = 35
        cam.keyframe_insert("lens", frame=1)
        cam.lens = 70
        cam.keyframe_insert("lens", frame=3)
    else:
        scene = scene_with_cube()
    if case == "node":
        mat = bpy.data.materials.new("Marble")
        mat.use_nodes = True
        nt = mat.node_tree
        bsdf = nt.nodes["Principled BSDF"]
        noise = nt.nodes.new("ShaderNodeTexNoise")
        noise.name = "Veins"
        nt.links.new(noise.outputs["Color"], bsdf.inputs["Base Color"])
        glass = bpy.data.materials.new("Window")
        glass.use_nodes = True
        gt = glass.node_tree
        g = gt.nodes.new("ShaderNodeBsdfGlass")
        g.name = "Pane"
        gt.links.new(g.outputs[0], gt.nodes["Material Output"].inputs["Surface"])
        a = util.mesh_object("A", [(-1, -1, 0.5), (0, -1, 0.5), (0, 0, 0.5), (-1, 0, 0.5)], [(0, 1, 2, 3)], mat)
        b = util.mesh_object("B", [(0, -1, 0.5), (1, -1, 0.5), (1, 0, 0.5), (0, 0, 0.5)], [(0, 1, 2, 3)], glass)
        assert a and b
    if case == "refused":
        scene.render.filter_size = 20.0
    scene.streyes.keep_files = True
    scene.streyes.export_folder = os.path.join(work, "export") + "/"
    scene.render.engine = "STREYES"
    scene.render.filepath = os.path.join(work, "out", "frame.####")
    try:
        bpy.ops.render.render(animation=True)
    except RuntimeError as e:
        print("RENDER-ERROR: %s" % str(e).strip())
        return
    print("RENDER-DONE")


main()
