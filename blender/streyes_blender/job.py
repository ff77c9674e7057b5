"""One run of the streyes command over a block of exported frames, watched from Blender.

Nothing here imports bpy, so that the tests can drive a run from plain Python too. The engine
starts a job on the first frame of an animation render and asks it, once a frame, to wait for
that frame's file: streyes writes every frame to a hidden temporary and renames it when it is
complete, so a frame file that exists is a whole frame.
"""

import glob
import os
import re
import shutil
import signal
import subprocess
import threading
import time

# "streyes: 30% (412/1373 buckets), 1:05 elapsed, ETA 2:31" (a line a tenth when stderr is not a
# terminal), "file.rib:12: error: ...", "file.rib:12: warning: ...".
_PROGRESS = re.compile(r"^streyes: (\d+)% \((\d+)/(\d+) buckets\), (\S+) elapsed, ETA (\S+)$")
_ERROR = re.compile(r"^(?:(?P<where>.+?:\d+(?::\d+)?): |streyes: )?(?:error|render failed): (?P<what>.*)$")
_WARNING = re.compile(r"^(?:(?P<where>.+?:\d+(?::\d+)?): )?warning: (?P<what>.*)$")


class StreyesNotFound(Exception):
    pass


def find_streyes(preference_path=""):
    """The streyes command: the add-on's preference, else $STREYES_BIN, else PATH.

    Raises StreyesNotFound naming the three places looked in."""
    looked = []
    pref = (preference_path or "").strip()
    if pref:
        path = os.path.abspath(os.path.expanduser(pref))
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return path
        looked.append("the add-on's preferences ('%s': %s)" %
                      (pref, "not executable" if os.path.exists(path) else "no such file"))
    else:
        looked.append("the add-on's preferences (empty)")
    env = os.environ.get("STREYES_BIN", "").strip()
    if env:
        path = os.path.abspath(os.path.expanduser(env))
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return path
        looked.append("$STREYES_BIN ('%s': %s)" % (env, "not executable" if os.path.exists(path) else "no such file"))
    else:
        looked.append("$STREYES_BIN (not set)")
    found = shutil.which("streyes")
    if found:
        return found
    looked.append("PATH (%s)" % (os.environ.get("PATH", "") or "empty"))
    raise StreyesNotFound("streyes was not found: looked in " + "; ".join(looked) +
                          ". Set its path in Edit > Preferences > Add-ons > streyes, or set STREYES_BIN, "
                          "or put streyes on PATH")


def temporaries(pattern):
    """Hidden temporaries streyes writes a frame into before renaming it (".STEM.tmpPID.EXT")."""
    folder, name = os.path.split(pattern)
    stem, ext = os.path.splitext(name)
    prefix = stem.split("#", 1)[0]
    return glob.glob(os.path.join(glob.escape(folder or "."), "." + glob.escape(prefix) + "*.tmp*" + glob.escape(ext)))


def frame_path(pattern, number):
    """The file of frame `number` in a ####-pattern (the run of # is the zero-padded number)."""
    m = re.search(r"#+", pattern)
    if not m:
        return pattern
    digits = len(m.group(0))
    text = "%0*d" % (digits, number) if number >= 0 else "-%0*d" % (digits, -number)
    return pattern[:m.start()] + text + pattern[m.end():]


class Job:
    """streyes render SCENE --frames A-B -o OUTPUT ..., run in the background.

    `args` are the extra options (--threads N, --tolerance T, --resume, --stats FILE ...)."""

    def __init__(self, executable, scene, output, first, last, args=(), log_path=None):
        self.executable = executable
        self.scene = scene
        self.output = output
        self.first, self.last = first, last
        self.command = [executable, "render", scene, "--frames", "%d-%d" % (first, last), "-o", output] + list(args)
        self.log_path = log_path
        self.process = None
        self.returncode = None
        self.cpu_seconds = None  # user + system CPU time of streyes, once it has exited
        self.percent = 0
        self.eta = ""
        self.elapsed = ""
        self.errors = []    # streyes's error lines, as it wrote them ("file:line: error: ...")
        self.warnings = []  # its warning lines (each once)
        self.lines = []     # everything streyes said on stderr
        self.cancelled = False
        self._lock = threading.Lock()
        self._reader = None
        self._waiter = None
        self._exited = threading.Event()

    # -- running -------------------------------------------------------------------------------------
    def start(self):
        folder = os.path.dirname(self.output)
        if folder:
            os.makedirs(folder, exist_ok=True)
        log = open(self.log_path, "w") if self.log_path else None
        if log:
            log.write("$ " + " ".join(_quote(a) for a in self.command) + "\n")
            log.flush()
        # Its own process group, so that cancelling stops streyes and nothing it started, and a
        # Ctrl+C meant for Blender does not reach it first.
        self.process = subprocess.Popen(self.command, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                        stderr=subprocess.STDOUT, start_new_session=True)
        self._reader = threading.Thread(target=self._read, args=(log,), daemon=True)
        self._reader.start()
        self._waiter = threading.Thread(target=self._wait, daemon=True)
        self._waiter.start()
        return self

    def _read(self, log):
        for raw in iter(self.process.stdout.readline, b""):
            line = raw.decode("utf-8", "replace").rstrip("\r\n")
            if log:
                log.write(line + "\n")
                log.flush()
            with self._lock:
                self.lines.append(line)
                m = _PROGRESS.match(line)
                if m:
                    self.percent = int(m.group(1))
                    self.elapsed, self.eta = m.group(4), m.group(5)
                    continue
                if _ERROR.match(line):
                    self.errors.append(line)
                elif _WARNING.match(line) and line not in self.warnings:
                    self.warnings.append(line)
        if log:
            log.close()

    def _wait(self):
        # os.wait4 gives the child's CPU time (Popen.wait does not).
        _, status, usage = os.wait4(self.process.pid, 0)
        self.cpu_seconds = usage.ru_utime + usage.ru_stime
        self.returncode = os.waitstatus_to_exitcode(status)
        self.process.returncode = self.returncode
        self._exited.set()

    def running(self):
        return self.process is not None and not self._exited.is_set()

    def wait(self, timeout=None):
        self._exited.wait(timeout)
        if self._exited.is_set() and self._reader:
            self._reader.join(5)
        return self.returncode

    def frame_file(self, number):
        return frame_path(self.output, number)

    def wait_for_frame(self, number, should_stop, on_progress=None, poll=0.1):
        """Waits until frame `number`'s file exists (True), streyes has exited without it (False), or
        should_stop() asks to cancel (cancels the run, returns None)."""
        path = self.frame_file(number)
        last = None
        while True:
            if os.path.exists(path):
                return True
            if should_stop():
                self.cancel()
                return None
            if self._exited.is_set():
                self.wait()
                return os.path.exists(path)
            if on_progress:
                with self._lock:
                    state = (self.percent, self.elapsed, self.eta)
                if state != last:
                    on_progress(*state)
                    last = state
            self._exited.wait(poll)

    def cancel(self, grace=5.0):
        """Stops streyes (SIGTERM to its process group, SIGKILL after `grace` seconds) and removes
        the temporaries of the frames it was writing: the frames already renamed are complete."""
        self.cancelled = True
        if self.running():
            try:
                os.killpg(self.process.pid, signal.SIGTERM)
            except ProcessLookupError:
                pass
            if not self._exited.wait(grace):
                try:
                    os.killpg(self.process.pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
                self._exited.wait()
        self.wait()
        for tmp in temporaries(self.output):
            try:
                os.remove(tmp)
            except OSError:
                pass

    def failure(self):
        """What went wrong, for Blender's report: streyes's own error lines (file:line: error: ...),
        or its exit status and last words."""
        if self.errors:
            return "; ".join(self.errors)
        tail = [l for l in self.lines if l and not _PROGRESS.match(l)][-5:]
        return "streyes exited with status %s%s" % (self.returncode, (": " + " | ".join(tail)) if tail else "")


def _quote(a):
    return a if re.fullmatch(r"[\w@%+=:,./-]+", a) else "'" + a.replace("'", "'\\''") + "'"
