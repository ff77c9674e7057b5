"""Blender materials as RenderMan surfaces.

Diffuse BSDF becomes the standard "matte" (Cs the colour, Kd 1: with the light units of
lights.py a diffuse surface gets Cycles' brightness); Principled BSDF becomes
shaders/blender_principled.sl (base colour, metallic, specular, roughness, alpha, emission, an
image texture on the base colour through texture()); Emission becomes "constant"; Holdout a
matte object. Anything else is approximated with a warning naming the material and the node.
"""

import os
import shutil

import bpy

from . import rib

GREY = (0.8, 0.8, 0.8)


class Surface:
    """What an object's faces of one material are shaded with."""

    def __init__(self, shader="matte", params=None, color=GREY, opacity=1.0, holdout=False):
        self.shader = shader
        self.params = params or {}
        self.color = tuple(color)
        self.opacity = opacity
        self.holdout = holdout

    def write(self, w):
        if self.holdout:
            # RenderMan's holdout: hides what is behind, leaves colour 0 and alpha 0 (as Cycles'
            # Holdout; tests/blender/export_test.py compares the two).
            w.write("Matte", "1")
            w.write("Surface", rib.string("constant"))
            w.write("Color", "[0 0 0]")
            return
        w.params("Surface", [rib.string(self.shader)], self.params)
        w.write("Color", rib.array(self.color))
        if self.opacity < 1.0:
            a = max(0.0, min(1.0, self.opacity))
            w.write("Opacity", rib.array((a, a, a)))


class Materials:
    """Converts each material once per export and remembers its warnings (said once each)."""

    def __init__(self, folder, warn):
        self.folder = folder  # where packed images are written
        self.warn = warn
        self.cache = {}
        self.said = set()
        self.textures = {}

    def _warn(self, key, text):
        if key not in self.said:
            self.said.add(key)
            self.warn(text)

    def surface(self, material):
        if material is None:
            return Surface()
        key = material.name_full if hasattr(material, "name_full") else material.name
        if key not in self.cache:
            self.cache[key] = self._convert(material)
        return self.cache[key]

    # -- conversion ----------------------------------------------------------------------------------
    def _convert(self, mat):
        if not mat.use_nodes or mat.node_tree is None:
            # Cycles renders a material without nodes as a diffuse surface of its viewport colour.
            return Surface("matte", {"Ka": 1, "Kd": 1}, tuple(mat.diffuse_color)[:3])
        out = _active_output(mat.node_tree)
        if out is None or not out.inputs["Surface"].is_linked:
            return Surface("constant", {}, (0, 0, 0))  # Cycles: black
        node = _follow(out.inputs["Surface"])
        return self._shader_node(mat, node)

    def _unsupported(self, mat, node, what):
        self._warn((mat.name, node.name),
                   "material '%s': node '%s' (%s) is not supported: %s" % (mat.name, node.name, node.bl_idname, what))

    def _shader_node(self, mat, node):
        kind = node.bl_idname if node else None
        if kind == "ShaderNodeBsdfDiffuse":
            color, tex = self._color_input(mat, node.inputs["Color"])
            if _value(node.inputs["Roughness"]) > 0:
                self._warn((mat.name, node.name, "roughness"),
                           "material '%s': node '%s': Oren-Nayar roughness is rendered as Lambertian (roughness 0)" %
                           (mat.name, node.name))
            self._linked_normal(mat, node)
            if tex:
                return Surface("blender_principled", dict({"float specular": 0.0}, **tex), color)
            return Surface("matte", {"Ka": 1, "Kd": 1}, color)
        if kind == "ShaderNodeBsdfPrincipled":
            return self._principled(mat, node)
        if kind == "ShaderNodeEmission":
            color, _ = self._color_input(mat, node.inputs["Color"], allow_texture=False)
            s = _value(node.inputs["Strength"])
            return Surface("constant", {}, tuple(c * s for c in color))
        if kind == "ShaderNodeHoldout":
            return Surface(holdout=True)
        if kind in ("ShaderNodeMixShader", "ShaderNodeAddShader"):
            first = [i for i in node.inputs if i.type == "SHADER" and i.is_linked]
            self._unsupported(mat, node, "rendered as its first shader input" if first else "rendered grey")
            return self._shader_node(mat, _follow(first[0])) if first else Surface()
        if node is None:
            return Surface("constant", {}, (0, 0, 0))
        self._unsupported(mat, node, "rendered as a grey diffuse surface")
        return Surface()

    def _principled(self, mat, node):
        inp = node.inputs
        color, tex = self._color_input(mat, inp["Base Color"])
        params = {
            "float metallic": _scalar(self, mat, inp["Metallic"]),
            "float specular": _scalar(self, mat, inp["Specular"]),
            "float roughness": _scalar(self, mat, inp["Roughness"]),
        }
        emission, _ = self._color_input(mat, inp["Emission"], allow_texture=False)
        strength = _scalar(self, mat, inp["Emission Strength"]) if "Emission Strength" in inp else 1.0
        emission = tuple(c * strength for c in emission)
        if any(emission):
            params["color emission"] = emission
        params.update(tex or {})
        # What the principled shader does not model, said once per material.
        ignored = [name for name, default in (("Subsurface", 0.0), ("Transmission", 0.0), ("Clearcoat", 0.0),
                                              ("Sheen", 0.0), ("Anisotropic", 0.0))
                   if name in inp and (inp[name].is_linked or abs(_value(inp[name]) - default) > 1e-6)]
        if ignored:
            self._warn((mat.name, node.name, "lobes"), "material '%s': node '%s': %s not rendered (base colour, "
                       "metallic, specular, roughness, alpha and emission are)" % (mat.name, node.name, ", ".join(ignored)))
        self._linked_normal(mat, node)
        alpha = _scalar(self, mat, inp["Alpha"])
        return Surface("blender_principled", params, color, opacity=alpha)

    def _linked_normal(self, mat, node):
        if "Normal" in node.inputs and node.inputs["Normal"].is_linked:
            src = _follow(node.inputs["Normal"])
            if src is not None:
                self._unsupported(mat, src, "bump and normal maps are not rendered")

    def _color_input(self, mat, socket, allow_texture=True):
        """(colour, texture parameters or None): the socket's own value, or an image texture."""
        if not socket.is_linked:
            return tuple(socket.default_value)[:3], None
        src = _follow(socket)
        if allow_texture and src is not None and src.bl_idname == "ShaderNodeTexImage":
            tex = self._image_texture(mat, src)
            if tex:
                return (1.0, 1.0, 1.0), tex
        if src is not None and src.bl_idname != "ShaderNodeTexImage":
            self._unsupported(mat, src, "the socket's own value is used")
        return tuple(socket.default_value)[:3], None

    def _image_texture(self, mat, node):
        image = node.image
        if image is None:
            return None
        vec = node.inputs["Vector"]
        if vec.is_linked:
            src = _follow(vec)
            if src is not None and not (src.bl_idname == "ShaderNodeUVMap" or
                                        (src.bl_idname == "ShaderNodeTexCoord" and vec.links[0].from_socket.name == "UV")):
                self._unsupported(mat, src, "image textures are looked up by the mesh's UV map")
        path = self._image_file(mat, image)
        if not path:
            return None
        srgb = 1.0 if image.colorspace_settings.name in ("sRGB", "Filmic sRGB") else 0.0
        return {"string basemap": path, "float basemap_srgb": srgb}

    def _image_file(self, mat, image):
        key = image.name_full if hasattr(image, "name_full") else image.name
        if key in self.textures:
            return self.textures[key]
        path = None
        if image.packed_file is not None:
            ext = os.path.splitext(image.filepath_raw or "")[1] or ".png"
            path = os.path.join(self.folder, "textures", bpy.path.clean_name(image.name) + ext)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "wb") as f:
                f.write(image.packed_file.data)
        elif image.source in ("FILE", "SEQUENCE", "MOVIE") and image.filepath:
            path = bpy.path.abspath(image.filepath, library=image.library)
            path = os.path.normpath(path)
            if not os.path.isfile(path):
                self._warn(("image", key), "material '%s': image '%s': file '%s' not found: the base colour is used" %
                           (mat.name, image.name, path))
                path = None
        else:
            self._warn(("image", key), "material '%s': image '%s' is generated, not a file: save it to render it" %
                       (mat.name, image.name))
        self.textures[key] = path
        return path


def _active_output(tree):
    outs = [n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial"]
    for n in outs:
        if n.is_active_output and n.target in ("ALL", "CYCLES"):
            return n
    for n in outs:
        if n.target in ("ALL", "CYCLES"):
            return n
    return outs[0] if outs else None


def _follow(socket):
    """The node feeding a socket, through reroutes; None if nothing is."""
    while socket.is_linked:
        link = socket.links[0]
        if not link.is_valid or link.is_muted:
            return None
        node = link.from_node
        if node.bl_idname == "NodeReroute":
            socket = node.inputs[0]
            continue
        return node
    return None


def _value(socket):
    v = socket.default_value
    try:
        return float(v)
    except TypeError:
        return float(v[0])


def _scalar(materials, mat, socket):
    if socket.is_linked:
        src = _follow(socket)
        if src is not None:
            materials._unsupported(mat, src, "the socket '%s' takes its own value" % socket.name)
    return _value(socket)
