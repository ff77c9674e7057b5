"""The engine's settings (scene.streyes) and the add-on's preferences (where streyes is)."""

import bpy
from bpy.props import BoolProperty, FloatProperty, IntProperty, PointerProperty, StringProperty

ADDON = __package__.rsplit(".", 1)[0]


class StreyesPreferences(bpy.types.AddonPreferences):
    bl_idname = ADDON

    streyes_path: StringProperty(
        name="streyes",
        description="The streyes command. Empty: $STREYES_BIN, then the PATH",
        subtype="FILE_PATH",
        default="",
    )

    def draw(self, context):
        self.layout.prop(self, "streyes_path")
        self.layout.label(text="Empty: the STREYES_BIN environment variable, then streyes on the PATH")


class StreyesSceneSettings(bpy.types.PropertyGroup):
    samples: IntProperty(
        name="Samples",
        description="Samples per pixel per frame (rounded up to a square: PixelSamples n n)",
        default=16, min=1, soft_max=256, max=4096,
    )
    tolerance: FloatProperty(
        name="Occlusion Tolerance",
        description="Drop bodies at most this much of whose pixel-frame block is uncovered (0: exact; "
                    "0.05 for quick previews)",
        default=0.0, min=0.0, max=1.0,
    )
    shading_rate: FloatProperty(
        name="Shading Rate",
        description="Micropolygon area in pixels (RenderMan's ShadingRate)",
        default=1.0, min=0.01, soft_max=16.0,
    )
    motion_keys: IntProperty(
        name="Motion Keys",
        description="Motion keys per frame over the shutter, for transforms and deforming meshes "
                    "(3: open, middle, close, as Cycles' default motion steps)",
        default=3, min=2, max=9,
    )
    export_subdivision: BoolProperty(
        name="Subdivision Surfaces",
        description="Send a mesh whose last modifier is a Catmull-Clark Subdivision Surface as a SubdivisionMesh "
                    "(its control mesh and creases; streyes dices the limit surface) instead of its polygons",
        default=True,
    )
    keep_files: BoolProperty(
        name="Keep Files",
        description="Keep the exported RIB sequence and streyes's EXR frames in the export folder (for "
                    "'streyes farm submit', or to resume an interrupted animation)",
        default=False,
    )
    export_folder: StringProperty(
        name="Export Folder",
        description="Where kept files go (a folder per scene inside it)",
        subtype="DIR_PATH",
        default="//streyes/",
    )


classes = (StreyesPreferences, StreyesSceneSettings)


def register():
    for c in classes:
        bpy.utils.register_class(c)
    bpy.types.Scene.streyes = PointerProperty(type=StreyesSceneSettings)


def unregister():
    del bpy.types.Scene.streyes
    for c in reversed(classes):
        bpy.utils.unregister_class(c)
