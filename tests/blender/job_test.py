"""The add-on's streyes runner (blender/streyes_blender/job.py), without Blender: where it looks
for streyes and in which order, frame names, progress and error lines, waiting for frames, and
cancelling (the process group stopped, temporaries removed, complete frames kept). A stand-in
`streyes` (a shell script) plays the renderer; one real render checks the real one's lines.

    job_test.py SOURCE STREYES WORK
"""

import os
import shutil
import stat
import sys
import time

SOURCE, STREYES, WORK = sys.argv[1:4]
sys.path.insert(0, os.path.join(SOURCE, "blender", "streyes_blender"))
import job  # noqa: E402

failures = []


def check(ok, text):
    print(("ok      " if ok else "FAILED  ") + text)
    if not ok:
        failures.append(text)


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)


def script(name, body):
    path = os.path.join(WORK, name)
    with open(path, "w") as f:
        f.write("#!/bin/sh\n" + body)
    os.chmod(path, os.stat(path).st_mode | stat.S_IEXEC)
    return path


# -- finding streyes: the preference, then STREYES_BIN, then PATH ------------------------------------
bin_dir = os.path.join(WORK, "bin")
os.makedirs(bin_dir)
on_path = script("bin/streyes", "exit 0\n")
pref = script("pref-streyes", "exit 0\n")
env_bin = script("env-streyes", "exit 0\n")
old_env = dict(os.environ)
os.environ["PATH"] = bin_dir
os.environ["STREYES_BIN"] = env_bin
check(job.find_streyes(pref) == pref, "the preference comes first")
check(job.find_streyes("") == env_bin, "then STREYES_BIN")
del os.environ["STREYES_BIN"]
check(job.find_streyes("") == on_path, "then the PATH")
os.environ["PATH"] = os.path.join(WORK, "empty")
os.environ["STREYES_BIN"] = os.path.join(WORK, "nothing")
try:
    job.find_streyes(os.path.join(WORK, "missing-pref"))
    check(False, "nowhere: an error")
except job.StreyesNotFound as e:
    msg = str(e)
    check("missing-pref" in msg and "no such file" in msg and "$STREYES_BIN" in msg and "nothing" in msg and
          "PATH (%s)" % os.path.join(WORK, "empty") in msg, "nowhere: the message names the three places: " + msg)
os.environ.clear()
os.environ.update(old_env)

# -- names ------------------------------------------------------------------------------------------
check(job.frame_path("/x/shot.####.exr", 7) == "/x/shot.0007.exr", "frame 7 of shot.####.exr")
check(job.frame_path("a.##.exr", 123) == "a.123.exr", "a number longer than the run of #")

# -- a run that reports progress and writes frames one by one ---------------------------------------
out = os.path.join(WORK, "frames", "f.####.exr")
fake = script("fake-streyes", """
out=$6; dir=$(dirname "$out")
mkdir -p "$dir"
echo "scene.rib:3: warning: something ignored" >&2
echo "scene.rib:3: warning: something ignored" >&2
i=1
while [ $i -le 3 ]; do
  echo "streyes: $((i * 30))% ($i/3 buckets), 0:0$i elapsed, ETA 0:0$((3 - i))" >&2
  touch "$dir/.f.000$i.tmp$$.exr"; sleep 0.3
  mv "$dir/.f.000$i.tmp$$.exr" "$dir/f.000$i.exr"
  i=$((i + 1))
done
""")
run = job.Job(fake, "scene.rib", out, 1, 3, ["--resume"], log_path=os.path.join(WORK, "log.txt")).start()
seen = []
got = run.wait_for_frame(2, lambda: False, lambda p, e, eta: seen.append(p))
check(got is True and os.path.exists(job.frame_path(out, 2)), "frame 2 is there when waited for")
# On a loaded machine the fake may print frame 3's line before frame 2 is noticed: 90 is fine too.
check(seen and seen == sorted(seen) and set(seen) <= {0, 30, 60, 90} and seen[-1] >= 30, "progress read from the lines: %s" % seen)
check(run.wait_for_frame(3, lambda: False) is True and run.wait(10) == 0, "frame 3, then streyes ends with 0")
check(run.warnings == ["scene.rib:3: warning: something ignored"], "each warning once: %s" % run.warnings)
check(run.cpu_seconds is not None and run.cpu_seconds >= 0, "the run's CPU time is known")
check(open(os.path.join(WORK, "log.txt")).read().startswith("$ " + fake + " render scene.rib --frames 1-3"),
      "the log starts with the command")

# -- a frame never written: the run ends without it, with streyes's error ---------------------------
bad = script("bad-streyes", 'echo "shot.0001.rib:12: error: Translate: expected 3 numbers" >&2\nexit 2\n')
run = job.Job(bad, "shot.####.rib", out, 1, 1).start()
check(run.wait_for_frame(9, lambda: False) is False, "an error: the frame is not waited for forever")
check(run.returncode == 2 and run.failure() == "shot.0001.rib:12: error: Translate: expected 3 numbers",
      "the failure is streyes's line: %r" % run.failure())

# -- cancelling ------------------------------------------------------------------------------------
out2 = os.path.join(WORK, "frames2", "f.####.exr")
slow = script("slow-streyes", """
dir=$(dirname "$6"); mkdir -p "$dir"
touch "$dir/f.0001.exr"
touch "$dir/.f.0002.tmp$$.exr"
sh -c 'sleep 60.%d' &
wait
""" % os.getpid())  # a sleep of its own: other runs of this test may share the machine
run = job.Job(slow, "s.rib", out2, 1, 2).start()
check(run.wait_for_frame(1, lambda: False) is True, "frame 1 written before the cancel")
t0 = time.time()
calls = [0]


def stop():
    calls[0] += 1
    return calls[0] > 3


check(run.wait_for_frame(2, stop) is None, "cancelled while waiting for frame 2")
check(time.time() - t0 < 5 and not run.running(), "streyes stopped at once (%.2f s)" % (time.time() - t0))
check(not job.temporaries(out2), "its temporaries removed: %s" % job.temporaries(out2))
check(os.path.exists(job.frame_path(out2, 1)), "the complete frame 1 kept")
def cmdline(pid):
    try:
        return open("/proc/%s/cmdline" % pid, "rb").read().replace(b"\0", b" ").decode(errors="replace")
    except OSError:  # gone while we looked
        return ""


mine = "sleep 60.%d" % os.getpid()
deadline = time.time() + 2  # a killed process may take a moment to leave /proc on a loaded machine
children = [p for p in os.listdir("/proc") if p.isdigit() and mine in cmdline(p)]
while children and time.time() < deadline:
    time.sleep(0.05)
    children = [p for p in os.listdir("/proc") if p.isdigit() and mine in cmdline(p)]
check(not children, "nothing it started is left running: %s" % children)

# -- the real streyes: its progress and error lines are read ---------------------------------------
rib = os.path.join(WORK, "real.rib")
with open(rib, "w") as f:
    f.write('Format 64 48 1\nProjection "perspective" "fov" [40]\nTranslate 0 0 5\nWorldBegin\n'
            'LightSource "distantlight" 1\nSurface "matte"\nSphere 1 -1 1 360\nWorldEnd\n')
out3 = os.path.join(WORK, "real", "r.####.exr")
run = job.Job(STREYES, rib, out3, 0, 0).start()
check(run.wait_for_frame(0, lambda: False) is True and run.wait(60) == 0, "a real render's frame 0")
check(run.percent == 100, "its progress lines read up to 100%% (%d)" % run.percent)
with open(rib, "a") as f:
    f.write("Translate 1 2\n")
run = job.Job(STREYES, rib, out3, 0, 0).start()
run.wait(60)
check(run.returncode == 2 and run.errors and run.errors[0].startswith(rib + ":9: error:"),
      "a real error line, with the RIB file and line: %s" % run.errors)

if failures:
    print("%d check(s) failed" % len(failures))
    sys.exit(1)
print("all checks passed")
