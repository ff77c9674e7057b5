"""streyes for Blender: streyes (SpaceTime REYES) as a render engine.

An animation render exports the whole frame range as a RIB sequence and renders it with one
`streyes render`, which treats the animation as one spacetime scene: what stays still is split,
diced and shaded once for all the frames. See the README's "Rendering from Blender".
"""

bl_info = {
    "name": "streyes",
    "author": "the streyes authors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Render > Render Engine > streyes",
    "description": "Renders with streyes, a spacetime REYES renderer: a whole animation as one scene",
    "category": "Render",
}

if "bpy" in locals():  # "Reload Scripts"
    import importlib
    for _m in (job, export, properties, ui, engine):  # noqa: F821
        importlib.reload(_m)

import bpy  # noqa: E402

from . import job, export, properties, ui, engine  # noqa: E402


def register():
    properties.register()
    bpy.utils.register_class(engine.StreyesRenderEngine)
    ui.register()


def unregister():
    ui.unregister()
    bpy.utils.unregister_class(engine.StreyesRenderEngine)
    properties.unregister()
