"""Exporting Blender's evaluated scene (the render depsgraph) as RIB, a complete file a frame.

Each frame is sampled at the shutter's times (engine.frame_set at sub-frames): transforms and
deforming meshes get a motion key at each; everything else is taken at the frame's own time.
Objects are named with Attribute "identifier" so that streyes's frame-sequence reader matches
them across frames and shares what stays still (docs/SCENE-FORMAT.md, "Frame sequences").
"""

import math
import os
import shutil

from . import camera as camera_mod
from . import lights as lights_mod
from . import materials as materials_mod
from . import mesh as mesh_mod
from . import rib

SHADER_DIR = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "shaders")


class Settings:
    """What the export reads of the scene's render settings (scene.render, scene.streyes)."""

    def __init__(self, scene):
        r = scene.render
        s = scene.streyes
        self.xres = max(1, int(r.resolution_x * r.resolution_percentage / 100))
        self.yres = max(1, int(r.resolution_y * r.resolution_percentage / 100))
        self.samples = s.samples
        self.pixel_samples = max(1, int(math.ceil(math.sqrt(s.samples))))
        self.filter_width = r.filter_size
        self.shading_rate = s.shading_rate
        self.film_transparent = r.film_transparent
        self.export_subdivision = s.export_subdivision
        self.motion = r.use_motion_blur and r.motion_blur_shutter > 0
        self.shutter = min(r.motion_blur_shutter, 1.0)
        cycles = getattr(scene, "cycles", None)
        self.position = getattr(cycles, "motion_blur_position", "CENTER") if cycles else "CENTER"
        self.motion_keys = max(2, s.motion_keys)
        self.step = max(1, scene.frame_step)

    def offsets(self):
        """The shutter's interval relative to the frame, in Blender frames."""
        if not self.motion:
            return 0.0, 0.0
        if self.position == "START":
            return 0.0, self.shutter
        if self.position == "END":
            return -self.shutter, 0.0
        return -self.shutter / 2, self.shutter / 2

    def times(self, frame):
        o, c = self.offsets()
        if o == c:
            return [float(frame)]
        n = self.motion_keys
        return [frame + o + (c - o) * k / (n - 1) for k in range(n)]


class Record:
    """One object instance over the frame's motion times."""

    def __init__(self, key, name, kind):
        self.key = key
        self.name = name        # its identifier
        self.kind = kind        # MESH, LIGHT, HAIR, INSTANCE
        self.matrices = {}      # time -> Matrix (object to world)
        self.positions = {}     # time -> points (deforming meshes, hair)
        self.data = None        # MeshData, light, hair strands at the frame's time
        self.materials = []     # by slot
        self.proto = None       # INSTANCE: the prototype's name
        self.visible_camera = True
        self.visible_shadow = True
        self.holdout = False


class Frame:
    def __init__(self, frame, number, times, main):
        self.frame = frame
        self.number = number
        self.times = times
        self.main = main
        self.camera = {}        # time -> Matrix
        self.projection = None
        self.records = {}
        self.prototypes = {}    # name -> (MeshData, materials)
        self.world = None


class Exporter:
    def __init__(self, engine, depsgraph, folder, warn):
        self.engine = engine
        self.depsgraph = depsgraph
        self.scene = depsgraph.scene
        self.settings = Settings(self.scene)
        self.folder = folder
        self.warn_cb = warn
        self.said = set()
        self.materials = materials_mod.Materials(folder, self.warn)
        self.first_projection = None
        self.subdivision_meshes = []   # names of objects written as SubdivisionMesh

    def warn(self, text):
        if text not in self.said:
            self.said.add(text)
            self.warn_cb(text)

    # -- numbering ------------------------------------------------------------------------------------
    def number(self, frame):
        """The RIB frame number of a Blender frame: the same with a frame step of 1 (and frames
        from 0 up); else consecutive numbers from 1, as a streyes sequence needs."""
        s = self.scene
        if self.settings.step == 1 and s.frame_start >= 0:
            return frame
        return (frame - s.frame_start) // self.settings.step + 1

    def rib_time(self, frame, number, t):
        return number + (t - frame) / self.settings.step

    # -- sampling -------------------------------------------------------------------------------------
    def sample(self, frame):
        number = self.number(frame)
        times = self.settings.times(frame)
        main = min(range(len(times)), key=lambda i: abs(times[i] - frame))
        fr = Frame(frame, number, times, main)
        for i, t in enumerate(times):
            whole = math.floor(t)
            self.engine.frame_set(int(whole), t - whole)
            self._snapshot(fr, t, i == main)
        return fr

    def _snapshot(self, fr, t, main):
        dg = self.depsgraph
        scene = dg.scene_eval
        cam = self.engine.camera_override or scene.camera
        if cam is None:
            raise ExportError("the scene has no camera")
        cam = cam.evaluated_get(dg)
        fr.camera[t] = cam.matrix_world.copy()
        if main:
            if cam.data.type == "PANO":
                raise ExportError("camera '%s': panoramic cameras are not supported by streyes" % cam.name)
            fr.projection = camera_mod.Projection(scene, cam, self.settings.xres, self.settings.yres)
            fr.world = self._world(scene)
        view_layer = dg.view_layer
        for inst in dg.object_instances:
            obj = inst.instance_object if inst.is_instance else inst.object
            if obj.type in ("CAMERA", "EMPTY", "ARMATURE", "LATTICE", "SPEAKER", "LIGHT_PROBE"):
                continue
            if inst.is_instance:
                parent = inst.parent
                key = ("I", parent.name, tuple(inst.persistent_id), obj.name)
                ident = "%s/%s/%s" % (parent.name, "-".join(str(i) for i in inst.persistent_id if i != 0x7fffffff), obj.name)
            else:
                key = ("O", obj.name)
                ident = obj.name
            if obj.type == "LIGHT":
                rec = self._record(fr, key, ident, "LIGHT")
                rec.matrices[t] = inst.matrix_world.copy()
                if main:
                    rec.data = obj.data
                continue
            if inst.show_self and obj.type in ("MESH", "CURVE", "SURFACE", "META", "FONT"):
                if inst.is_instance:
                    self._instance(fr, key, ident, inst, obj, t, main)
                else:
                    self._object(fr, key, ident, obj, t, main)
            if inst.show_particles and not inst.is_instance and len(obj.particle_systems):
                self._hair(fr, key, ident, obj, t, main)
            if obj.type == "CURVES":
                self.warn("object '%s': Curves objects (the new hair) are not exported yet: use a hair particle system" %
                          obj.name)
            elif obj.type in ("VOLUME", "POINTCLOUD", "GPENCIL"):
                self.warn("object '%s': %s objects are not exported" % (obj.name, obj.type.lower()))

    def _record(self, fr, key, ident, kind):
        rec = fr.records.get(key)
        if rec is None:
            rec = fr.records[key] = Record(key, ident, kind)
        return rec

    def _visibility(self, rec, obj):
        orig = obj.original
        rec.visible_camera = obj.visible_camera
        rec.visible_shadow = obj.visible_shadow
        try:
            rec.holdout = orig.holdout_get(view_layer=self.depsgraph.view_layer)
        except (TypeError, AttributeError):
            rec.holdout = getattr(orig, "is_holdout", False)

    def _object(self, fr, key, ident, obj, t, main):
        rec = self._record(fr, key, ident, "MESH")
        rec.matrices[t] = obj.matrix_world.copy()
        subdiv = mesh_mod.subdivision_modifier(obj) if self.settings.export_subdivision else None
        deforms = self._may_deform(obj)
        if not main and not deforms:
            return
        me = mesh_mod.evaluated_mesh(obj, self.depsgraph, subdiv is not None)
        try:
            if me is None:
                return
            if main:
                rec.data = mesh_mod.MeshData(me, subdiv)
                rec.materials = [s.material for s in obj.material_slots]
                self._visibility(rec, obj)
                if subdiv is not None and ident not in self.subdivision_meshes:
                    self.subdivision_meshes.append(ident)
            if deforms:
                rec.positions[t] = mesh_mod.positions(me)
        finally:
            obj.to_mesh_clear()

    def _may_deform(self, obj):
        if not self.settings.motion:
            return False
        cycles = getattr(obj.original, "cycles", None)
        if cycles is not None and not (cycles.use_motion_blur and cycles.use_deform_motion):
            return False
        try:
            return obj.original.is_deform_modified(self.scene, "RENDER")
        except (TypeError, AttributeError):
            return True

    def _instance(self, fr, key, ident, inst, obj, t, main):
        rec = self._record(fr, key, ident, "INSTANCE")
        rec.matrices[t] = inst.matrix_world.copy()
        if not main:
            return
        proto = obj.name
        rec.proto = proto
        rec.materials = [s.material for s in obj.material_slots]
        self._visibility(rec, obj)
        if proto not in fr.prototypes:
            subdiv = mesh_mod.subdivision_modifier(obj) if self.settings.export_subdivision else None
            me = mesh_mod.evaluated_mesh(obj, self.depsgraph, subdiv is not None)
            try:
                fr.prototypes[proto] = mesh_mod.MeshData(me, subdiv) if me is not None else None
            finally:
                obj.to_mesh_clear()

    def _hair(self, fr, key, ident, obj, t, main):
        for psys in obj.particle_systems:
            part = psys.settings
            if part.type != "HAIR" or part.render_type != "PATH":
                continue
            hkey = key + ("hair", psys.name)
            if not main and not self.settings.motion:
                continue
            strands = mesh_mod.hair_strands(obj, psys)
            if strands is None:
                continue
            rec = self._record(fr, hkey, ident + "/" + psys.name, "HAIR")
            rec.positions[t] = strands[0]
            if main:
                rec.data = strands
                slot = part.material - 1
                rec.materials = [obj.material_slots[slot].material if 0 <= slot < len(obj.material_slots) else None]
                self._visibility(rec, obj)

    def _world(self, scene):
        world = scene.world
        if world is None:
            return (0.0, 0.0, 0.0)
        if not world.use_nodes or world.node_tree is None:
            return tuple(world.color)[:3]
        out = [n for n in world.node_tree.nodes if n.bl_idname == "ShaderNodeOutputWorld" and n.is_active_output]
        out = out or [n for n in world.node_tree.nodes if n.bl_idname == "ShaderNodeOutputWorld"]
        if not out or not out[0].inputs["Surface"].is_linked:
            return (0.0, 0.0, 0.0)
        node = materials_mod._follow(out[0].inputs["Surface"])
        if node is None or node.bl_idname != "ShaderNodeBackground":
            self.warn("world '%s': only a Background node is rendered (found '%s')" %
                      (world.name, node.name if node else "nothing"))
            return (0.0, 0.0, 0.0)
        color = node.inputs["Color"]
        if color.is_linked:
            src = materials_mod._follow(color)
            self.warn("world '%s': node '%s' (%s) is not supported: the Background colour is used" %
                      (world.name, src.name if src else "?", src.bl_idname if src else "?"))
        strength = node.inputs["Strength"].default_value
        return tuple(c * strength for c in tuple(color.default_value)[:3])

    # -- writing --------------------------------------------------------------------------------------
    def write_frame(self, fr, path, display):
        st = self.settings
        w = rib.Writer()
        w.comment("streyes for Blender: scene '%s', Blender frame %d" % (self.scene.name, fr.frame))
        w.begin("FrameBegin", str(fr.number))
        w.write("Format", str(st.xres), str(st.yres), rib.num(fr.projection.pixel_aspect))
        w.write("PixelSamples", str(st.pixel_samples), str(st.pixel_samples))
        # Blender's filter width w is Blackman-Harris's radius (Cycles doubles it): RenderMan's
        # widths are the whole support.
        w.write("PixelFilter", rib.string("blackman-harris"), rib.num(2 * st.filter_width), rib.num(2 * st.filter_width))
        o, c = st.offsets()
        w.write("Shutter", rib.num(o / st.step), rib.num(c / st.step))
        proj = fr.projection
        if self.first_projection is None:
            self.first_projection = proj
        elif proj.key() != self.first_projection.key():
            self.warn("camera '%s': the projection (focal length, shift, sensor, clipping or focus) changes in "
                      "frame %d: a streyes sequence has one projection, so the frames use frame %d's" %
                      (proj.name, fr.frame, self._first_frame))
            proj = self.first_projection
        proj.write(w)
        if not st.film_transparent:
            w.params("Imager", [rib.string("background")], {"color background": fr.world})
        w.write("Display", rib.string(display), rib.string("openexr"), rib.string("rgba"))
        keys = self._keys(fr, fr.camera)
        self._transform(w, fr, keys, "Transform", camera_mod.world_to_camera)
        w.begin("WorldBegin")
        if any(fr.world):
            w.params("LightSource", [rib.string("ambientlight"), rib.string("world")],
                     {"float intensity": 1.0, "color lightcolor": fr.world})
        w.write("ShadingRate", rib.num(st.shading_rate))
        for rec in fr.records.values():
            if rec.kind == "LIGHT" and rec.data is not None:
                light = rec.data
                cycles = getattr(light, "cycles", None)
                shadows = cycles.cast_shadow if cycles is not None else light.use_shadow
                lights_mod.write_light(w, light, rec.name, self._rib_keys(fr, self._keys(fr, rec.matrices)),
                                       shadows, self.warn)
        for name, data in fr.prototypes.items():
            if data is None:
                continue
            for mat in data.used_materials():
                w.begin("ObjectBegin", rib.string("%s:%d" % (name, mat)))
                data.write(w, mat, [(None, data.P)])
                w.end("ObjectEnd")
        for rec in fr.records.values():
            if rec.kind in ("MESH", "INSTANCE", "HAIR") and (rec.data is not None or rec.proto):
                self._write_object(w, fr, rec)
        w.end("WorldEnd")
        w.end("FrameEnd")
        tmp = path + ".tmp"
        with open(tmp, "w") as f:
            f.write(w.text())
        os.replace(tmp, path)

    def _keys(self, fr, by_time):
        """[(time, value)] at the frame's times, one entry when nothing changes."""
        items = [(t, by_time[t]) for t in fr.times if t in by_time]
        if not items:
            return []
        first = items[0][1]
        if all(_same(v, first) for _, v in items[1:]):
            main_t = fr.times[fr.main]
            return [(main_t, by_time.get(main_t, first))]
        return items

    def _rib_keys(self, fr, keys):
        return [(self.rib_time(fr.frame, fr.number, t), v) for t, v in keys]

    def _transform(self, w, fr, keys, request, convert=lambda m: m):
        keys = self._rib_keys(fr, keys)
        if len(keys) == 1:
            w.write(request, rib.matrix(convert(keys[0][1])))
            return
        w.begin("MotionBegin", rib.array([t for t, _ in keys]))
        for _, m in keys:
            w.write(request, rib.matrix(convert(m)))
        w.end("MotionEnd")

    def _write_object(self, w, fr, rec):
        if not rec.visible_camera and not rec.visible_shadow:
            return  # seen by nothing that streyes renders (direct light)
        w.begin("AttributeBegin")
        w.write("Attribute", rib.string("identifier"), rib.string("name"), rib.array([rec.name]))
        if not rec.visible_camera:
            # Casts shadows, unseen: a see-through surface casts shadows as if opaque in streyes.
            w.write("Attribute", rib.string("visibility"), rib.string("int camera"), "[0]")
        if not rec.visible_shadow:
            self.warn("object '%s': not casting shadows needs Attribute \"visibility\" (a streyes that lacks it "
                      "warns and lets it cast them)" % rec.name)
            w.write("Attribute", rib.string("visibility"), rib.string("int transmission"), "[0]")
        if rec.kind != "HAIR":
            self._transform(w, fr, self._keys(fr, rec.matrices), "ConcatTransform")
        if rec.kind == "INSTANCE":
            data = fr.prototypes.get(rec.proto)
            for mat in (data.used_materials() if data else []):
                self._surface(w, rec, mat)
                w.write("ObjectInstance", rib.string("%s:%d" % (rec.proto, mat)))
        elif rec.kind == "HAIR":
            self._surface(w, rec, 0)
            mesh_mod.write_hair(w, rec.data, self._rib_keys(fr, self._position_keys(fr, rec)))
        else:
            data = rec.data
            keys = self._rib_keys(fr, self._position_keys(fr, rec))
            for mat in data.used_materials():
                w.begin("AttributeBegin")
                self._surface(w, rec, mat)
                data.write(w, mat, keys)
                w.end("AttributeEnd")
        w.end("AttributeEnd")

    def _position_keys(self, fr, rec):
        """[(time, points)]: a key at each time when the points change, else the frame's own."""
        main_t = fr.times[fr.main]
        pts = [(t, rec.positions[t]) for t in fr.times if t in rec.positions]
        if len(pts) > 1 and all(p.shape == pts[0][1].shape for _, p in pts):
            import numpy as np
            if not all(np.array_equal(p, pts[0][1]) for _, p in pts[1:]):
                return pts
        elif len(pts) > 1:
            self.warn("object '%s': its topology changes within the shutter: no deformation blur" % rec.name)
        base = rec.data.P if rec.kind != "HAIR" else rec.data[0]
        return [(main_t, base)]

    def _surface(self, w, rec, slot):
        mat = rec.materials[slot] if 0 <= slot < len(rec.materials) else None
        surface = self.materials.surface(mat)
        if rec.holdout:
            surface = materials_mod.Surface(holdout=True)
        if not rec.visible_camera:
            w.write("Opacity", "[0 0 0]")
            w.write("Surface", rib.string("constant"))
            return
        surface.write(w)

    # -- the whole export -----------------------------------------------------------------------------
    def export(self, frames, stem, progress=None):
        """Writes FOLDER/STEM.####.rib for each Blender frame and the shaders beside them; returns
        [(frame, number, rib path)]."""
        os.makedirs(self.folder, exist_ok=True)
        for name in os.listdir(SHADER_DIR):
            if name.endswith(".sl"):
                shutil.copyfile(os.path.join(SHADER_DIR, name), os.path.join(self.folder, name))
        current = self.scene.frame_current
        done = []
        self._first_frame = frames[0] if frames else current
        try:
            for i, frame in enumerate(frames):
                fr = self.sample(frame)
                path = os.path.join(self.folder, "%s.%04d.rib" % (stem, fr.number))
                self.write_frame(fr, path, "%s.####.exr" % stem)
                done.append((frame, fr.number, path))
                if progress:
                    progress(i + 1, len(frames))
        finally:
            self.engine.frame_set(current, 0.0)
        return done


class ExportError(Exception):
    pass


def _same(a, b):
    try:
        return a == b
    except Exception:
        return False
