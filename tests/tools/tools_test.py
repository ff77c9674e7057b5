#!/usr/bin/env python3
"""Tests of the report tools (tools/speed-vs-error, tools/bench): the logic that turns
measurements into answers, on synthetic data; which knobs the help text switches on; argument
handling; and one tiny end-to-end run of each on scenes/ramp.rib. Full benchmark runs are not
tests (performance lives in tools/).

Run by ctest with STREYES_EXE set to the built executable."""
import importlib.machinery
import importlib.util
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TOOLS = os.path.join(ROOT, "tools")
EXE = os.environ.get("STREYES_EXE", os.path.join(ROOT, "build", "streyes"))
sys.path.insert(0, TOOLS)
import streyes_runs as sr  # noqa: E402


def load_script(name):
    loader = importlib.machinery.SourceFileLoader(name.replace("-", "_"), os.path.join(TOOLS, name))
    spec = importlib.util.spec_from_loader(loader.name, loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


sve = load_script("speed-vs-error")
bc = load_script("block-curve")
bench = load_script("bench")

TODAY_HELP = """render options:
  --frames A-B        frames to render
  --samples N         samples per pixel per frame
  --algorithm NAME    spacetime (default: Algorithm S, split once per block of frames)
                      frames    (Algorithm C: Catmull's split loop frame by frame)
  -o PATTERN          output files
"""
OCCLUSION_HELP = """render options:
  --res WxH           image size
  --samples N         samples per pixel per frame
  --algorithm NAME    spacetime-occlusion (default: Algorithm S with occlusion culling)
                      spacetime, frames, frames-occlusion
  --tolerance EPS     occlusion culling tolerance (default 0)
  --layers N          depth layers
"""


def point(knob, setting, value, seconds, rmse, **extra):
    p = {"knob": knob, "setting": setting, "value": value, "seconds": seconds, "time": seconds,
         "all_seconds": [seconds],
         "peak_memory_bytes": 2**20, "counters": {}, "error": {"rmse_rgb": rmse, "rmse_a": rmse, "psnr": 30.0,
                                                               "share_over_threshold": 0.1, "nonfinite": 0,
                                                               "threshold": 0.01}}
    p.update(extra)
    return p


def dataset(tolerance_points, samples_points, knobs=("samples", "tolerance")):
    """A sweep result: base 16 spp at 10 s and RMSE 0.010, spacetime-occlusion."""
    base = point("base", "base", None, 10.0, 0.010)
    pts = [base] + [point("samples", "%d spp" % n, n, t, e) for n, t, e in samples_points] + \
        [point("tolerance", "ε=%g" % v, v, t, e) for v, t, e in tolerance_points]
    return sve.use_time({"scene": "scenes/x.rib", "base": {"samples": 16, "width": 64, "height": 32,
                                                          "algorithm": "spacetime-occlusion"},
                         "knobs": list(knobs), "points": pts}, "wall")


class Capabilities(unittest.TestCase):
    def test_todays_help_offers_no_occlusion_knobs(self):
        c = sr.Capabilities(TODAY_HELP)
        self.assertEqual(c.algorithms, ["spacetime", "frames"])
        self.assertTrue(c.has("--samples"))
        self.assertFalse(c.has("--tolerance"))
        self.assertEqual([k.name for k in sve.active_knobs(c)], ["samples"])  # no --res in this help

    def test_occlusion_knobs_and_algorithms_join_when_listed(self):
        c = sr.Capabilities(OCCLUSION_HELP)
        self.assertEqual(c.algorithms, ["spacetime", "frames", "spacetime-occlusion", "frames-occlusion"])
        self.assertEqual([k.name for k in sve.active_knobs(c)], ["samples", "resolution", "tolerance", "layers"])
        self.assertEqual(sve.base_algorithm(c), "spacetime-occlusion")
        base = {"samples": 16, "width": 640, "height": 360, "algorithm": "spacetime-occlusion"}
        plan = sve.plan_points(c, base)
        settings = [(k, label) for k, _, label, _, _ in plan]
        self.assertIn(("tolerance", "ε=0.05"), settings)
        self.assertIn(("layers", "layers=4"), settings)
        self.assertIn(("resolution", "160x90"), settings)
        self.assertIn(("algorithm", "frames-occlusion"), settings)
        self.assertNotIn(("algorithm", "spacetime-occlusion"), settings)  # the base itself
        self.assertNotIn(("samples", "16 spp"), settings)
        resize = {label: r for k, _, label, _, r in plan}
        self.assertTrue(resize["320x180"])
        self.assertFalse(resize["4 spp"])
        only = sve.plan_points(c, base, ["tolerance"])
        self.assertEqual({k for k, *_ in only}, {"tolerance"})


class TimeAtError(unittest.TestCase):
    def test_interpolates_in_log_log_and_bounds(self):
        # A knob on the line error = 0.1 / time: at error 0.02 the time is 5 s.
        pts = [point("k", "a", 1, 1.0, 0.1), point("k", "b", 2, 10.0, 0.01), point("k", "c", 3, 3.0, 0.2)]
        t, how = sve.time_at_error(pts, 0.02)
        self.assertEqual(how, "interpolated")
        self.assertAlmostEqual(t, 5.0, places=9)
        self.assertEqual(sve.time_at_error(pts, 0.5), (1.0, "at most"))  # the 3 s point is dominated
        self.assertEqual(sve.time_at_error(pts, 0.01), (10.0, "measured"))
        self.assertIsNone(sve.time_at_error(pts, 0.005))


class Answers(unittest.TestCase):
    def test_tolerance_wins_when_it_is_faster_at_equal_error(self):
        # Samples: 4 spp at 3 s and RMSE 0.02; tolerance 0.05 reaches RMSE 0.011 in 6 s, where samples
        # (interpolated between 16 spp and 4 spp) needs about 8.6 s.
        d = dataset([(0.05, 6.0, 0.011)], [(4, 3.0, 0.02)])
        text = sve.answer_tolerance(d)
        self.assertIn("**Yes**", text)
        self.assertIn("at 1 of the 1 tolerances", text)

    def test_tolerance_loses_when_samples_are_faster(self):
        d = dataset([(0.05, 9.5, 0.03)], [(4, 3.0, 0.02)])
        text = sve.answer_tolerance(d)
        self.assertIn("**No**", text)
        self.assertIn("| ε=0.05 | 9.5 s | 0.03 | ≤ 3 s | samples |", text)

    def test_times_within_two_percent_tie(self):
        # Tolerance 0.01 leaves the image as it is (the base error) and takes 10.1 s against the base's 10 s.
        d = dataset([(0.01, 10.1, 0.010)], [(4, 3.0, 0.02)])
        text = sve.answer_tolerance(d)
        self.assertIn("**No**", text)
        self.assertIn("tied (times within 2%) at 1", text)
        self.assertIn("| tie: tolerance, samples |", text)

    def test_the_chosen_time_measure_decides(self):
        # In wall time the tolerance loses (9.5 s against samples' 3 s); in CPU time it wins (1 s against 6 s).
        d = dataset([(0.05, 9.5, 0.03)], [(4, 3.0, 0.02)])
        for p, cpu in zip(d["points"], [12.0, 6.0, 1.0]):
            p["cpu_seconds"] = cpu
        self.assertIn("**No**", sve.answer_tolerance(sve.use_time(d, "wall")))
        self.assertIn("**Yes**", sve.answer_tolerance(sve.use_time(d, "cpu")))

    def test_without_tolerance_it_says_so(self):
        d = dataset([], [(4, 3.0, 0.02)], knobs=("samples",))
        text = sve.answer_tolerance(d)
        self.assertIn("Not measured yet", text)
        self.assertNotIn("**Yes**", text)

    def test_algorithms_are_placed_from_their_numbers(self):
        d = dataset([], [(4, 3.0, 0.02)], knobs=("samples",))
        d["points"].append(point("algorithm", "frames", "frames", 20.0, 0.010,
                                 vs_base={"share_differing": 0, "rmse_rgb": 0}))
        sve.use_time(d, "wall")
        text = sve.answer_algorithms(d)
        self.assertIn("**frames**: 20 s (2.00× the base algorithm's wall time)", text)
        self.assertIn("bit-identical to spacetime-occlusion's", text)
        self.assertIn("behind", text.split("**frames**")[1])
        self.assertIn("on the front", text.split("**spacetime-occlusion**")[1].split("\n")[0])


class BlockCurve(unittest.TestCase):
    def test_blocks_sample_the_same_parts_of_the_shot(self):
        self.assertEqual(bc.sampled_blocks((1, 64), 64, 4), [(1, 64)])
        self.assertEqual(bc.sampled_blocks((1, 64), 16, 4), [(1, 16), (17, 32), (33, 48), (49, 64)])
        self.assertEqual(bc.sampled_blocks((1, 64), 4, 4), [(1, 4), (17, 20), (33, 36), (49, 52)])
        self.assertEqual(bc.sampled_blocks((1, 64), 1, 4), [(1, 1), (17, 17), (33, 33), (49, 49)])
        self.assertEqual(bc.sampled_blocks((1, 10), 4, 4), [(1, 4), (5, 8), (9, 10)])  # every block: few enough
        self.assertEqual(bc.sampled_blocks((5, 8), 16, 4), [(5, 8)])  # no longer than the span

    def test_fit_recovers_the_model(self):
        pts = [{"block": L, "cpu_per_frame": 1.5 + 6.0 / L} for L in (1, 4, 16, 64)]
        a, b = bc.fit(pts)
        self.assertAlmostEqual(a, 1.5, places=9)
        self.assertAlmostEqual(b, 6.0, places=9)
        self.assertIsNone(bc.fit(pts[:1]))


class BenchReport(unittest.TestCase):
    def kernels(self, simd, rate):
        return {"context": {"num_cpus": 2, "mhz_per_cpu": 2600, "simd": simd},
                "benchmarks": [{"name": "BM_QuadTestKernel", "run_type": "iteration", "real_time": 40.0,
                                "time_unit": "us", "sample_tests/s": rate}]}

    def test_names_the_instruction_set_and_adds_the_avx2_table(self):
        md = bench.report({"machine": sr.machine_info(), "scenes": [], "kernels": self.kernels("AVX3", 190e6),
                           "kernels_avx2": self.kernels("AVX2", 163e6)})
        self.assertIn("the sample kernels ran on AVX-512 (Highway's AVX3)", md)
        self.assertIn("### The sampling kernels on AVX2", md)
        avx2 = md[md.index("### The sampling kernels on AVX2"):]
        self.assertIn("the sample kernels ran on AVX2", avx2)
        self.assertIn("163 M", avx2)
        self.assertIn("190 M", md[:md.index("### The sampling kernels on AVX2")])
        # A machine whose best is AVX2 has one table.
        md = bench.report({"machine": sr.machine_info(), "scenes": [], "kernels": self.kernels("AVX2", 163e6)})
        self.assertNotIn("### The sampling kernels on AVX2", md)


def run(args, cwd=None):
    return subprocess.run([sys.executable] + args, capture_output=True, text=True, cwd=cwd)


# A multi-pass file as exporters write a shadow-mapped light: per frame a depth frame from the
# light (32x32, 1 sample), MakeShadow, the picture (32x18, 4 samples); a ball moving in front of
# a wall, its shadow on the wall.
MULTIPASS_FRAME = """FrameBegin {n}
Display "key.z" "zfile" "z"
Format 32 32 1
PixelSamples 1 1
PixelFilter "box" 1 1
Projection "orthographic"
ScreenWindow -3 3 -3 3
Clipping 1 20
Translate 0 0 10
WorldBegin
Translate {x} 0 0
Sphere 0.7 -0.7 0.7 360
WorldEnd
FrameEnd
MakeShadow "key.z" "key.shd"
FrameBegin {n}
Display "pic.####.exr" "openexr" "rgba"
Format 32 18 1
PixelSamples 2 2
Projection "perspective" "fov" [60]
Translate 0 0 5
WorldBegin
LightSource "shadowdistant" 1 "from" [0 0 -10] "to" [0 0 0] "shadowname" ["key.shd"]
Surface "matte"
AttributeBegin
Translate {x} 0 0
Sphere 0.7 -0.7 0.7 360
AttributeEnd
Patch "bilinear" "P" [-4 3 2  4 3 2  -4 -3 2  4 -3 2]
WorldEnd
FrameEnd
"""


class CommandLines(unittest.TestCase):
    def test_usage_errors_exit_2(self):
        for tool, args, message in [
            ("speed-vs-error", [], "give scene files or --all"),
            ("speed-vs-error", ["--all", "scenes/demo.rib"], "give scene files or --all"),
            ("speed-vs-error", ["x.rib", "--knobs", "colour"], "unknown knob colour"),
            ("speed-vs-error", ["x.rib", "--frames", "1-x"], "--frames expects"),
            ("speed-vs-error", ["/no/such/scene.rib", "--exe", EXE], "'/no/such/scene.rib' does not exist"),
            ("bench", ["--no-kernels", "--no-renders"], "leave nothing to do"),
            ("bench", ["/no/such/scene.rib", "--no-kernels", "--exe", EXE], "does not exist"),
            ("bench", ["--bogus"], "unrecognized arguments"),
            ("block-curve", ["--blocks", "1,x"], "--blocks expects"),
            ("block-curve", ["--blocks", "1,128"], "block 128 is longer than the span 1-64"),
            ("block-curve", ["--span", "9-2"], "the last frame comes before the first"),
            ("block-curve", ["--scenes", "/no/such.rib", "--exe", EXE], "'/no/such.rib' does not exist"),
            ("block-curve", ["--replot", "--out", "/no/such/curve.json"], "nothing to replot"),
        ]:
            r = run([os.path.join(TOOLS, tool)] + args)
            self.assertEqual(r.returncode, 2, (tool, args, r.stderr))
            self.assertIn(message, r.stderr, (tool, args))

    def test_help(self):
        for tool in ("speed-vs-error", "bench", "block-curve"):
            r = run([os.path.join(TOOLS, tool), "--help"])
            self.assertEqual(r.returncode, 0)
            self.assertIn("usage: tools/" + tool, r.stdout)


class EndToEnd(unittest.TestCase):
    def setUp(self):
        # Not skipped when something is missing: a skip reads as a pass in ctest, and the suite's
        # set-up (tools/setup.sh) installs gnuplot, so its absence is a broken set-up to report.
        if not shutil.which("gnuplot"):
            self.fail("gnuplot is not on PATH: the report tools plot through it, so these end-to-end checks cannot "
                      "run (apt-get install gnuplot-nox; tools/setup.sh installs it)")
        if not os.access(EXE, os.X_OK):
            self.fail("no streyes executable at '%s': build it, or set STREYES_EXE" % EXE)
        self.dir = tempfile.mkdtemp(prefix="streyes-tools-")

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def test_speed_vs_error_on_the_ramp(self):
        r = run([os.path.join(TOOLS, "speed-vs-error"), os.path.join(ROOT, "scenes/ramp.rib"), "--knobs",
                 "samples", "--runs", "1", "--ref-samples", "1024", "--exe", EXE, "--out", self.dir, "--work",
                 os.path.join(self.dir, "work"), "--quiet"])
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(self.dir, "ramp.json")) as f:
            data = json.load(f)
        err = {p["setting"]: p["error"]["rmse_rgb"] for p in data["points"]}
        self.assertEqual(set(err), {"base", "1 spp", "2 spp", "4 spp", "9 spp"})
        # The ramp's noise falls as samples rise: 1 spp is far from the 1024-spp reference, 256 close.
        self.assertGreater(err["1 spp"], 4 * err["9 spp"])
        self.assertGreater(err["9 spp"], err["base"])
        self.assertGreater(err["base"], 0)
        with open(os.path.join(self.dir, "ramp.md")) as f:
            md = f.read()
        self.assertIn("![time against error](ramp.png)", md)
        self.assertIn("| samples | 1 spp |", md)
        self.assertIn("Not swept here (`--knobs`): resolution", md)  # the knobs --knobs left out are said
        self.assertNotIn("| resolution |", md)
        with open(os.path.join(self.dir, "ramp.png"), "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        self.assertIn("![frames of the base render](ramp-sheet.png)", md)
        self.assertTrue(os.path.exists(os.path.join(self.dir, "ramp-sheet.png")))
        self.assertFalse(os.path.exists(os.path.join(self.dir, "work", "ramp", "run01")))  # frames cleaned up
        # --replot rewrites the page from the measurements alone.
        os.remove(os.path.join(self.dir, "ramp.md"))
        r = run([os.path.join(TOOLS, "speed-vs-error"), "--replot", os.path.join(ROOT, "scenes/ramp.rib"), "--out",
                 self.dir, "--quiet"])
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(self.dir, "ramp.md")) as f:
            self.assertEqual(f.read(), md)

    def test_speed_vs_error_on_a_multi_pass_file(self):
        # --frames picks pictures and brings the depth frames they read; the base setting is the
        # pictures' (32x18, 4 samples), not the depth frames'; the maps land in each render's
        # folder, not in the folder the tool runs from.
        scene = os.path.join(self.dir, "maps.rib")
        with open(scene, "w") as f:
            f.write("".join(MULTIPASS_FRAME.format(n=n, x=0.5 * (n - 2)) for n in (1, 2, 3)))
        caller = os.path.join(self.dir, "caller")
        os.makedirs(caller)
        r = run([os.path.join(TOOLS, "speed-vs-error"), scene, "--frames", "2-3", "--knobs", "samples", "--runs", "1",
                 "--ref-samples", "64", "--exe", EXE, "--out", self.dir, "--work", os.path.join(self.dir, "work"),
                 "--quiet"], cwd=caller)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(os.listdir(caller), [])
        ref = os.path.join(self.dir, "work", "maps", "reference")
        self.assertEqual(sr.picture_files(ref), ["f.0002.exr", "f.0003.exr"])
        self.assertTrue(os.path.exists(os.path.join(ref, "key.shd")))
        with open(os.path.join(self.dir, "maps.json")) as f:
            data = json.load(f)
        self.assertEqual(data["frames"], [2, 3])
        self.assertEqual((data["base"]["width"], data["base"]["height"], data["base"]["samples"]), (32, 18, 4))
        err = {p["setting"]: p["error"] for p in data["points"]}
        self.assertEqual(set(err), {"base", "1 spp", "2 spp"})
        self.assertGreater(err["1 spp"]["rmse_rgb"], err["base"]["rmse_rgb"])
        self.assertGreater(err["base"]["rmse_rgb"], 0)
        self.assertEqual(err["base"]["pixels_skipped"], 0)

    def test_block_curve_on_the_ramp(self):
        out = os.path.join(self.dir, "curve.json")
        r = run([os.path.join(TOOLS, "block-curve"), "--quick", "--scenes", os.path.join(ROOT, "scenes/ramp.rib"),
                 "--exe", EXE, "--out", out, "--work", os.path.join(self.dir, "work"), "--quiet"])
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out) as f:
            data = json.load(f)
        pts = data["curves"]["ramp"]["points"]
        self.assertEqual([p["block"] for p in pts], [1, 4])
        self.assertEqual([p["frames_rendered"] for p in pts], [4, 8])  # 1, 3, 5, 7; then 1-4 and 5-8
        for p in pts:
            self.assertGreater(p["cpu_seconds"], 0)
            self.assertAlmostEqual(p["cpu_per_frame"], p["cpu_seconds"] / p["frames_rendered"], places=3)
        with open(out[:-5] + ".md") as f:
            self.assertIn("## ramp (scenes/ramp.rib, 64×36, frames 1-8)", f.read())
        self.assertFalse(os.path.exists(os.path.join(self.dir, "work")))

    def test_bench_on_the_ramp(self):
        out = os.path.join(self.dir, "bench.md")
        r = run([os.path.join(TOOLS, "bench"), os.path.join(ROOT, "scenes/ramp.rib"), "--no-kernels", "--exe", EXE,
                 "--out", out, "--work", os.path.join(self.dir, "work"), "--quiet"])
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out[:-3] + ".json") as f:
            data = json.load(f)
        rows = {a["algorithm"]: a for a in data["scenes"][0]["algorithms"]}
        self.assertEqual(data["scenes"][0]["baseline"], "frames")
        self.assertIn("spacetime", rows)
        # Both algorithms dice the same still patch: the counters agree, and so do the pixels.
        self.assertEqual(rows["spacetime"]["counters"]["micropolygons"], rows["frames"]["counters"]["micropolygons"])
        self.assertIn("vs_baseline", rows["spacetime"])
        with open(out) as f:
            self.assertIn("### scenes/ramp.rib", f.read())


class AqsisComparePlugins(unittest.TestCase):
    """tools/aqsis-compare builds a scene's DynamicLoad plug-in from its source beside the scene, for
    streyes against this checkout's include/ri.h, for Aqsis against the prefix given with --aqsis."""
    PLUGIN = """#include <ri.h>
AQSIS_EXPORT RtPointer ConvertParameters(RtString p) { (void)p; return 0; }
AQSIS_EXPORT RtVoid Subdivide(RtPointer d, RtFloat detail) { (void)d; (void)detail; RiSphere(1, -1, 1, 360, RI_NULL); }
AQSIS_EXPORT RtVoid Free(RtPointer d) { (void)d; }
"""
    SCENE = """Format 32 32 1
Display "out.exr" "openexr" "rgba"
Projection "orthographic"
ScreenWindow -2 2 -2 2
WorldBegin
Translate 0 0 5
Procedural "DynamicLoad" ["ball" ""] [-1 1 -1 1 -1 1]
WorldEnd
"""

    def setUp(self):
        if not os.access(EXE, os.X_OK):
            self.fail("no streyes executable at '%s': build it, or set STREYES_EXE" % EXE)
        self.dir = tempfile.mkdtemp(prefix="streyes-tools-")
        for name, text in (("ball.c", self.PLUGIN), ("scene.rib", self.SCENE)):
            with open(os.path.join(self.dir, name), "w") as f:
                f.write(text)
        self.tool = load_script("aqsis-compare")

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def test_streyes_renders_the_plugin_built_against_its_ri_h(self):
        self.tool.build_plugins("streyes", self.dir, "scene.rib", "/unused")
        self.assertTrue(os.path.exists(os.path.join(self.dir, "ball.so")))
        r = subprocess.run([EXE, "render", "scene.rib", "--stats", "stats.json"], cwd=self.dir, capture_output=True,
                           text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("warning", r.stderr)
        with open(os.path.join(self.dir, "stats.json")) as f:
            counters = json.load(f)["counters"]
        # The plug-in was loaded and expanded, and its sphere (the only geometry) was diced.
        self.assertEqual(counters["procedurals_expanded"], 1)
        self.assertGreater(counters["micropolygons"], 100)

    def test_aqsis_builds_against_the_prefix_given(self):
        calls = []

        class Done:
            returncode = 0
            stdout = b""
        real = self.tool.subprocess.run
        self.tool.subprocess.run = lambda cmd, **kw: calls.append(cmd) or Done()
        try:
            self.tool.build_plugins("aqsis", self.dir, "scene.rib", "/opt/aqsis-x")
        finally:
            self.tool.subprocess.run = real
        self.assertEqual(len(calls), 1)
        cmd = " ".join(calls[0])
        for part in ("ball.c -o ball.so", "-I /opt/aqsis-x/include/aqsis/ri", "-L /opt/aqsis-x/lib", "-laqsis_core"):
            self.assertIn(part, cmd)
        self.assertNotIn(os.path.join(ROOT, "include"), cmd)


class AqsisComparePictures(unittest.TestCase):
    """Scenes of one folder that write pictures of one name (Aqsis's cornell box passes all write
    cornellbox.tif) each keep their own: a later scene's render must not replace an earlier one's."""

    def test_each_scene_keeps_its_own_picture(self):
        tool = load_script("aqsis-compare")
        work = tempfile.mkdtemp(prefix="streyes-tools-")
        try:
            folder = os.path.join(work, "scenes")
            os.makedirs(folder)
            kept = {}
            for scene in ("bake_pass", "beauty_pass"):
                with open(os.path.join(folder, "cornellbox.exr"), "w") as f:
                    f.write(scene)  # what this scene's render wrote
                kept[scene] = os.path.join(work, "done", scene)
                self.assertTrue(tool.keep_pictures(folder, ["cornellbox.exr", "absent.exr"], kept[scene]))
            for scene, dest in kept.items():
                with open(os.path.join(dest, "cornellbox.exr")) as f:
                    self.assertEqual(f.read(), scene)
                self.assertFalse(os.path.exists(os.path.join(dest, "absent.exr")))
        finally:
            shutil.rmtree(work, ignore_errors=True)


class ShadowBenchProvenanceTest(unittest.TestCase):
    """tools/shadow-bench's table says when and at which commit it was measured."""

    def test_provenance_names_the_day_and_the_commit(self):
        tool = load_script("shadow-bench")
        day, commit = tool.provenance()
        self.assertRegex(day, r"^\d{4}-\d{2}-\d{2}$")
        self.assertRegex(commit, r"^([0-9a-f]{7,}( with local changes)?|unknown)$")


if __name__ == "__main__":
    unittest.main()
