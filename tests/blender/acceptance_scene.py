"""The scene of issue 49's acceptance, built in Python: a subdivided cube moving (its last
modifier a Catmull-Clark Subdivision Surface, four creased edges), a bar bent by an armature, a
still floor, a sun and an area light, a camera that stands for frames 1-4 and pans over 5-8,
motion blur on (shutter 0.5, centred), diffuse materials, a black world.
"""

import math

import bpy
from mathutils import Vector

import blender_test_util as util


def _linear(obj):
    if obj.animation_data and obj.animation_data.action:
        for fc in obj.animation_data.action.fcurves:
            for k in fc.keyframe_points:
                k.interpolation = "LINEAR"


def _look_at(obj, target):
    direction = Vector(target) - obj.location
    obj.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()


def box(name, sx, sy, sz, segments=1, material=None):
    """A box centred on the origin in x and y, from z = 0 to sz, cut in `segments` along z."""
    verts, faces = [], []
    for i in range(segments + 1):
        z = sz * i / segments
        verts += [(-sx / 2, -sy / 2, z), (sx / 2, -sy / 2, z), (sx / 2, sy / 2, z), (-sx / 2, sy / 2, z)]
    for i in range(segments):
        a, b = 4 * i, 4 * (i + 1)
        for k in range(4):
            faces.append((a + k, a + (k + 1) % 4, b + (k + 1) % 4, b + k))
    faces.append((3, 2, 1, 0))
    top = 4 * segments
    faces.append((top, top + 1, top + 2, top + 3))
    return util.mesh_object(name, verts, faces, material)


def build(xres=240, yres=136, pan=True, others=True):
    scene = util.empty_scene(xres, yres, (1, 8))
    scene.render.use_motion_blur = True
    scene.render.motion_blur_shutter = 0.5
    scene.cycles.motion_blur_position = "CENTER"
    scene.render.film_transparent = True

    floor = util.mesh_object("Floor", [(-6.5, -6.5, 0), (6.5, -6.5, 0), (6.5, 6.5, 0), (-6.5, 6.5, 0)], [(0, 1, 2, 3)],
                             util.diffuse("FloorMat", (0.6, 0.6, 0.6)))

    if others:
        # The cube: a Catmull-Clark cage whose top edges are creased, sliding and turning.
        cube = box("Cube", 1.4, 1.4, 1.4, 1, util.diffuse("CubeMat", (0.75, 0.25, 0.2)))
        me = cube.data
        top = {4, 5, 6, 7}
        for e in me.edges:
            if set(e.vertices) <= top:
                e.crease = 1.0
        for p in me.polygons:
            p.use_smooth = True
        # Normals split where the surface turns sharply (the creased rim), as the limit surface's
        # are: Blender's smooth shading would otherwise blend the top's into the sides'.
        me.use_auto_smooth = True
        me.auto_smooth_angle = math.radians(40)
        mod = cube.modifiers.new("Subdivision", "SUBSURF")
        mod.levels = 2
        mod.render_levels = 3
        cube.location = (-2.6, 0.3, 0.0)
        cube.rotation_euler = (0, 0, 0)
        cube.keyframe_insert("location", frame=1)
        cube.keyframe_insert("rotation_euler", frame=1)
        cube.location = (0.2, 0.3, 0.0)
        cube.rotation_euler = (0, 0, math.radians(50))
        cube.keyframe_insert("location", frame=8)
        cube.keyframe_insert("rotation_euler", frame=8)
        _linear(cube)

        # The bar: 12 rings, bent at its middle by an armature of two bones.
        bar = box("Bar", 0.45, 0.45, 2.4, 12, util.diffuse("BarMat", (0.2, 0.55, 0.3)))
        for p in bar.data.polygons:
            p.use_smooth = True
        bar.location = (2.0, 1.0, 0.0)
        arm_data = bpy.data.armatures.new("Rig")
        rig = bpy.data.objects.new("Rig", arm_data)
        rig.location = bar.location
        scene.collection.objects.link(rig)
        bpy.context.view_layer.objects.active = rig
        bpy.ops.object.mode_set(mode="EDIT")
        lower = arm_data.edit_bones.new("Lower")
        lower.head, lower.tail = (0, 0, 0), (0, 0, 1.2)
        upper = arm_data.edit_bones.new("Upper")
        upper.head, upper.tail = (0, 0, 1.2), (0, 0, 2.4)
        upper.parent = lower
        upper.use_connect = True
        bpy.ops.object.mode_set(mode="OBJECT")
        g_low = bar.vertex_groups.new(name="Lower")
        g_up = bar.vertex_groups.new(name="Upper")
        for v in bar.data.vertices:
            w = min(1.0, max(0.0, (v.co.z - 1.0) / 0.4))  # a soft joint between 1.0 and 1.4
            if w < 1:
                g_low.add([v.index], 1 - w, "REPLACE")
            if w > 0:
                g_up.add([v.index], w, "REPLACE")
        bar.modifiers.new("Armature", "ARMATURE").object = rig
        pb = rig.pose.bones["Upper"]
        pb.rotation_mode = "XYZ"
        pb.rotation_euler = (0, 0, 0)
        pb.keyframe_insert("rotation_euler", frame=1)
        pb.rotation_euler = (math.radians(70), 0, 0)
        pb.keyframe_insert("rotation_euler", frame=8)
        _linear(rig)

    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 2.5
    sun.data.angle = 0.0
    sun.rotation_euler = (math.radians(40), 0, math.radians(60))
    scene.collection.objects.link(sun)

    area = bpy.data.objects.new("Area", bpy.data.lights.new("Area", "AREA"))
    area.data.energy = 150.0
    area.data.size = 1.5
    # Where the sun casts its shape's shadow off the floor: a streyes without Attribute
    # "visibility" lets the (unseen) shape of an area light cast shadows from other lights.
    area.location = (-4.5, -3.0, 3.5)
    _look_at(area, (0, 0, 0.5))
    scene.collection.objects.link(area)

    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.data.lens = 32
    cam.data.clip_start = 0.1
    cam.data.clip_end = 100
    cam.location = (0.5, -9.0, 3.6)
    _look_at(cam, (0, 0, 0.7))
    scene.collection.objects.link(cam)
    scene.camera = cam
    if pan:
        # Still through frame 4's shutter (it closes at 4.25), turning from 4.5 to 8.
        cam.keyframe_insert("rotation_euler", frame=1)
        cam.keyframe_insert("rotation_euler", frame=4.5)
        cam.rotation_euler.z += math.radians(12)
        cam.keyframe_insert("rotation_euler", frame=8)
        _linear(cam)
    return scene
