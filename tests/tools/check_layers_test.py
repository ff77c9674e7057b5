#!/usr/bin/env python3
"""tools/check-layers: the source tree passes, and the checker catches each kind of break."""
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
TOOL = os.path.join(ROOT, "tools", "check-layers")


def run(root=None):
    args = [sys.executable, TOOL] + ([root] if root else [])
    return subprocess.run(args, capture_output=True, text=True)


def tree(files):
    """A temporary tree: {relative path: text}."""
    d = tempfile.TemporaryDirectory()
    for rel, text in files.items():
        path = os.path.join(d.name, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(text)
    return d


class CheckLayers(unittest.TestCase):
    def test_the_source_tree_has_no_include_pointing_up(self):
        r = run()
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)

    def test_an_include_of_a_later_stage_fails_naming_file_and_line(self):
        with tree({"src/geom/body.h": "", "src/shade/shading.h": "",
                   "src/geom/curved.cpp": '#include "geom/body.h"\n#include "shade/shading.h"\n'}) as d:
            r = run(d)
            self.assertEqual(r.returncode, 1)
            self.assertIn("src/geom/curved.cpp:2: geom includes shade/shading.h from shade", r.stdout)

    def test_includes_down_and_within_a_stage_pass(self):
        with tree({"src/util/sampling.h": "", "src/geom/body.h": '#include "util/sampling.h"\n',
                   "src/render/bucket.h": "", "src/render/bucket.cpp": '#include "bucket.h"\n#include "geom/body.h"\n',
                   "src/render/bucket_test.cpp": '#include "cli/whatever.h"\n'}) as d:
            r = run(d)
            self.assertEqual(r.returncode, 0, r.stdout)

    def test_a_public_header_including_an_internal_one_fails(self):
        with tree({"src/geom/camera.h": "", "include/streyes/scene.h": '#include "geom/camera.h"\n'}) as d:
            r = run(d)
            self.assertEqual(r.returncode, 1)
            self.assertIn("include/streyes/scene.h:1: public header includes geom/camera.h", r.stdout)

    def test_a_folder_outside_the_layers_fails(self):
        with tree({"src/misc/thing.cpp": ""}) as d:
            r = run(d)
            self.assertEqual(r.returncode, 1)
            self.assertIn("not in a known layer (misc)", r.stdout)


if __name__ == "__main__":
    unittest.main()
