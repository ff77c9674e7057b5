#!/usr/bin/env python3
"""Regenerates docs/results/raytrace.md: the ray tracer's statistics like Tables 1 and 2 of
Glassner's "Spacetime ray tracing for animation" (1988), spacetime hierarchy against one
hierarchy per frame, for scenes/atom.rib and scenes/grove.rib; and the error of the ray tracer
against the rasterizer (the same samples) on scenes/demo.rib and scenes/atom.rib.

    tools/raytrace_report.py [--threads N] [--out DIR] [--skip-demo]

Needs build/streyes and build/streyes_bench (tools/test.sh builds them) and python3-openimageio.
Both columns of a table come from this one run; the prose under the tables is
written here, with the run's ratios filled in. Renders go to out/raytrace/ (several GB of
EXR frames are not kept: each comparison deletes its frames when done)."""
import argparse
import datetime
import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
EXE = os.path.join(ROOT, "build", "streyes")
BENCH = os.path.join(ROOT, "build", "streyes_bench")


def render(scene, algorithm, outdir, threads, tag):
    """Renders a scene; returns (stats, frame pattern)."""
    os.makedirs(outdir, exist_ok=True)
    pattern = os.path.join(outdir, "%s.####.exr" % tag)
    stats_path = os.path.join(outdir, "%s.json" % tag)
    cmd = [EXE, "render", os.path.join(ROOT, "scenes", scene), "--algorithm", algorithm, "-o", pattern,
           "--stats", stats_path, "--quiet", "--threads", str(threads)]
    print("  $ " + " ".join(os.path.relpath(c, ROOT) if c.startswith(ROOT) else c for c in cmd), flush=True)
    subprocess.run(cmd, check=True)
    with open(stats_path) as f:
        return json.load(f), pattern


def frame_paths(pattern, stats):
    first, last = stats["frames"]
    return [pattern.replace("####", "%04d" % f) for f in range(first, last + 1)]


def compare(pattern_a, pattern_b, stats, threshold=0.02):
    """RMSE of RGBA over every pixel of every frame, and the share of pixels where some RGBA
    channel differs by more than `threshold`."""
    sq, n, differ, pixels = 0.0, 0, 0, 0
    for pa, pb in zip(frame_paths(pattern_a, stats), frame_paths(pattern_b, stats)):
        a = oiio.ImageBuf(pa).get_pixels(oiio.FLOAT)[..., :4].astype(np.float64)
        b = oiio.ImageBuf(pb).get_pixels(oiio.FLOAT)[..., :4].astype(np.float64)
        if a.shape != b.shape or not (np.isfinite(a).all() and np.isfinite(b).all()):
            raise SystemExit("frames %s and %s differ in size or hold NaN/Inf" % (pa, pb))
        d = a - b
        sq += float((d * d).sum())
        n += d.size
        differ += int((np.abs(d).max(axis=-1) > threshold).sum())
        pixels += d.shape[0] * d.shape[1]
    return math.sqrt(sq / n), differ / pixels


def table(name, st, fr):
    cs, cf = st["counters"], fr["counters"]
    ts, tf = cs["trace"], cf["trace"]
    ss, sf = st["seconds"], fr["seconds"]

    def row(label, a, b, fmt="{:,}"):
        ratio = "%.3f" % (a / b) if b else "-"
        return "| %s | %s | %s | %s |" % (label, fmt.format(b), fmt.format(a), ratio)
    lines = [
        "| %s | frame-by-frame | spacetime | spacetime / frame-by-frame |" % name,
        "|---|---:|---:|---:|",
        row("bounding volumes built", ts["bounding_volumes"], tf["bounding_volumes"]),
        row("ray/body intersection tests", ts["ray_body_tests"], tf["ray_body_tests"]),
        row("ray/bounding-volume tests", ts["ray_box_tests"], tf["ray_box_tests"]),
        row("hierarchy build time (CPU s)", ss["cpu_by_stage"]["hierarchy_build"],
            sf["cpu_by_stage"]["hierarchy_build"], "{:.2f}"),
        row("tracing and shading (CPU s)", ss["cpu_by_stage"]["trace"], sf["cpu_by_stage"]["trace"], "{:.1f}"),
        row("total time (wall s)", ss["total"], sf["total"], "{:.1f}"),
        row("eye rays", ts["eye_rays"], tf["eye_rays"]),
        row("shadow rays", ts["shadow_rays"], tf["shadow_rays"]),
        row("bodies (patch segments between motion keys)", ts["bodies"], tf["bodies"]),
        row("peak memory (MiB)", st["peak_memory_bytes"] / 2**20, fr["peak_memory_bytes"] / 2**20, "{:.0f}"),
    ]
    return "\n".join(lines)


def bench_sweep():
    """The bench's atom.rib sweep over the spacetime hierarchy's time resolution."""
    if not os.path.exists(BENCH):
        return None
    out = subprocess.run([BENCH, "--benchmark_filter=BM_TraceAtom", "--benchmark_format=json"],
                         check=True, capture_output=True, text=True).stdout
    rows = ["| hierarchy | bounding volumes | build (CPU s) | body tests / ray | bounding-volume tests / ray |"
            " rays / s (one core) |", "|---|---:|---:|---:|---:|---:|"]
    for b in json.loads(out)["benchmarks"]:
        mode = int(b["name"].split(":")[-1])
        label = "frame by frame (3D)" if mode == 0 else "spacetime, time cells >= %g frame" % (1.0 / 2 ** (mode - 1))
        rows.append("| %s | {:,} | %.2f | %.3f | %.1f | %.2f M |".format(int(b["bounding_volumes"])) %
                    (label, b["build_cpu_s"], b["body_tests/ray"], b["box_tests/ray"], b["rays/s"] / 1e6))
    return "\n".join(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--threads", type=int, default=1, help="threads for the table renders (default 1)")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "raytrace"))
    ap.add_argument("--skip-demo", action="store_true", help="leave out the demo.rib comparison (the longest)")
    args = ap.parse_args()
    for exe in (EXE,):
        if not os.path.exists(exe):
            sys.exit("%s is missing: build first (tools/test.sh)" % exe)
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip() or "?"
    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")

    print("== Tables: spacetime against frame-by-frame hierarchies")
    tables, compared = {}, {}
    for scene in ("atom.rib", "grove.rib"):
        stem = scene[:-4]
        st, st_pat = render(scene, "raytrace", args.out, args.threads, stem + "-raytrace")
        fr, fr_pat = render(scene, "raytrace-frames", args.out, args.threads, stem + "-raytrace-frames")
        tables[scene] = (st, fr)
        if scene == "atom.rib":
            print("== Ray tracer against the rasterizer: atom.rib")
            ra, ra_pat = render(scene, "spacetime", args.out, os.cpu_count(), stem + "-spacetime")
            compared[scene] = (ra, st) + compare(st_pat, ra_pat, st)
            same = compare(st_pat, fr_pat, st)
            tables[scene] += (same,)
        shutil.rmtree(args.out)
    if not args.skip_demo:
        print("== Ray tracer against the rasterizer: demo.rib")
        ra, ra_pat = render("demo.rib", "spacetime", args.out, os.cpu_count(), "demo-spacetime")
        rt, rt_pat = render("demo.rib", "raytrace", args.out, os.cpu_count(), "demo-raytrace")
        compared["demo.rib"] = (ra, rt) + compare(rt_pat, ra_pat, rt)
        shutil.rmtree(args.out)
    print("== Benchmark sweep (build/streyes_bench --benchmark_filter=BM_TraceAtom)")
    sweep = bench_sweep()

    md = []
    w = md.append
    w("# Ray tracing: spacetime hierarchy against frame by frame\n")
    w("Generated by `tools/raytrace_report.py --threads %d` on %s (commit %s, %s, %d cores shared with other "
      "work: times are indicative; counts are exact and reproducible).\n" %
      (args.threads, datetime.date.today().isoformat(), commit, cpu, os.cpu_count()))
    w("Like Tables 1 and 2 of Glassner 1988: the same eye rays (the rasterizer's jittered samples, spread over "
      "each frame's exposure) and shadow rays traced through one spacetime hierarchy for the whole animation "
      "(`--algorithm raytrace`) or through a 3D hierarchy built for each frame (`--algorithm raytrace-frames`). "
      "Intersection tests count ray/body tests (each body at most once per ray); both columns of a table come "
      "from one run of the script.\n")
    for scene, label in (("atom.rib", "Table 1: scenes/atom.rib (the paper's Figure 6: 64 frames, 126x126, "
                          "32 samples per pixel, a nucleus, six electrons, a floor, shadows)"),
                         ("grove.rib", "Table 2: scenes/grove.rib (a forest-like stand-in: 256 trees of patches, "
                          "a third swaying; 64 frames, 160x120, 4 samples per pixel, shadows)")):
        st, fr = tables[scene][:2]
        w("## %s\n" % label)
        w(table(scene, st, fr) + "\n")
        if len(tables[scene]) > 2:
            rmse, share = tables[scene][2]
            w("The two hierarchies give the same images (RMSE %.2g, %.4f%% of pixels differ): both find the exact "
              "nearest hit.\n" % (rmse, 100 * share))
    w("## Ray tracer against the rasterizer\n")
    w("The same samples (positions and times), the same shaders and the same pixel filter; the ray tracer "
      "intersects the exact patches and shades each hit, the rasterizer samples micropolygons shaded at their "
      "vertices. A pixel differs when some RGBA channel differs by more than 0.02.\n")
    w("| scene | frames | RMSE of RGBA | pixels that differ | rasterizer total (s) | ray tracer total (s) |")
    w("|---|---:|---:|---:|---:|---:|")
    for scene, (ra, rt, rmse, share) in compared.items():
        w("| %s | %d | %.4f | %.2f%% | %.1f | %.1f |" % (scene, ra["frames"][1] - ra["frames"][0] + 1, rmse,
                                                     100 * share, ra["seconds"]["total"], rt["seconds"]["total"]))
    w("")
    st, fr = tables["atom.rib"][:2]
    gst, gfr = tables["grove.rib"][:2]
    ratio = lambda a, b, k: a["counters"]["trace"][k] / b["counters"]["trace"][k]
    w("## Where we land, and why\n")
    w("The paper found about 0.57 of the frame-by-frame intersections (0.565 and 0.583 in its two tables). "
      "Here the spacetime hierarchy makes %.2f (atom.rib) and %.2f (grove.rib) of the frame-by-frame ray/body "
      "tests, and builds %.2f and %.2f of the bounding volumes.\n" %
      (ratio(st, fr, "ray_body_tests"), ratio(gst, gfr, "ray_body_tests"),
       ratio(st, fr, "bounding_volumes"), ratio(gst, gfr, "bounding_volumes")))
    w("- **The baseline is stronger than the paper's.** Both columns use the same builder: cells are cut where "
      "the expected tests drop (surface-area estimate), every body is bounded by its own answer for the time it "
      "can spend in the cell, and a leaf notes when each body is in it. A frame's hierarchy therefore bounds each "
      "moving body over one exposure only, as tightly in space as the spacetime hierarchy does; what is left for "
      "spacetime to win is motion *within* an exposure, and the bounding volumes of what does not move.")
    w("- **Most tests are on still geometry.** The floor, the nucleus and the trees are bounded identically by "
      "both hierarchies; only rays near the electrons or the swaying crowns can gain. The paper's scenes were a "
      "handful of spheres, so a moving sphere's blurred bound was a large share of every frame's hierarchy.")
    w("- **Time is not cut finer than a frame by default** (`HierarchyOptions::minTimeCut`). Finer time cells do "
      "cut tests further (the sweep below), but for many more bounding volumes; at one frame the spacetime "
      "hierarchy builds fewer bounding volumes than frame by frame and still makes fewer tests.")
    w("- **Bounding volumes** are where spacetime wins clearly on mostly-still scenes (grove.rib): still geometry "
      "is bounded once for all 64 frames. On atom.rib the electrons' cells are cut down to single frames "
      "anyway, and the still floor and nucleus near them are copied into each time slice.")
    w("- **Time per ray** is higher in the spacetime hierarchy: its tree is larger (cache misses), a time-cut node "
      "has up to 16 children of which a ray tests the half for its time, and each test also checks a time "
      "interval. With tests this cheap (one bilinear patch), fewer tests do not make up for it; the paper's "
      "argument is about expensive intersections (its boiling volcano), where the ratio of tests is what counts.\n")
    if sweep:
        w("## Time resolution of the spacetime hierarchy\n")
        w("`build/streyes_bench --benchmark_filter=BM_TraceAtom`: scenes/atom.rib frames 1-16, an eye ray through "
          "every second pixel of each frame and a shadow ray from each hit. The spacetime hierarchy cuts time "
          "where the expected tests drop by a fifth, but not into cells shorter than `minTimeCut` (default one "
          "frame).\n")
        w(sweep + "\n")
    path = os.path.join(ROOT, "docs", "results", "raytrace.md")
    with open(path, "w") as f:
        f.write("\n".join(md))
    print("== Wrote " + os.path.relpath(path, ROOT))


if __name__ == "__main__":
    main()
