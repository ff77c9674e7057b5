"""What the add-on exports, checked against Cycles where a picture says it, and in the RIB where
the structure does:

- light units: a diffuse floor under each kind of light (sun, point, spot with its blend, square
  and disk area lights, the world colour) has Cycles' brightness, to 3%;
- cameras: sensor fit, lens shift, orthographic scale and clipping put things where Cycles does
  (alpha); collection instances too (ObjectBegin / ObjectInstance);
- structure: the frame step numbers RIB frames consecutively with the shutter scaled, hair
  becomes Curves, smooth and flat shading, UVs, holdouts, objects unseen by the camera,
  Principled BSDF with an image texture.
"""

import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402
from mathutils import Vector  # noqa: E402

import blender_test_util as util  # noqa: E402

A = util.args()
util.register_addon(A.source)
F = util.Failures()


def look_at(obj, target):
    obj.rotation_euler = (Vector(target) - obj.location).to_track_quat("-Z", "Y").to_euler()


def camera(scene, location, target, ortho=None, lens=50):
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.location = location
    look_at(cam, target)
    cam.data.lens = lens
    if ortho:
        cam.data.type = "ORTHO"
        cam.data.ortho_scale = ortho
    scene.collection.objects.link(cam)
    scene.camera = cam
    return cam


def both(scene, name, samples=32):
    """Renders frame 1 (F12, a still) with streyes (keeping the RIB) and with Cycles; returns the
    two images and the RIB text."""
    scene.streyes.keep_files = True
    scene.streyes.export_folder = os.path.join(A.work, name, "export") + "/"
    s = util.render(scene, "STREYES", os.path.join(A.work, name, "streyes"), animation=False, samples=samples)
    c = util.render(scene, "CYCLES", os.path.join(A.work, name, "cycles"), animation=False, samples=samples)
    ribs = sorted(os.listdir(os.path.join(A.work, name, "export", "Scene")))
    rib = open(os.path.join(A.work, name, "export", "Scene", [r for r in ribs if r.endswith(".rib")][0])).read()
    si, ci = util.read_exr(util.frame_file(s, 1)), util.read_exr(util.frame_file(c, 1))
    util.check_finite(name + " streyes", si)
    util.check_finite(name + " Cycles", ci)
    return si, ci, rib


def floor_scene(size=48):
    scene = util.empty_scene(size, size)
    util.mesh_object("Floor", [(-20, -20, 0), (20, -20, 0), (20, 20, 0), (-20, 20, 0)], [(0, 1, 2, 3)],
                     util.diffuse("FloorMat", (0.5, 0.5, 0.5)))
    camera(scene, (0, 0, 10), (0, 0, 0), ortho=8)
    return scene


def light(scene, kind, location=(0, 0, 3), target=(0, 0, 0), **kw):
    ob = bpy.data.objects.new(kind, bpy.data.lights.new(kind, kind))
    for k, v in kw.items():
        setattr(ob.data, k, v)
    ob.location = location
    look_at(ob, target)
    scene.collection.objects.link(ob)
    return ob


def region_means(img, boxes):
    return [float(img[y0:y1, x0:x1, :3].mean()) for (x0, y0, x1, y1) in boxes]


# -- light units ------------------------------------------------------------------------------------
BOXES = [(20, 20, 28, 28), (4, 20, 10, 28), (38, 4, 44, 10), (20, 38, 28, 44)]
for name, make in [
    ("sun", lambda s: light(s, "SUN", (2, -3, 5), energy=2.0, angle=0.0)),
    ("point", lambda s: light(s, "POINT", (1, 0.5, 2.5), energy=300.0, shadow_soft_size=0.0)),
    ("spot", lambda s: light(s, "SPOT", (0, 0, 3), (0.4, 0, 0), energy=500.0, shadow_soft_size=0.0,
                             spot_size=math.radians(70), spot_blend=0.4)),
    ("area-square", lambda s: light(s, "AREA", (-1, 0.5, 2.5), (0, 0, 0), energy=200.0, size=0.6)),
    ("area-disk", lambda s: light(s, "AREA", (1, 1, 2), (0, 0, 0), energy=150.0, shape="DISK", size=0.8)),
    ("world", None),
]:
    scene = floor_scene()
    if make:
        make(scene)
    else:
        scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.3, 0.4, 0.5, 1)
    si, ci, rib = both(scene, "light-" + name, samples=64)
    ms, mc = region_means(si, BOXES), region_means(ci, BOXES)
    print("%s: streyes %s, Cycles %s" % (name, ["%.4f" % v for v in ms], ["%.4f" % v for v in mc]))
    F.check(max(mc) > 0.02, "%s: Cycles lights the floor (%.3f)" % (name, max(mc)))
    for k, (a, b) in enumerate(zip(ms, mc)):
        # 3% of the value, and a floor of 0.004 where the light hardly reaches (the spot's edge).
        F.check(abs(a - b) <= 0.03 * b + 0.004, "%s, region %d: streyes %.4f, Cycles %.4f" % (name, k, a, b))

# -- cameras -----------------------------------------------------------------------------------------
def boxes_scene(xres, yres):
    scene = util.empty_scene(xres, yres)
    scene.render.film_transparent = True
    grey = util.diffuse("Grey", (0.5, 0.5, 0.5))
    for i, (x, y) in enumerate([(-2, 0), (0, 1), (2, -1), (1, 3)]):
        s = 0.5
        util.mesh_object("Box%d" % i, [(x - s, y - s, 0), (x + s, y - s, 0), (x + s, y + s, 0), (x - s, y + s, 0),
                                       (x - s, y - s, 1.5), (x + s, y - s, 1.5), (x + s, y + s, 1.5),
                                       (x - s, y + s, 1.5)],
                         [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)], grey)
    light(scene, "SUN", (1, -2, 4), energy=3.0)
    return scene


def alpha_agrees(name, si, ci, mean=0.01, within=0.995):
    d = np.abs(si[..., 3] - ci[..., 3])
    F.check(ci[..., 3].mean() > 0.05, "%s: Cycles sees them (%.3f of the frame)" % (name, ci[..., 3].mean()))
    F.check(d.mean() <= mean and (d <= 0.1).mean() >= within,
            "%s: alpha agrees with Cycles (mean %.4f, %.2f%% within 0.1)" % (name, d.mean(), 100 * (d <= 0.1).mean()))


scene = boxes_scene(48, 72)  # portrait: AUTO fits the sensor to the height
cam = camera(scene, (0.5, -8, 4), (0, 0.5, 0.5), lens=35)
cam.data.shift_x, cam.data.shift_y = 0.1, -0.05
si, ci, _ = both(scene, "camera-auto-shift")
alpha_agrees("perspective, portrait, AUTO fit, shifted", si, ci)

scene = boxes_scene(80, 40)
cam = camera(scene, (-1, -7, 5), (0.5, 0.5, 0.3), lens=40)
cam.data.sensor_fit = "VERTICAL"
cam.data.sensor_height = 20
cam.data.clip_start = 6.5  # cuts the nearest box
si, ci, _ = both(scene, "camera-vertical-clip")
alpha_agrees("perspective, VERTICAL fit, clipped", si, ci)

scene = boxes_scene(64, 48)
scene.render.pixel_aspect_x = 2.0  # pixels twice as wide as tall
cam = camera(scene, (3, -6, 6), (0, 0.5, 0), ortho=9)
cam.data.shift_y = 0.08
si, ci, _ = both(scene, "camera-ortho-aspect")
alpha_agrees("orthographic, pixel aspect 2, shifted", si, ci)

# -- collection instances --------------------------------------------------------------------------
scene = util.empty_scene(64, 48)
scene.render.film_transparent = True
coll = bpy.data.collections.new("Props")
proto = util.mesh_object("Prop", [(-0.9, 0, 0), (0.9, 0, 0), (0, 0, 2.2)], [(0, 1, 2)], util.diffuse("P", (1, 1, 1)))
scene.collection.objects.unlink(proto)
coll.objects.link(proto)
for i in range(3):
    e = bpy.data.objects.new("Inst%d" % i, None)
    e.instance_type = "COLLECTION"
    e.instance_collection = coll
    e.location = (-2.5 + 2.2 * i, 0, 0)
    e.rotation_euler = (0, 0, 0.4 * i)
    e.scale = (1, 1, 0.6 + 0.3 * i)
    scene.collection.objects.link(e)
light(scene, "SUN", (0, -3, 3), energy=2.0)
camera(scene, (0, -8, 1.5), (0, 0, 0.8), lens=35)
si, ci, rib = both(scene, "instances")
alpha_agrees("collection instances", si, ci)
F.check(rib.count("ObjectBegin") == 1 and rib.count("ObjectInstance") == 3,
        "one object definition, three instances (%d, %d)" % (rib.count("ObjectBegin"), rib.count("ObjectInstance")))

# -- holdouts --------------------------------------------------------------------------------------
# A holdout square (2 x 2, 1 above the lit floor, pixels 18..30 of 48) leaves a hole: colour 0 and
# alpha 0 where it is, in streyes (Matte 1) as in Cycles; the floor around it as before.
scene = floor_scene()
scene.render.film_transparent = True
light(scene, "SUN", (2, -3, 5), energy=2.0, angle=0.0)
holdout = util.mesh_object("Holdout", [(-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)], [(0, 1, 2, 3)])
holdout.is_holdout = True
si, ci, rib = both(scene, "holdout")
F.check("Matte 1" in rib, "the holdout is exported as Matte 1")
for name, img in (("streyes", si), ("Cycles", ci)):
    hole, floor = img[20:28, 20:28], img[4:10, 4:10]
    F.check(float(np.abs(hole).max()) == 0.0, "%s: the holdout leaves colour 0, alpha 0 (max %.4f)" %
            (name, float(np.abs(hole).max())))
    F.check(float(floor[..., 3].min()) == 1.0 and float(floor[..., :3].mean()) > 0.02,
            "%s: the floor beside it is lit and opaque (alpha %.4f)" % (name, float(floor[..., 3].min())))
alpha_agrees("holdout", si, ci, mean=0.02, within=0.97)

# -- structure -------------------------------------------------------------------------------------
scene = util.empty_scene(32, 32, (1, 5))
scene.frame_step = 2
scene.render.use_motion_blur = True
scene.render.motion_blur_shutter = 0.5
camera(scene, (0, -6, 2), (0, 0, 0.5))
light(scene, "SUN", (0, -2, 3))
mover = util.mesh_object("Mover", [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)], [(0, 1, 2, 3)])
mover.keyframe_insert("location", frame=1)
mover.location.x = 2
mover.keyframe_insert("location", frame=5)
for fc in mover.animation_data.action.fcurves:
    for k in fc.keyframe_points:
        k.interpolation = "LINEAR"
smooth = util.mesh_object("Smooth", [(-2, 0, 0), (-1, 0, 0), (-1, 0.5, 1), (-2, 0.5, 1)], [(0, 1, 2, 3)])
smooth.data.polygons[0].use_smooth = True
smooth.data.uv_layers.new(name="UVMap")
hidden = util.mesh_object("Unseen", [(0, 1, 0), (1, 1, 0), (1, 1, 1)], [(0, 1, 2)])
hidden.visible_camera = False
hold = util.mesh_object("Hold", [(0, 2, 0), (1, 2, 0), (1, 2, 1)], [(0, 1, 2)])
hold.is_holdout = True
tex = bpy.data.images.new("Checker", 8, 8)
tex.filepath_raw = os.path.join(A.work, "checker.png")
tex.file_format = "PNG"
tex.save()
mat = bpy.data.materials.new("Painted")
mat.use_nodes = True
node = mat.node_tree.nodes.new("ShaderNodeTexImage")
node.image = tex
bsdf = mat.node_tree.nodes["Principled BSDF"]
mat.node_tree.links.new(node.outputs["Color"], bsdf.inputs["Base Color"])
bsdf.inputs["Metallic"].default_value = 0.25
smooth.data.materials.append(mat)
emitter = util.mesh_object("Emitter", [(-3, -1, 0), (3, -1, 0), (3, 1, 0), (-3, 1, 0)], [(0, 1, 2, 3)])
emitter.modifiers.new("Hair", "PARTICLE_SYSTEM")
part = emitter.particle_systems[0].settings
part.type = "HAIR"
part.count = 20
part.hair_length = 0.5
part.render_step = 2
pebble = util.mesh_object("Pebble", [(0, 0, 0), (0.1, 0, 0), (0, 0.1, 0.1)], [(0, 1, 2)])
pebble.location = (0, 0, -30)  # out of view: only its instances are seen
ground = util.mesh_object("Ground", [(-1, 2, 0), (1, 2, 0), (1, 3, 0), (-1, 3, 0)], [(0, 1, 2, 3)])
ground.modifiers.new("Pebbles", "PARTICLE_SYSTEM")
pp = ground.particle_systems[0].settings
pp.type = "EMITTER"
pp.count = 7
pp.frame_start = pp.frame_end = 1
pp.lifetime = 100
pp.physics_type = "NO"
pp.render_type = "OBJECT"
pp.instance_object = pebble
scene.streyes.keep_files = True
scene.streyes.export_folder = os.path.join(A.work, "structure") + "/"
util.render(scene, "STREYES", os.path.join(A.work, "structure-frames"), samples=1)
folder = os.path.join(A.work, "structure", "Scene")
ribs = sorted(f for f in os.listdir(folder) if f.endswith(".rib"))
F.check(ribs == ["shot.0001.rib", "shot.0002.rib", "shot.0003.rib"], "frame step 2: frames 1 3 5 are RIB frames 1-3: %s" % ribs)
F.check(sorted(os.listdir(os.path.join(A.work, "structure-frames"))) ==
        ["frame.0001.exr", "frame.0003.exr", "frame.0005.exr"], "Blender's frames 1, 3, 5 are written")
r2 = open(os.path.join(folder, "shot.0002.rib")).read()
F.check("FrameBegin 2" in r2 and "Shutter -0.125 0.125" in r2, "the shutter in RIB frames: half a Blender frame's")
F.check("MotionBegin [1.875 2 2.125]" in r2, "Blender frame 3's motion keys at RIB times 1.875 2 2.125")
m = re.search(r'"name" \["Mover"\].*?MotionBegin \[[^\]]*\]\s*ConcatTransform \[([^\]]*)\]', r2, re.S)
F.check(m is not None and abs(float(m.group(1).split()[12]) - 0.875) < 1e-6,
        "the mover at Blender time 2.75 is at x = 0.875 (%s)" % (m.group(1).split()[12] if m else None))
smooth_part = r2[r2.index('"name" ["Smooth"]'):]
smooth_part = smooth_part[:smooth_part.index("AttributeEnd")]
F.check('"vertex normal N"' in smooth_part and '"facevarying float[2] st"' in smooth_part,
        "a smooth face: vertex normals, and its UVs as st")
F.check('Surface "blender_principled"' in smooth_part and "checker.png" in smooth_part and
        '"float metallic" [0.25]' in smooth_part, "Principled BSDF with its image texture")
mover_part = r2[r2.index('"name" ["Mover"]'):]
mover_part = mover_part[:mover_part.index("AttributeEnd")]
F.check("normal N" not in mover_part, "a flat face: no normals (its own are flat)")
unseen = r2[r2.index('"name" ["Unseen"]'):]
F.check('"int camera" [0]' in unseen[:400] and "Opacity [0 0 0]" in unseen[:600],
        "unseen by the camera: visibility off and see-through (casting shadows)")
hold_part = r2[r2.index('"name" ["Hold"]'):]
F.check("Matte 1" in hold_part[:600], "a holdout is Matte")
m = re.search(r'Curves "linear" \[([^\]]*)\] "nonperiodic"', r2)
F.check(m is not None and m.group(1).split() == ["5"] * 20, "20 hair strands of 5 points as Curves")
F.check(os.path.exists(os.path.join(folder, "blender_principled.sl")), "the add-on's shader beside the RIB")
F.check(len(re.findall(r'ObjectInstance "Pebble:0"', r2)) == 7 and r2.count('ObjectBegin "Pebble:0"') == 1,
        "7 particle instances of one object (%d)" % len(re.findall(r'ObjectInstance "Pebble:0"', r2)))

F.finish()
