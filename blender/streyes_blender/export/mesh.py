"""Meshes as RenderMan geometry: PointsPolygons, or SubdivisionMesh when the last modifier is a
Catmull-Clark Subdivision Surface (the control mesh before it, with its creases and corners: the
renderer dices the limit surface itself), and hair as Curves.

Data come out of Blender through foreach_get into numpy arrays, and go into the RIB as they are
(object space): the same mesh is written the same in every frame."""

import numpy as np

from . import rib

INFINITE_SHARPNESS = 10.0


def subdivision_modifier(obj):
    """The object's last modifier if it is a Catmull-Clark Subdivision Surface shown in renders."""
    if obj.type != "MESH" or len(obj.modifiers) == 0:
        return None
    mod = obj.modifiers[-1]
    if mod.type == "SUBSURF" and mod.show_render and mod.subdivision_type == "CATMULL_CLARK" and mod.render_levels > 0:
        return mod
    return None


def evaluated_mesh(obj, depsgraph, without_subdivision):
    """A temporary mesh of the evaluated object (free it with obj.to_mesh_clear()). Without the
    subdivision modifier: the object's modifiers evaluated again with that one off, as Cycles
    does for its adaptive subdivision (on the evaluated copy: the user's object is untouched)."""
    if not without_subdivision:
        return obj.to_mesh()
    mod = obj.modifiers[-1]
    was = (mod.show_render, mod.show_viewport)
    mod.show_render = False
    mod.show_viewport = False
    try:
        return obj.to_mesh(preserve_all_data_layers=True, depsgraph=depsgraph)
    finally:
        mod.show_render, mod.show_viewport = was


def _get(collection, attr, n, width, dtype):
    a = np.empty(n * width, dtype=dtype)
    if n:
        collection.foreach_get(attr, a)
    return a.reshape(n, width) if width > 1 else a


def positions(mesh):
    return _get(mesh.vertices, "co", len(mesh.vertices), 3, np.float32)


class MeshData:
    """What one mesh is at the frame's own time (topology, normals, UVs, creases)."""

    def __init__(self, mesh, subdivision=None):
        nv, nf, nl = len(mesh.vertices), len(mesh.polygons), len(mesh.loops)
        self.P = positions(mesh)
        self.counts = _get(mesh.polygons, "loop_total", nf, 1, np.int32)
        self.starts = _get(mesh.polygons, "loop_start", nf, 1, np.int32)
        self.loop_verts = _get(mesh.loops, "vertex_index", nl, 1, np.int32)
        self.material_index = _get(mesh.polygons, "material_index", nf, 1, np.int32)
        self.subdivision = subdivision is not None
        self.N = None
        self.N_class = None
        self.st = None
        uv = None
        for layer in mesh.uv_layers:
            if layer.active_render:
                uv = layer
        if uv is None and len(mesh.uv_layers):
            uv = mesh.uv_layers.active
        if uv is not None and nl:
            st = _get(uv.data, "uv", nl, 2, np.float32)
            st[:, 1] = 1.0 - st[:, 1]  # Blender's v runs up the image; texture t runs down
            self.st = st
        if self.subdivision:
            self._creases(mesh, subdivision)
            return
        smooth = _get(mesh.polygons, "use_smooth", nf, 1, bool)
        if mesh.has_custom_normals or (mesh.use_auto_smooth and smooth.any()) or (smooth.any() and not smooth.all()):
            mesh.calc_normals_split()
            self.N = _get(mesh.loops, "normal", nl, 3, np.float32)
            self.N_class = "facevarying"
        elif smooth.all() and nf:
            self.N = _get(mesh.vertices, "normal", nv, 3, np.float32)
            self.N_class = "vertex"
        # else: every face flat; the polygons' own normals are the flat shading.

    def _creases(self, mesh, mod):
        self.creases = []
        self.corners = []
        self.boundary = 2 if mod.boundary_smooth == "ALL" else 1
        if mod.use_creases:
            ne = len(mesh.edges)
            if ne and mesh.has_crease_edge:
                c = _get(mesh.edges, "crease", ne, 1, np.float32)
                ev = _get(mesh.edges, "vertices", ne, 2, np.int32)
                for i in np.nonzero(c > 0)[0]:
                    # Blender's crease c is OpenSubdiv's sharpness 10 c^2 (BKE_subdiv_crease_to_sharpness_f).
                    self.creases.append((int(ev[i, 0]), int(ev[i, 1]), min(10.0 * float(c[i]) ** 2, INFINITE_SHARPNESS)))
            if len(mesh.vertices) and mesh.has_crease_vertex:
                vc = np.array([d.value for d in mesh.vertex_creases[0].data], dtype=np.float32) \
                    if len(mesh.vertex_creases) else np.zeros(0, np.float32)
                for i in np.nonzero(vc > 0)[0]:
                    self.corners.append((int(i), min(10.0 * float(vc[i]) ** 2, INFINITE_SHARPNESS)))

    def used_materials(self):
        return sorted(set(self.material_index.tolist())) if len(self.material_index) else [0]

    def _faces(self, material):
        sel = self.material_index == material
        counts = self.counts[sel]
        starts = self.starts[sel]
        # The loops of the selected faces, in order: each face's run of loop indices.
        loops = np.repeat(starts - np.concatenate(([0], np.cumsum(counts)[:-1])), counts) + np.arange(counts.sum())
        return sel, counts, loops

    def write_polygons(self, w, material, keys):
        """PointsPolygons of the faces of one material; `keys` are the positions at each motion
        time (one entry: no deformation)."""
        sel, counts, loops = self._faces(material)
        if len(counts) == 0:
            return
        verts = self.loop_verts[loops]
        used, remap = np.unique(verts, return_inverse=True)
        if len(keys) > 1:
            w.begin("MotionBegin", rib.array([t for t, _ in keys]))
        for _, P in keys:
            extra = []
            if self.N is not None:
                N = self.N[used] if self.N_class == "vertex" else self.N[loops]
                extra += [rib.string("%s normal N" % self.N_class), rib.array(N.ravel())]
            if self.st is not None:
                extra += [rib.string("facevarying float[2] st"), rib.array(self.st[loops].ravel())]
            w.write("PointsPolygons", rib.array(counts, "int"), rib.array(remap, "int"),
                    rib.string("P"), rib.array(P[used].ravel()), *extra)
        if len(keys) > 1:
            w.end("MotionEnd")

    def write_subdivision(self, w, material, keys):
        """A SubdivisionMesh of the whole control mesh; faces of other materials are holes, so
        that each material's part is the same piece of one limit surface."""
        names, nargs, intargs, floatargs = [], [], [], []
        if self.boundary:
            names.append("interpolateboundary")
            nargs += [1, 0]
            intargs.append(self.boundary)
        for a, b, s in self.creases:
            names.append("crease")
            nargs += [2, 1]
            intargs += [a, b]
            floatargs.append(s)
        for v, s in self.corners:
            names.append("corner")
            nargs += [1, 1]
            intargs.append(v)
            floatargs.append(s)
        holes = np.nonzero(self.material_index != material)[0] if len(self.used_materials()) > 1 else []
        if len(holes):
            names.append("hole")
            nargs += [len(holes), 0]
            intargs += [int(h) for h in holes]
        extra = []
        if self.st is not None:
            extra += [rib.string("facevarying float[2] st"), rib.array(self.st.ravel())]
        if len(keys) > 1:
            w.begin("MotionBegin", rib.array([t for t, _ in keys]))
        for _, P in keys:
            w.write("SubdivisionMesh", rib.string("catmull-clark"), rib.array(self.counts, "int"),
                    rib.array(self.loop_verts, "int"), rib.array(names, "string"), rib.array(nargs, "int"),
                    rib.array(intargs, "int"), rib.array(floatargs), rib.string("P"), rib.array(P.ravel()), *extra)
        if len(keys) > 1:
            w.end("MotionEnd")

    def write(self, w, material, keys):
        if self.subdivision:
            self.write_subdivision(w, material, keys)
        else:
            self.write_polygons(w, material, keys)


def hair_strands(obj, psys, settings_render=True):
    """World-space points of every strand of a hair particle system (parents then children) and
    the strand's root and tip widths, or None when it has none."""
    part = psys.settings
    steps = 2 ** (part.render_step if settings_render else part.display_step) + 1
    total = len(psys.particles) + len(psys.child_particles)
    if total == 0:
        return None
    pts = np.empty((total, steps, 3), dtype=np.float32)
    for i in range(total):
        for k in range(steps):
            pts[i, k] = psys.co_hair(obj, particle_no=i, step=k)
    # Cycles: radius = radius_scale * root_radius / 2 at the root, tip_radius at the tip.
    root = part.radius_scale * part.root_radius
    tip = part.radius_scale * part.tip_radius
    return pts, root, tip


def write_hair(w, strands, keys=None):
    """Curves "linear", one per strand, widths going linearly from root to tip; the points are
    world space, so the caller writes no transform. keys: [(time, points)] for motion."""
    pts, root, tip = strands
    n, steps, _ = pts.shape
    width = np.tile(np.linspace(root, tip, steps, dtype=np.float32), n)
    keys = keys or [(None, pts)]
    if len(keys) > 1:
        w.begin("MotionBegin", rib.array([t for t, _ in keys]))
    for _, p in keys:
        w.write("Curves", rib.string("linear"), rib.array([steps] * n, "int"), rib.string("nonperiodic"),
                rib.string("P"), rib.array(p.ravel()), rib.string("width"), rib.array(width))
    if len(keys) > 1:
        w.end("MotionEnd")
