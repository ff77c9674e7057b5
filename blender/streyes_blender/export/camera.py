"""The Blender camera as RenderMan's projection, screen window, clipping and depth of field.

Blender's camera looks down its -z axis with y up, in a right-handed world; RenderMan's camera
space is left-handed, x right, y up, looking down +z: the world-to-camera transform is the
inverse of the camera's matrix followed by Scale 1 1 -1.

The screen window is Cycles' view plane (blender_camera_viewplane): the sensor fits the width
(HORIZONTAL, or AUTO when the image is wider than tall) or the height; the fitted side spans
±aspect and the other ±1, the field of view is the one that maps the ±1 side, and the lens shift
moves the window by 2 * aspect * shift.
"""

import math

from mathutils import Matrix

from . import rib

FLIP_Z = Matrix.Scale(-1, 4, (0, 0, 1))


def world_to_camera(camera_matrix):
    return FLIP_Z @ camera_matrix.inverted_safe()


class Projection:
    """What RenderMan needs of a camera at one instant; equal projections compare equal."""

    def __init__(self, scene, camera_object, xres, yres):
        cam = camera_object.data
        render = scene.render
        self.name = camera_object.name
        xratio = xres * render.pixel_aspect_x
        yratio = yres * render.pixel_aspect_y
        if cam.sensor_fit == "AUTO":
            horizontal = xratio > yratio
            sensor = cam.sensor_width
        elif cam.sensor_fit == "HORIZONTAL":
            horizontal, sensor = True, cam.sensor_width
        else:
            horizontal, sensor = False, cam.sensor_height
        aspect = xratio / yratio if horizontal else yratio / xratio
        xa, ya = (aspect, 1.0) if horizontal else (1.0, aspect)
        self.type = cam.type
        if cam.type == "ORTHO":
            xa *= cam.ortho_scale / (aspect * 2)
            ya *= cam.ortho_scale / (aspect * 2)
            shift_scale = cam.ortho_scale / 2
            self.fov = None
        else:
            shift_scale = aspect
            self.fov = math.degrees(2 * math.atan(0.5 * sensor / cam.lens / aspect))
        dx, dy = 2 * shift_scale * cam.shift_x, 2 * shift_scale * cam.shift_y
        self.window = (-xa + dx, xa + dx, -ya + dy, ya + dy)
        self.clip = (cam.clip_start, cam.clip_end)
        self.pixel_aspect = render.pixel_aspect_x / render.pixel_aspect_y
        self.dof = None
        if cam.dof.use_dof and cam.type != "ORTHO":
            fstop = max(cam.dof.aperture_fstop, 1e-5)
            dist = cam.dof.focus_distance
            if cam.dof.focus_object is not None:
                view = camera_object.matrix_world.to_3x3() @ (0, 0, -1)
                view.normalize()
                target = cam.dof.focus_object.matrix_world.translation
                dist = abs(view.dot(target - camera_object.matrix_world.translation))
            # Cycles: aperture radius = lens (mm, as metres) / (2 fstop), as RenderMan's thin lens.
            self.dof = (fstop, cam.lens * 1e-3, max(dist, 1e-4))

    def key(self):
        return (self.type, self.fov, self.window, self.clip, self.pixel_aspect, self.dof)

    def write(self, w):
        if self.type == "ORTHO":
            w.write("Projection", rib.string("orthographic"))
        else:
            w.write("Projection", rib.string("perspective"), rib.string("fov"), rib.array([self.fov]))
        w.write("ScreenWindow", rib.nums(self.window))
        near, far = self.clip
        w.write("Clipping", rib.nums((max(near, 1e-4), max(far, near * 1.001))))
        if self.dof:
            w.write("DepthOfField", rib.nums(self.dof))
