"""Installing the add-on the Blender way: tools/blender-addon zip makes a zip that Blender's
Install button (bpy.ops.preferences.addon_install) takes; enabled, the add-on finds streyes by
its preference alone (no STREYES_BIN, not on the PATH) and renders a frame; disabled, it is gone.

    install_test.py BLENDER STREYES SOURCE WORK
"""

import os
import shutil
import subprocess
import sys

BLENDER, STREYES, SOURCE, WORK = sys.argv[1:5]
shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
zip_path = os.path.join(WORK, "streyes_blender.zip")
subprocess.run([os.path.join(SOURCE, "tools", "blender-addon"), "zip", zip_path], check=True)

script = r'''
import bpy, os, sys
work, zip_path, streyes = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.preferences.addon_install(filepath=zip_path)
bpy.ops.preferences.addon_enable(module="streyes_blender")
bpy.context.preferences.addons["streyes_blender"].preferences.streyes_path = streyes
scene = bpy.context.scene           # the default scene: a cube, a light, a camera
scene.render.engine = "STREYES"
assert scene.render.engine == "STREYES"
panels = [p for p in dir(bpy.types) if p.startswith("RENDER_PT_streyes")]
scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 64, 48, 100
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.filepath = os.path.join(work, "still")
bpy.ops.render.render(write_still=True)
print("PANELS", len(panels))
print("WROTE", os.path.exists(os.path.join(work, "still.exr")))
bpy.ops.preferences.addon_disable(module="streyes_blender")
engines = [e.identifier for e in scene.render.bl_rna.properties["engine"].enum_items]
print("AFTER-DISABLE", "STREYES" in engines, hasattr(bpy.types.Scene, "streyes"))
'''
env = dict(os.environ, BLENDER_USER_SCRIPTS=os.path.join(WORK, "user-scripts"), BLENDER_USER_CONFIG=os.path.join(WORK, "config"))
env.pop("STREYES_BIN", None)
env["PATH"] = ":".join(p for p in env.get("PATH", "").split(":") if "pyenv" not in p and not os.path.exists(os.path.join(p, "streyes")))
for k in [k for k in env if k.startswith("PYENV")]:
    del env[k]
p = subprocess.run([BLENDER, "-b", "--factory-startup", "--python-exit-code", "1", "--python-expr", script, "--",
                    WORK, zip_path, STREYES], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                   timeout=300)
print(p.stdout[-2000:])
failures = []
for ok, text in [(p.returncode == 0, "Blender ran the install script (exit %d)" % p.returncode),
                 ("PANELS 6" in p.stdout, "the engine's six panels are registered"),
                 ("WROTE True" in p.stdout, "installed from the zip and found by its preference, it renders a frame"),
                 ("AFTER-DISABLE False False" in p.stdout, "disabled, the engine and its settings are gone")]:
    print(("ok      " if ok else "FAILED  ") + text)
    if not ok:
        failures.append(text)
sys.exit(1 if failures else 0)
