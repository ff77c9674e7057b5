"""Blender lights as RenderMan lights, in units that give a diffuse surface Cycles' brightness.

The surfaces the add-on writes are RenderMan's (matte: Ci = Cs * sum Cl cos), so a light's Cl must
be the irradiance it gives, divided by pi: a Lambertian surface of albedo rho under irradiance E
has radiance rho E / pi. What each Blender light gives, in Cycles 3.4 (checked by rendering; see
docs/results/blender.md):

- Sun of strength S (W/m^2): irradiance S cos(theta). distantlight "intensity" S / pi.
- Point of power P (W): radiant intensity P / (4 pi) W/sr, so E = P cos / (4 pi d^2).
  pointlight "intensity" P / (4 pi^2) (pointlight's Cl is intensity / d^2).
- Spot of power P: the point light's intensity times Cycles' spot attenuation, cos(angle to the
  axis) times smoothstep over the blend, which runs in cosine from cos(size / 2) to
  cos(size / 2) + (1 - cos(size / 2)) blend. spotlight with the same intensity, beamdistribution 1
  (its cos^1), coneangle size / 2, and conedeltaangle such that cos(coneangle - delta) is the
  blend's end: the same smoothstep.
- Area of power P and area A: a one-sided Lambertian emitter of radiance P / (4 A), so
  E = P cos_e cos_r / (4 d^2) from a small one. arealight (Cl = intensity cos_e / d^2 summed over
  its points, each weighted 1/16) "intensity" P / (4 pi), "twosided" 0.
- World colour W (radiance from every direction): an unoccluded diffuse surface has radiance
  rho W. ambientlight "intensity" 1, "lightcolor" W.
"""

import math

from . import rib

PI = math.pi


def light_handle(name):
    return rib.string("light:" + name)


def write_light(w, light, name, matrices, shadows, warn):
    """Writes one light (a bpy.types.Light, evaluated) with its transforms at the motion times
    (`matrices`: [(time, Matrix)], one entry if it does not move)."""
    color = tuple(light.color)
    energy = light.energy
    shadow = {"string shadowname": "raytrace"} if shadows else {}
    kind = light.type
    handle = light_handle(name)
    if getattr(light, "use_nodes", False) and light.node_tree is not None:
        nodes = [n for n in light.node_tree.nodes if n.bl_idname not in ("ShaderNodeEmission", "ShaderNodeOutputLight")]
        if nodes:
            warn("light '%s': its nodes (%s) are not rendered: its colour and power are" % (name, nodes[0].name))
    w.comment("%s light '%s'" % (kind.lower(), name))
    if kind == "AREA":
        w.begin("AttributeBegin")
        w.write("Attribute", rib.string("identifier"), rib.string("name"), rib.array([name]))
        _transform(w, matrices)
        params = {"float intensity": energy / (4 * PI), "color lightcolor": color, "float twosided": 0.0}
        params.update(shadow)
        w.params("AreaLightSource", [rib.string("arealight"), handle], params)
        # The shape: drawn see-through (an area light is not seen by the camera in Cycles unless
        # asked). What a later streyes will read: not seen, casting no shadow.
        w.write("Attribute", rib.string("visibility"), rib.string("int camera"), "[0]",
                rib.string("int transmission"), "[0]")
        w.write("Opacity", "[0 0 0]")
        w.write("Surface", rib.string("constant"))
        _area_shape(w, light)
        w.end("AttributeEnd")
        w.write("Illuminate", handle, "1")
        return
    w.begin("TransformBegin")
    _transform(w, matrices)
    if kind == "SUN":
        params = {"float intensity": energy / PI, "color lightcolor": color,
                  "point from": (0, 0, 0), "point to": (0, 0, -1)}
        params.update(shadow)
        w.params("LightSource", [rib.string("distantlight"), handle], params)
    elif kind == "POINT":
        params = {"float intensity": energy / (4 * PI * PI), "color lightcolor": color, "point from": (0, 0, 0)}
        params.update(shadow)
        w.params("LightSource", [rib.string("pointlight"), handle], params)
    elif kind == "SPOT":
        half = min(light.spot_size, math.radians(179.9)) / 2
        cos_half = math.cos(half)
        blend_end = cos_half + (1 - cos_half) * max(0.0, min(1.0, light.spot_blend))
        # At least a thousandth of a radian: smoothstep over an empty range is not a step in SL.
        delta = max(half - math.acos(min(1.0, blend_end)), 1e-3)
        params = {"float intensity": energy / (4 * PI * PI), "color lightcolor": color,
                  "point from": (0, 0, 0), "point to": (0, 0, -1), "float coneangle": half,
                  "float conedeltaangle": min(delta, half), "float beamdistribution": 1.0}
        params.update(shadow)
        w.params("LightSource", [rib.string("spotlight"), handle], params)
    else:
        warn("light '%s': type %s is not supported: skipped" % (name, kind))
    w.end("TransformEnd")


def _transform(w, matrices):
    if len(matrices) == 1:
        w.write("ConcatTransform", rib.matrix(matrices[0][1]))
        return
    w.begin("MotionBegin", rib.array([t for t, _ in matrices]))
    for _, m in matrices:
        w.write("ConcatTransform", rib.matrix(m))
    w.end("MotionEnd")


def _area_shape(w, light):
    """The light's shape in its own space: centred on the origin in the xy plane, emitting
    towards -z. arealight's one side is where dP/du x dP/dv points (in the world, where the shape's
    points are; the mirror of the camera transform does not enter): corners in RenderMan order
    with u along y and v along x make it -z; the disk's face +z, so it is mirrored in y (a mirror in z
    would not move its points, nor turn it)."""
    sx = light.size
    sy = light.size_y if light.shape in ("RECTANGLE", "ELLIPSE") else light.size
    if light.shape in ("DISK", "ELLIPSE"):
        w.begin("TransformBegin")
        w.write("Scale", rib.nums((sx / 2, -sy / 2, 1)))
        w.write("Disk", "0 1 360")
        w.end("TransformEnd")
        return
    x, y = sx / 2, sy / 2
    w.write("Patch", rib.string("bilinear"), rib.string("P"),
            rib.array((-x, -y, 0, -x, y, 0, x, -y, 0, x, y, 0)))
