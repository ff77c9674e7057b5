#!/usr/bin/env python3
"""The installed package works for a program outside the source tree.

Installs the build into a temporary prefix, builds examples/render_rib against it with
find_package(streyes), renders a scene whose coverage is known (a square over a quarter of the
image) and checks the numbers the program prints and the frame it writes. Then builds
examples/ri_scene (C, through <ri.h>) and the Menger plug-in against the same prefix.

  package_test.py BUILD_DIR SOURCE_DIR
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

BUILD, SOURCE = (os.path.abspath(a) for a in sys.argv[1:3])

# 64 x 64 pixels, one scene unit a pixel, a box filter one pixel wide: the square [16, 48]^2
# covers exactly a quarter of the image.
SCENE = """Format 64 64 1
Projection "orthographic"
ScreenWindow 0 64 0 64
PixelFilter "box" 1 1
PixelSamples 2 2
WorldBegin
  Surface "constant"
  Color [1 0.5 0.25]
  Patch "bilinear" "P" [16 16 5  48 16 5  16 48 5  48 48 5]
WorldEnd
"""


def run(args, **kw):
    r = subprocess.run(args, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        raise AssertionError(f"{' '.join(args)} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return r


class Package(unittest.TestCase):
    def test_example_builds_against_the_installed_package_and_renders(self):
        with tempfile.TemporaryDirectory(prefix="streyes-package-") as tmp:
            prefix = os.path.join(tmp, "prefix")
            run(["cmake", "--install", BUILD, "--prefix", prefix])
            # Only public headers are installed, and nothing of src/.
            headers = sorted(os.listdir(os.path.join(prefix, "include", "streyes")))
            self.assertEqual([h for h in headers if not h.endswith(".h")], [])
            self.assertIn("renderer.h", headers)
            self.assertNotIn("rasterizer.h", headers)
            self.assertTrue(os.path.isfile(os.path.join(prefix, "bin", "streyes")))

            example = os.path.join(tmp, "example")
            shutil.copytree(os.path.join(SOURCE, "examples", "render_rib"), example)
            # Every installed header compiles on its own (one translation unit includes each).
            with open(os.path.join(example, "all_headers.cpp"), "w") as f:
                f.writelines(f'#include <streyes/{h}>\n' for h in headers)
                f.write('#include <ri.h>\n')
            with open(os.path.join(example, "CMakeLists.txt"), "a") as f:
                f.write("target_sources(render_rib PRIVATE all_headers.cpp)\n")
            run(["cmake", "-S", example, "-B", os.path.join(tmp, "build"), "-G", "Ninja",
                 "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_PREFIX_PATH=" + prefix])
            run(["cmake", "--build", os.path.join(tmp, "build")])

            scene = os.path.join(tmp, "square.rib")
            with open(scene, "w") as f:
                f.write(SCENE)
            out = os.path.join(tmp, "square.####.exr")
            r = run([os.path.join(tmp, "build", "render_rib"), scene, out, "--threads", "2"])
            m = re.search(r"frame 0: 64x64 mean alpha ([0-9.]+)", r.stdout)
            self.assertIsNotNone(m, r.stdout)
            self.assertAlmostEqual(float(m.group(1)), 0.25, places=6)
            frame = os.path.join(tmp, "square.0000.exr")
            self.assertTrue(os.path.isfile(frame))
            self.assertIn(frame + ": centre R=1 G=0.5 B=0.25 A=1 Z=5\n", r.stdout)

    def test_c_program_builds_a_scene_through_ri_h_and_loads_a_plugin(self):
        """examples/ri_scene (C, <ri.h>) against the installed package, with the Menger plug-in
        built from the installed header alone: the RIB it writes and the frame it renders agree."""
        with tempfile.TemporaryDirectory(prefix="streyes-package-ri-") as tmp:
            prefix = os.path.join(tmp, "prefix")
            run(["cmake", "--install", BUILD, "--prefix", prefix])
            self.assertTrue(os.path.isfile(os.path.join(prefix, "include", "ri.h")))
            plugin = os.path.join(tmp, "menger.so")
            run(["cc", "-shared", "-fPIC", "-Wall", "-Wextra", "-Werror", "-I" + os.path.join(prefix, "include"),
                 os.path.join(SOURCE, "examples", "plugins", "menger.c"), "-o", plugin])
            builds = {}
            for name in ("ri_scene", "render_rib"):
                src = os.path.join(tmp, name)
                shutil.copytree(os.path.join(SOURCE, "examples", name), src)
                builds[name] = os.path.join(tmp, "build-" + name)
                run(["cmake", "-S", src, "-B", builds[name], "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                     "-DCMAKE_PREFIX_PATH=" + prefix])
                run(["cmake", "--build", builds[name]])
            ri_scene = os.path.join(builds["ri_scene"], "ri_scene")

            # Written as RIB, then rendered: the square (a quarter of 64 x 64) and a level-1 sponge
            # face on, 8/9 of 9 x 9 pixels.
            rib = os.path.join(tmp, "scene.rib")
            run([ri_scene, rib, plugin])
            with open(rib) as f:
                text = f.read()
            self.assertIn('Procedural "DynamicLoad" [ "' + plugin + '"', text)
            r = run([os.path.join(builds["render_rib"], "render_rib"), rib, os.path.join(tmp, "viarib.####.exr")])
            m = re.search(r"frame 0: 64x64 mean alpha ([0-9.]+)", r.stdout)
            self.assertIsNotNone(m, r.stdout)
            self.assertAlmostEqual(float(m.group(1)), (32 * 32 + 72) / 4096, places=6)

            # Rendered by RiEnd itself: the same pixels.
            direct = os.path.join(tmp, "direct.exr")
            r = run([ri_scene, direct, plugin])
            self.assertNotIn("error", r.stderr)
            self.assertTrue(os.path.isfile(direct))
            run([os.path.join(prefix, "bin", "streyes"), "compare", os.path.join(tmp, "viarib.0000.exr"), direct,
                 "--fail", "0"])


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
