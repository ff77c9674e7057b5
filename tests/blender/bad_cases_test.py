"""The add-on's bad cases, end to end: Blender run as a user runs it, its output read.

    bad_cases_test.py BLENDER STREYES SOURCE WORK

- streyes not found: the render stops with a message naming the three places looked in (the
  add-on's preferences, $STREYES_BIN, PATH);
- an unsupported node: a warning naming the material and the node, and the frame is rendered;
- a scene streyes refuses: the render stops with streyes's message, naming the RIB file and line;
- a projection that changes over the frames (streyes has one a sequence until per-frame
  projections land): a warning, and every frame takes the first's;
- cancelling (SIGINT to Blender, as Ctrl+C or Esc): streyes stops at once, and every frame file
  left (Blender's and streyes's) is complete; no temporaries are left.
"""

import glob
import os
import re
import shutil
import signal
import subprocess
import sys
import time

BLENDER, STREYES, SOURCE, WORK = sys.argv[1:5]
SCENE = os.path.join(SOURCE, "tests", "blender", "bad_case_scene.py")
failures = []


def check(ok, text):
    print(("ok      " if ok else "FAILED  ") + text)
    if not ok:
        failures.append(text)


def blender(case, env_extra=None, wait=True):
    work = os.path.join(WORK, case)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    env = dict(os.environ, STREYES_BIN=STREYES)
    # Blender's Python takes its prefix from the python3 on the PATH: not a pyenv interpreter
    # that may be running this script (it lacks Debian's numpy and OpenImageIO).
    env["PATH"] = ":".join(p for p in env.get("PATH", "").split(":") if "pyenv" not in p)
    for k in [k for k in env if k.startswith("PYENV")]:
        del env[k]
    env.update(env_extra or {})
    cmd = [BLENDER, "-b", "--factory-startup", "--python-exit-code", "1", "--python", SCENE, "--",
           "--case", case, "--source", SOURCE, "--work", work]
    if not wait:
        return subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True), work
    p = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
    return p.returncode, p.stdout, work


def exr_complete(path, width, height):
    """Reads the whole file back (a half-written one does not read)."""
    try:
        import OpenImageIO as oiio
    except ImportError:
        out = subprocess.run(["oiiotool", "--info", "-v", "--stats", path], capture_output=True, text=True)
        size = re.search(r"\b%d\s+x\s+%d\b" % (width, height), out.stdout)
        return out.returncode == 0 and size is not None and "rror" not in out.stdout + out.stderr
    inp = oiio.ImageInput.open(path)
    if inp is None:
        return False
    spec = inp.spec()
    pixels = inp.read_image(0, 0, 0, spec.nchannels, oiio.FLOAT)
    inp.close()
    return pixels is not None and spec.width == width and spec.height == height


def children(pid):
    """Every process descended from pid (from /proc)."""
    found, todo = [], [pid]
    while todo:
        p = todo.pop()
        for task in glob.glob("/proc/%d/task/*/children" % p):
            try:
                kids = [int(k) for k in open(task).read().split()]
            except OSError:
                continue
            found += kids
            todo += kids
    return found


def command_of(pid):
    try:
        return open("/proc/%d/cmdline" % pid, "rb").read().split(b"\0")[0].decode()
    except OSError:
        return ""


def case_missing():
    env = {"STREYES_BIN": os.path.join(WORK, "no-such-streyes"), "PATH": "/nonexistent-bin"}
    rc, out, _ = blender("missing", env)
    errors = [l for l in out.splitlines() if l.startswith("RENDER-ERROR:")]
    check(len(errors) == 1, "streyes missing: the render reports an error")
    msg = errors[0] if errors else ""
    check("streyes was not found" in msg and "preferences" in msg and "$STREYES_BIN" in msg and
          "no-such-streyes" in msg and "PATH (/nonexistent-bin)" in msg,
          "the message names the three places looked in: %s" % msg)


def case_node():
    rc, out, work = blender("node")
    check(rc == 0 and "RENDER-DONE" in out, "unsupported nodes: the render goes on (exit %d)" % rc)
    check("material 'Marble': node 'Veins' (ShaderNodeTexNoise) is not supported" in out,
          "a warning names the material and the noise node")
    check("material 'Window': node 'Pane' (ShaderNodeBsdfGlass) is not supported" in out,
          "a warning names the material and the glass node")
    frame = os.path.join(work, "out", "frame.0001.exr")
    check(os.path.exists(frame) and exr_complete(frame, 64, 48), "the frame is written")


def case_refused():
    rc, out, work = blender("refused")
    errors = [l for l in out.splitlines() if l.startswith("RENDER-ERROR:")]
    msg = errors[0] if errors else ""
    rib = os.path.join(work, "export", "Scene", "shot.0001.rib")
    check(len(errors) == 1, "a refused scene: the render reports an error")
    check((rib + ":5: error:") in msg and "filter widths must be at most 32 pixels" in msg,
          "the message is streyes's, with the RIB file and line: %s" % msg)
    check(not glob.glob(os.path.join(work, "out", "*")), "no frame is written")


def case_zoom():
    rc, out, work = blender("zoom")
    check(rc == 0 and "RENDER-DONE" in out, "a zooming camera: the render goes on (exit %d)" % rc)
    check("camera 'Camera': the projection (focal length, shift, sensor, clipping or focus) changes in frame 2" in out,
          "a warning says the projection changes and which frame's is used")
    ribs = [open(os.path.join(work, "export", "Scene", "shot.%04d.rib" % f)).read() for f in (1, 2, 3)]
    proj = [re.search(r"^\s*Projection .*$", r, re.M).group(0) for r in ribs]
    check(len(set(proj)) == 1, "every frame has frame 1's projection: %s" % proj)
    frames = sorted(glob.glob(os.path.join(work, "out", "*.exr")))
    check(len(frames) == 3, "the three frames are written")


def case_cancel():
    proc, work = blender("cancel", wait=False)
    frames_dir = os.path.join(work, "export", "Scene", "frames")
    streyes_pid = None
    deadline = time.time() + 300
    while time.time() < deadline and proc.poll() is None:
        kids = [k for k in children(proc.pid) if os.path.basename(command_of(k)) == "streyes"]
        if kids:
            streyes_pid = kids[0]
            break
        time.sleep(0.2)
    check(streyes_pid is not None, "cancel: streyes started")
    time.sleep(3)  # into the render
    check(proc.poll() is None and streyes_pid is not None and os.path.exists("/proc/%d" % streyes_pid),
          "cancel: streyes is still rendering after 3 s")
    t0 = time.time()
    proc.send_signal(signal.SIGINT)  # what Ctrl+C (Esc in the interface) does to a render
    gone = False
    while time.time() - t0 < 30:
        if streyes_pid is None or not os.path.exists("/proc/%d" % streyes_pid) or \
                open("/proc/%d/stat" % streyes_pid).read().split()[2] == "Z":
            gone = True
            break
        time.sleep(0.05)
    stopped = time.time() - t0
    check(gone, "cancel: streyes stops (%.1f s after the interrupt)" % stopped)
    try:
        out, _ = proc.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, _ = proc.communicate()
        check(False, "cancel: Blender exits after the interrupt")
    print(out[-3000:])
    left = glob.glob(os.path.join(frames_dir, ".*")) + glob.glob(os.path.join(frames_dir, "*.tmp*"))
    check(not left, "cancel: no temporaries left in streyes's frames: %s" % left)
    for path in sorted(glob.glob(os.path.join(frames_dir, "*.exr")) + glob.glob(os.path.join(work, "out", "*"))):
        check(exr_complete(path, 640, 360), "cancel: %s is complete" % os.path.relpath(path, work))
    blender_frames = glob.glob(os.path.join(work, "out", "*.exr"))
    check(len(blender_frames) < 24, "cancel: the animation was cut short (%d of 24 frames)" % len(blender_frames))


for case in (case_missing, case_node, case_refused, case_zoom, case_cancel):
    case()
if failures:
    print("%d check(s) failed" % len(failures))
    sys.exit(1)
print("all checks passed")
