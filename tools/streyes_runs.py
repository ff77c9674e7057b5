"""Shared by tools/speed-vs-error and tools/bench: running streyes, reading what it reports,
and writing results. Python 3 standard library only (plots go through gnuplot).

Every figure these tools publish comes from here, measured one way:
  - wall time: the whole `streyes render` process (parse, render, write the EXRs), as a user
    waits for it;
  - peak memory and counters: the render's --stats JSON;
  - error: `streyes compare REFERENCE TEST --json`, pooled over all frames.
"""
import datetime
import json
import os
import platform
import re
import resource
import shutil
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The benchmark scenes, in report order; those not in the tree yet are skipped with a note.
BENCHMARK_SCENES = ["scenes/demo.rib", "scenes/occluded.rib", "scenes/forest.rib"]
# Settings a benchmark scene needs to keep a sweep within an hour on two cores; the command
# line's --frames and --ref-samples win. "why" is quoted in the reports; "report" names them (else
# the scene's file name); "see_also" is a line under a report's head.
SCENE_SETTINGS = {
    "scenes/forest.rib": {"frames": "1-8", "ref_samples": 36,
                          "why": "8 of its 64 frames and a 36-sample reference (9 times its 4 samples per pixel) keep "
                                 "the sweep within an hour on two cores",
                          "see_also": "The same sweep on the Weber–Penn forest with the sun's shadow maps "
                                      "(scenes/forest-wp-maps.rib, issue 51): [forest-wp.md](forest-wp.md)."},
    # A multi-pass file (per frame a depth frame from the sun, MakeShadow, the picture): --frames
    # picks pictures and brings the depth frames they read; --res and --samples change the pictures.
    "scenes/forest-wp-maps.rib": {"frames": "1-8", "ref_samples": 36, "report": "forest-wp",
                                  "why": "8 of its 64 pictures and a 36-sample reference (9 times its 4 samples "
                                         "per pixel), as for scenes/forest.rib; every run also renders the sun's "
                                         "depth frames its pictures read (2048×1076, 1 sample per pixel, not changed "
                                         "by --res or --samples, jittered by the seed), and their time counts; the "
                                         "depth maps themselves are not compared",
                                  "see_also": "The same sweep on scenes/forest.rib (100,000 of the older trees, no "
                                              "shadows): [forest.md](forest.md)."},
}


def scene_settings(path):
    return SCENE_SETTINGS.get(scene_label(path), {})


def report_stem(path):
    """The name of a scene's report files (OUT/STEM.md, .png, .json): the scene's file name, or
    its SCENE_SETTINGS "report"."""
    return scene_settings(path).get("report") or os.path.splitext(os.path.basename(path))[0]

# Every algorithm the tools know; one is used when `streyes render --help` lists it.
ALGORITHMS = ["spacetime", "frames", "spacetime-occlusion", "frames-occlusion"]


class ToolError(Exception):
    """Bad input or a failed step: printed as 'tool: error: ...', exit code 2 (bad input) or 1."""

    def __init__(self, message, code=2):
        super().__init__(message)
        self.code = code


def run_main(name, main):
    """Runs main(), turning ToolError into a message and an exit code."""
    try:
        sys.exit(main())
    except ToolError as e:
        print("%s: error: %s" % (name, e), file=sys.stderr)
        sys.exit(e.code)
    except KeyboardInterrupt:
        sys.exit(130)


class Capabilities:
    """What this streyes binary offers, read from `streyes render --help`."""

    def __init__(self, help_text):
        self.help_text = help_text
        # "  --res WxH ..." and "  -q,--quiet ...": the long names.
        self.options = set(re.findall(r"(?m)^\s+(?:-[a-zA-Z],)?(--[a-z][a-z0-9-]*)", help_text))
        self.algorithms = [a for a in ALGORITHMS if a in self._algorithm_names(help_text)]

    @staticmethod
    def _algorithm_names(help_text):
        # The --algorithm entry and its continuation lines (indented, not starting an option):
        # the words of each description before any parenthesis, e.g. "spacetime (default: ...)"
        # or "frames, frames-occlusion".
        names, inside = set(), False
        for line in help_text.splitlines():
            m = re.match(r"^\s+--algorithm\s+\S+\s+(.*)$", line)
            if m:
                inside, text = True, m.group(1)
            elif inside and line.startswith(" " * 8) and not re.match(r"^\s+-", line):
                text = line
            else:
                inside = False
                continue
            names.update(re.findall(r"(?<![\w-])[a-z][a-z0-9-]*", text.split("(")[0]))
        return names

    def has(self, option):
        return option in self.options


# The pictures' files in a render's folder (-o); compare and sheet read only these.
PICTURES = "f.####.exr"


def picture_files(out_dir):
    """The pictures render wrote in out_dir (not the maps a multi-pass scene writes beside them)."""
    return sorted(f for f in os.listdir(out_dir) if re.fullmatch(r"f\.\d+\.exr", f))


class Streyes:
    """The streyes executable."""

    def __init__(self, exe):
        self.exe = os.path.abspath(exe)
        if not os.access(self.exe, os.X_OK):
            raise ToolError("no streyes executable at '%s': build it (cmake --build --preset release) "
                            "or pass --exe" % exe)

    def capabilities(self):
        out = subprocess.run([self.exe, "render", "--help"], capture_output=True, text=True)
        if out.returncode != 0:
            raise ToolError("'%s render --help' failed: %s" % (self.exe, out.stderr.strip()), 1)
        return Capabilities(out.stdout)

    def render(self, scene, args, out_dir):
        """One render into out_dir (emptied first), run in out_dir: what the scene writes besides
        the pictures -o names (a multi-pass file's depth and shadow maps, named from the working
        folder) goes there too, not into the caller's folder. Returns (wall seconds, CPU seconds,
        stats dict): wall time is what a user waits for; CPU time (user + system of the process)
        is less disturbed by other work on the machine."""
        out_dir = os.path.abspath(out_dir)
        if os.path.isdir(out_dir):
            shutil.rmtree(out_dir)
        os.makedirs(out_dir)
        stats_path = os.path.join(out_dir, "stats.json")
        cmd = [self.exe, "render", os.path.abspath(scene), "-o", os.path.join(out_dir, PICTURES), "--stats",
               stats_path, "--quiet"] + list(args)
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        out = subprocess.run(cmd, capture_output=True, text=True, cwd=out_dir)
        wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
        if out.returncode != 0:
            raise ToolError("render failed (exit %d): %s\n%s" % (out.returncode, " ".join(cmd), out.stderr.strip()),
                            out.returncode)
        with open(stats_path) as f:
            return wall, cpu, json.load(f)

    def compare(self, reference_dir, test_dir, resize=False):
        """`streyes compare --json` of every frame in test_dir against reference_dir."""
        cmd = [self.exe, "compare", os.path.join(reference_dir, PICTURES), os.path.join(test_dir, PICTURES),
               "--json"] + (["--resize"] if resize else [])
        out = subprocess.run(cmd, capture_output=True, text=True)
        if out.returncode not in (0, 1):
            raise ToolError("compare failed (exit %d): %s\n%s" % (out.returncode, " ".join(cmd), out.stderr.strip()),
                            1)
        return json.loads(out.stdout)


    def sheet(self, frames_dir, out_png, every=1, columns=0, cell_width=0):
        """`streyes sheet` of the frames in frames_dir (as written by render)."""
        cmd = [self.exe, "sheet", os.path.join(frames_dir, PICTURES), "-o", out_png, "--every", str(every)] + \
            (["--columns", str(columns)] if columns else []) + (["--cell-width", str(cell_width)] if cell_width else [])
        out = subprocess.run(cmd, capture_output=True, text=True)
        if out.returncode != 0:
            raise ToolError("sheet failed (exit %d): %s\n%s" % (out.returncode, " ".join(cmd), out.stderr.strip()), 1)


def counter_value(value):
    """A counter as one number: scalars as they are, {"total": n} dicts by their total."""
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, float)):
        return value
    if isinstance(value, dict) and isinstance(value.get("total"), (int, float)):
        return value["total"]
    return None


# Counters shown in tables, in this order; any other scalar counter a build reports (such as
# occlusion culling's) is appended after them automatically, so a counter added to the renderer's
# list (STREYES_RENDER_COUNTERS, include/streyes/stats.h) needs nothing here.
KNOWN_COUNTERS = [("splits", "splits"), ("grids_diced", "grids"), ("micropolygons", "micropolygons"),
                  ("sample_tests", "sample tests"), ("hit_efficiency", "hit eff.")]
SKIPPED_COUNTERS = {"root_bodies", "buckets", "sample_hits", "culled_eye_split_limit", "culled_split_limit",
                    "eye_splits", "culled_clip", "culled_view", "passes"}


def counter_columns(stats_list):
    """(key, heading) pairs for the counters of these stats: the known ones, then any other that is
    not zero in every one of them."""
    cols = list(KNOWN_COUNTERS)
    known = {k for k, _ in cols} | SKIPPED_COUNTERS
    extra = []
    for s in stats_list:
        for k, v in s.get("counters", {}).items():
            if k not in known and k not in extra and counter_value(v):
                extra.append(k)
    return cols + [(k, k.replace("_", " ")) for k in extra]


def format_count(v):
    if v is None:
        return "–"
    if isinstance(v, float) and v < 10:
        return "%.3g" % v
    v = float(v)
    for unit, scale in (("G", 1e9), ("M", 1e6), ("k", 1e3)):
        if abs(v) >= scale:
            return "%.3g %s" % (v / scale, unit)
    return "%d" % v


def markdown_table(headings, rows, align=None):
    align = align or ["l"] + ["r"] * (len(headings) - 1)
    line = lambda cells: "| " + " | ".join(str(c) for c in cells) + " |"
    sep = "|" + "|".join(":--" if a == "l" else "--:" for a in align) + "|"
    return "\n".join([line(headings), sep] + [line(r) for r in rows]) + "\n"


def machine_info():
    """Where and when the figures were measured."""
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        if commit and dirty:
            commit += " (with local changes)"
    except OSError:
        commit = ""
    return {
        "date": datetime.datetime.now().strftime("%Y-%m-%d %H:%M"),
        "cpu": cpu,
        "cores": os.cpu_count(),
        "load_average": os.getloadavg()[0],
        "commit": commit or "unknown",
    }


def machine_line(info):
    return ("%s, commit %s, %s, %d cores, load average %.2f at the start (other work on the machine slows "
            "every setting alike, but adds noise to the times)" %
            (info["date"], info["commit"], info["cpu"], info["cores"], info["load_average"]))


def existing_scenes(scenes, note):
    """The scenes that exist (relative to the project root when not found as given)."""
    found = []
    for s in scenes:
        path = s if os.path.exists(s) else os.path.join(ROOT, s)
        if os.path.exists(path):
            found.append(path)
        else:
            note("skipping %s: it does not exist (yet)" % s)
    return found


def scene_label(path):
    """'scenes/demo.rib' for a scene in the project, else the path as given."""
    rel = os.path.relpath(os.path.abspath(path), ROOT)
    return rel if not rel.startswith("..") else path


def write_text(path, text):
    """Writes a file whole: to a temporary name first, then renamed."""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    tmp = path + ".tmp%d" % os.getpid()
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def gnuplot(script, out_png):
    """Runs a gnuplot script that writes out_png (through a temporary name)."""
    exe = shutil.which("gnuplot")
    if not exe:
        raise ToolError("gnuplot is not installed: apt-get install gnuplot-nox (tools/setup.sh lists it)", 1)
    tmp = out_png + ".tmp%d.png" % os.getpid()
    out = subprocess.run([exe], input=script.replace("@OUTPUT@", tmp), capture_output=True, text=True)
    if out.returncode != 0 or not os.path.exists(tmp):
        raise ToolError("gnuplot failed: %s" % out.stderr.strip(), 1)
    os.replace(tmp, out_png)
