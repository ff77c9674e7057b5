"""The engine's panels in the Render properties, and Blender's own panels (output, camera,
lights, materials, world) made to show for it."""

import bpy

ENGINE = "STREYES"


class StreyesPanel:
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {ENGINE}

    @classmethod
    def poll(cls, context):
        return context.engine == ENGINE


class RENDER_PT_streyes_sampling(StreyesPanel, bpy.types.Panel):
    bl_label = "Sampling"

    def draw(self, context):
        s = context.scene.streyes
        layout = self.layout
        layout.use_property_split = True
        layout.prop(s, "samples")
        layout.prop(s, "shading_rate")
        layout.prop(s, "tolerance")


class RENDER_PT_streyes_film(StreyesPanel, bpy.types.Panel):
    bl_label = "Film"

    def draw(self, context):
        r = context.scene.render
        layout = self.layout
        layout.use_property_split = True
        layout.prop(r, "filter_size", text="Filter Size (Blackman-Harris)")
        layout.prop(r, "film_transparent", text="Transparent")


class RENDER_PT_streyes_motion_blur(StreyesPanel, bpy.types.Panel):
    bl_label = "Motion Blur"
    bl_options = {"DEFAULT_CLOSED"}

    def draw_header(self, context):
        self.layout.prop(context.scene.render, "use_motion_blur", text="")

    def draw(self, context):
        scene = context.scene
        layout = self.layout
        layout.use_property_split = True
        layout.active = scene.render.use_motion_blur
        cycles = getattr(scene, "cycles", None)
        if cycles is not None and hasattr(cycles, "motion_blur_position"):
            layout.prop(cycles, "motion_blur_position", text="Position")
        layout.prop(scene.render, "motion_blur_shutter")
        layout.prop(scene.streyes, "motion_keys")


class RENDER_PT_streyes_geometry(StreyesPanel, bpy.types.Panel):
    bl_label = "Geometry"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.prop(context.scene.streyes, "export_subdivision")


class RENDER_PT_streyes_performance(StreyesPanel, bpy.types.Panel):
    bl_label = "Performance"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        r = context.scene.render
        layout = self.layout
        layout.use_property_split = True
        layout.prop(r, "threads_mode")
        sub = layout.row()
        sub.enabled = r.threads_mode == "FIXED"
        sub.prop(r, "threads")


class RENDER_PT_streyes_files(StreyesPanel, bpy.types.Panel):
    bl_label = "Export"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        s = context.scene.streyes
        layout = self.layout
        layout.use_property_split = True
        layout.prop(s, "keep_files")
        row = layout.row()
        row.active = s.keep_files
        row.prop(s, "export_folder")


classes = (RENDER_PT_streyes_sampling, RENDER_PT_streyes_film, RENDER_PT_streyes_motion_blur,
           RENDER_PT_streyes_geometry, RENDER_PT_streyes_performance, RENDER_PT_streyes_files)

# Blender's own panels that apply to this engine as they are: output and format, camera, lights
# (Eevee's shows power, colour, size and spot shape), materials and world as node trees.
_BORROWED = (
    "RENDER_PT_format", "RENDER_PT_frame_range", "RENDER_PT_time_stretching", "RENDER_PT_output",
    "RENDER_PT_output_views", "RENDER_PT_encoding", "RENDER_PT_encoding_video", "RENDER_PT_encoding_audio",
    "RENDER_PT_post_processing", "RENDER_PT_stamp", "RENDER_PT_color_management",
    "DATA_PT_lens", "DATA_PT_camera", "DATA_PT_camera_dof", "DATA_PT_camera_dof_aperture",
    "DATA_PT_camera_display", "DATA_PT_context_light", "DATA_PT_EEVEE_light", "DATA_PT_EEVEE_light_distance",
    "DATA_PT_spot", "DATA_PT_context_mesh", "DATA_PT_normals", "DATA_PT_uv_texture", "DATA_PT_vertex_colors",
    "DATA_PT_shape_keys", "DATA_PT_vertex_groups", "DATA_PT_customdata",
    "MATERIAL_PT_preview", "EEVEE_MATERIAL_PT_context_material", "EEVEE_MATERIAL_PT_surface",
    "WORLD_PT_context_world", "EEVEE_WORLD_PT_surface",
    "OBJECT_PT_visibility", "PARTICLE_PT_context_particles", "PARTICLE_PT_hair_dynamics",
    "PARTICLE_PT_render", "PARTICLE_PT_children", "PARTICLE_PT_hair_shape",
)


def _borrowed():
    for name in _BORROWED:
        panel = getattr(bpy.types, name, None)
        if panel is not None and hasattr(panel, "COMPAT_ENGINES"):
            yield panel


def register():
    for c in classes:
        bpy.utils.register_class(c)
    for panel in _borrowed():
        panel.COMPAT_ENGINES.add(ENGINE)


def unregister():
    for panel in _borrowed():
        panel.COMPAT_ENGINES.discard(ENGINE)
    for c in reversed(classes):
        bpy.utils.unregister_class(c)
