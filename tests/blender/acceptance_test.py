"""Issue 49's acceptance: the Python-built scene (acceptance_scene.py), 8 frames with motion blur,
rendered by streyes through the add-on and by Cycles (direct light only, film transparent):

- coverage: on every frame, alpha differs by at most 0.02 on average and by at most 0.1 on at
  least 99% of the pixels;
- colour: on every frame, RGB within RMSE 0.03 at a quarter of the size (4 x 4 means);
- the animation runs streyes once (one command, frames 1-8), the cube reaches it as a
  SubdivisionMesh (its creases with it), the bar's deformation as motion keys;
- the still floor alone (the same scene without the cube and bar): frames 1-4, where the camera
  stands, are split, diced and shaded as often as frame 1 alone; with a camera that never moves,
  all 8 frames are.

Figures go to --report (JSON) for docs/results/blender.md.
"""

import json
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np  # noqa: E402

import acceptance_scene  # noqa: E402
import blender_test_util as util  # noqa: E402

SAMPLES = 64


def streyes_stats(a, rib_pattern, frames, name):
    out = os.path.join(a.work, "stats-" + name)
    os.makedirs(out, exist_ok=True)
    stats = os.path.join(out, "stats.json")
    subprocess.run([a.streyes, "render", rib_pattern, "--frames", "%d-%d" % frames, "-o",
                    os.path.join(out, "f.####.exr"), "--stats", stats, "--quiet"], check=True)
    with open(stats) as f:
        c = json.load(f)["counters"]
    return {"root_bodies": c["root_bodies"], "splits": c["splits"]["total"], "grids_diced": c["grids_diced"],
            "micropolygons": c["micropolygons"],
            "points_shaded": c["shading"]["points_builtin"] + c["shading"]["points_surface"]}


def floor_only(a, pan, failures, report):
    """The floor, the lights and the camera: how often the floor is split, diced and shaded."""
    scene = acceptance_scene.build(pan=pan, others=False)
    scene.streyes.keep_files = True
    name = "pan" if pan else "still"
    scene.streyes.export_folder = os.path.join(a.work, "floor-" + name) + "/"
    util.render(scene, "STREYES", os.path.join(a.work, "floor-" + name + "-frames"), samples=4)
    ribs = os.path.join(a.work, "floor-" + name, "Scene", "shot.####.rib")
    one = streyes_stats(a, ribs, (1, 1), name + "-1")
    four = streyes_stats(a, ribs, (1, 4), name + "-1-4")
    eight = streyes_stats(a, ribs, (1, 8), name + "-1-8")
    report["floor_" + name] = {"frame 1": one, "frames 1-4": four, "frames 1-8": eight}
    print("floor (%s camera): frame 1 %s, frames 1-4 %s, frames 1-8 %s" % (name, one, four, eight))
    failures.check(one["grids_diced"] > 0 and one["points_shaded"] > 0, "the floor is diced and shaded")
    failures.check(four == one, "floor, %s camera: frames 1-4 split, diced and shaded as often as frame 1 alone" % name)
    if not pan:
        failures.check(eight == one, "floor, still camera: frames 1-8 split, diced and shaded as often as frame 1")
    else:
        # The camera turns in frames 5-8: in camera space the floor moves, a body a frame there.
        failures.check(eight["grids_diced"] > one["grids_diced"], "floor, panning camera: frames 5-8 diced again")


def main():
    a = util.args()
    util.register_addon(a.source)
    failures = util.Failures()
    report = {"samples": SAMPLES}

    scene = acceptance_scene.build()
    scene.streyes.keep_files = True
    scene.streyes.export_folder = os.path.join(a.work, "export") + "/"
    ours = util.render(scene, "STREYES", os.path.join(a.work, "streyes"), samples=SAMPLES)
    theirs = util.render(scene, "CYCLES", os.path.join(a.work, "cycles"), samples=SAMPLES)

    folder = os.path.join(a.work, "export", "Scene")
    with open(os.path.join(folder, "streyes.log")) as f:
        log = f.read()
    runs = [l for l in log.splitlines() if l.startswith("$ ")]
    failures.check(len(runs) == 1 and " --frames 1-8 " in runs[0], "one streyes run renders frames 1-8: %s" % runs)
    ribs = [os.path.join(folder, "shot.%04d.rib" % f) for f in range(1, 9)]
    failures.check(all(os.path.exists(p) for p in ribs), "a RIB file a frame")
    text = open(ribs[4]).read()
    cube = text[text.index('"name" ["Cube"]'):text.index('"name" ["Bar"]')]
    failures.check("SubdivisionMesh" in cube and "PointsPolygons" not in cube,
                   "the subdivided cube is a SubdivisionMesh")
    failures.check(len(re.findall(r'"crease"', cube)) == 4, "its four creased edges are crease tags")
    bar = text[text.index('"name" ["Bar"]'):]
    failures.check(bar.count("PointsPolygons") == 3 and "MotionBegin [4.75 5 5.25]" in bar,
                   "the bar's deformation: three keys over the shutter")

    per_frame = []
    for f in range(1, 9):
        s = util.read_exr(util.frame_file(ours, f))
        c = util.read_exr(util.frame_file(theirs, f))
        util.check_finite("streyes frame %d" % f, s)
        util.check_finite("Cycles frame %d" % f, c)
        failures.check(s.shape == c.shape, "frame %d: the same size (%s, %s)" % (f, s.shape, c.shape))
        da = np.abs(s[..., 3] - c[..., 3])
        mean_a = float(da.mean())
        within = float((da <= 0.1).mean())
        rmse = float(np.sqrt(np.mean((util.quarter(s[..., :3]) - util.quarter(c[..., :3])) ** 2)))
        rmse_full = float(np.sqrt(np.mean((s[..., :3] - c[..., :3]) ** 2)))
        covered = float((c[..., 3] > 0.5).mean())
        per_frame.append({"frame": f, "alpha_mean_diff": mean_a, "alpha_within_0.1": within,
                          "rgb_rmse_quarter": rmse, "rgb_rmse_full": rmse_full, "covered": covered,
                          "mean_rgb_cycles": float(c[..., :3].mean()), "mean_rgb_streyes": float(s[..., :3].mean())})
        failures.check(covered > 0.3, "frame %d: the scene covers the frame (%.2f)" % (f, covered))
        failures.check(mean_a <= 0.02, "frame %d: alpha mean difference %.4f <= 0.02" % (f, mean_a))
        failures.check(within >= 0.99, "frame %d: alpha within 0.1 on %.2f%% >= 99%%" % (f, 100 * within))
        failures.check(rmse <= 0.03, "frame %d: RGB RMSE at a quarter size %.4f <= 0.03" % (f, rmse))
    report["frames"] = per_frame

    floor_only(a, False, failures, report)
    floor_only(a, True, failures, report)
    if a.report:
        with open(a.report, "w") as f:
            json.dump(report, f, indent=1)
    failures.finish()


main()
