"""The render engine: F12 renders a frame, an animation render runs streyes once for the range.

Blender calls render() once a frame, on a new engine each time. The first call of an animation
(is_animation) exports every frame still to render (frame step included) and starts one
`streyes render SHOT.####.rib --frames A-B --resume`; that job lives at module level, and each
call waits for its frame's file, hands it to Blender and, on the last, tidies up.
"""

import hashlib
import json
import os
import shutil
import tempfile
import time

import bpy

from . import export
from . import job as job_mod
from .properties import ADDON

STEM = "shot"
_current = None  # the animation being rendered: an Animation, or None


class Animation:
    """The exported frames of one render and the streyes run that renders them."""

    def __init__(self, key, folder, temporary, numbers, run, exporter_said):
        self.key = key
        self.folder = folder
        self.temporary = temporary
        self.numbers = numbers        # Blender frame -> RIB frame number
        self.pending = set(numbers)   # Blender frames not handed to Blender yet
        self.run = run
        self.reported = set(exporter_said)

    def finish(self):
        global _current
        if self.run.running():
            self.run.cancel()
        self.run.wait()
        if self.temporary:
            shutil.rmtree(self.folder, ignore_errors=True)
        if _current is self:
            _current = None


class StreyesRenderEngine(bpy.types.RenderEngine):
    bl_idname = "STREYES"
    bl_label = "streyes"
    bl_use_preview = False
    bl_use_postprocess = True
    bl_use_eevee_viewport = True  # the viewport's Rendered mode shows Eevee: streyes renders files
    bl_use_shading_nodes_custom = False  # materials are Blender's shader node trees

    def render(self, depsgraph):
        try:
            self._render(depsgraph)
        except (job_mod.StreyesNotFound, export.ExportError, OSError) as e:
            self._fail(str(e))

    # -- reporting ------------------------------------------------------------------------------------
    def _fail(self, message):
        global _current
        if _current is not None:
            _current.finish()
        self.error_set(message)
        self.report({"ERROR"}, message)

    def _warn(self, text):
        self.report({"WARNING"}, "streyes: " + text)

    # -- one call a frame ------------------------------------------------------------------------------
    def _render(self, depsgraph):
        global _current
        scene = depsgraph.scene
        frame = scene.frame_current
        prefs = bpy.context.preferences.addons.get(ADDON)
        exe = job_mod.find_streyes(prefs.preferences.streyes_path if prefs else "")
        anim = _current
        key = self._key(scene)
        if anim is not None and not (self.is_animation and anim.key == key and frame in anim.pending and
                                     not anim.run.cancelled):
            anim.finish()
            anim = None
        if anim is None:
            frames = self._frames(scene, frame) if self.is_animation else [frame]
            anim = _current = self._start(depsgraph, exe, key, frames)
            if anim is None:
                return
        number = anim.numbers[frame]
        self.update_stats("", "streyes: rendering frames %d-%d" % (anim.run.first, anim.run.last))

        def progress(percent, elapsed, eta):
            self.update_progress(percent / 100.0)
            self.update_stats("", "streyes: %d%% of frames %d-%d, %s elapsed, ETA %s" %
                              (percent, anim.run.first, anim.run.last, elapsed or "0:00", eta or "?"))

        done = anim.run.wait_for_frame(number, self.test_break, progress)
        self._forward_warnings(anim)
        if done is None:  # cancelled: streyes is stopped, only complete frames remain
            anim.finish()
            return
        if not done:
            message = anim.run.failure()
            anim.finish()
            self._fail(message)
            return
        self._load(scene, anim.run.frame_file(number))
        anim.pending.discard(frame)
        if not anim.pending:
            anim.run.wait()
            self._finished(anim)
            anim.finish()

    def _key(self, scene):
        r = scene.render
        return (scene.name, bpy.data.filepath, r.resolution_x, r.resolution_y, r.resolution_percentage,
                scene.frame_start, scene.frame_end, scene.frame_step)

    def _frames(self, scene, frame):
        """The frames this animation render will ask for: from this one to the end, by the frame
        step, less those whose files Blender will not overwrite."""
        r = scene.render
        frames = []
        for f in range(frame, scene.frame_end + 1, max(1, scene.frame_step)):
            if f != frame and not r.use_overwrite and os.path.exists(r.frame_path(frame=f)):
                continue
            frames.append(f)
        return frames

    def _folder(self, scene):
        s = scene.streyes
        if not s.keep_files:
            return tempfile.mkdtemp(prefix="streyes-"), True
        base = bpy.path.abspath(s.export_folder) if bpy.data.filepath or not s.export_folder.startswith("//") \
            else os.path.join(tempfile.gettempdir(), "streyes")
        return os.path.join(base, bpy.path.clean_name(scene.name)), False

    def _start(self, depsgraph, exe, key, frames):
        scene = depsgraph.scene
        folder, temporary = self._folder(scene)
        os.makedirs(folder, exist_ok=True)
        warnings = []
        exporter = export.Exporter(self, depsgraph, folder, warnings.append)
        # Every frame from the first to the last asked for: a streyes sequence is consecutive files.
        step = max(1, scene.frame_step)
        span = list(range(frames[0], frames[-1] + 1, step))

        def exported(i, n):
            self.update_stats("", "streyes: exporting frame %d of %d" % (i, n))
            self.update_progress(0.0)

        self.update_stats("", "streyes: exporting %d frame%s" % (len(span), "" if len(span) == 1 else "s"))
        cpu = time.process_time()
        written = exporter.export(span, STEM, exported)
        print("streyes: exported %d frame%s in %.2f s of CPU" %
              (len(span), "" if len(span) == 1 else "s", time.process_time() - cpu))
        for w in warnings:
            self._warn(w)
        if self.test_break():
            if temporary:
                shutil.rmtree(folder, ignore_errors=True)
            return None
        numbers = {f: n for f, n, _ in written if f in frames}
        first, last = written[0][1], written[-1][1]
        output = os.path.join(folder, "frames", STEM + ".####.exr")
        args = self._options(scene, folder)
        self._drop_stale_frames(written, output, args)
        run = job_mod.Job(exe, os.path.join(folder, STEM + ".####.rib"), output, first, last, args,
                          log_path=os.path.join(folder, "streyes.log"))
        print("streyes: %s" % " ".join(run.command))
        run.start()
        anim = Animation(key, folder, temporary, numbers, run, warnings)
        anim.subdivision_meshes = list(exporter.subdivision_meshes)
        return anim

    def _options(self, scene, folder):
        s = scene.streyes
        r = scene.render
        args = ["--resume", "--stats", os.path.join(folder, "stats.json")]
        if s.tolerance > 0:
            args += ["--tolerance", "%g" % s.tolerance]
        if r.threads_mode == "FIXED":
            args += ["--threads", str(r.threads)]
        return args

    def _drop_stale_frames(self, written, output, args):
        """--resume keeps a frame file only if it was rendered from the same RIB and options: a
        stamp beside each frame says what it was rendered from."""
        opts = [a for a in args if a not in ("--resume",)]
        for _, number, rib_path in written:
            with open(rib_path, "rb") as f:
                digest = hashlib.sha256(f.read() + json.dumps(opts).encode()).hexdigest()
            frame = job_mod.frame_path(output, number)
            stamp = frame + ".stamp"
            old = open(stamp).read().strip() if os.path.exists(stamp) else None
            if old != digest and os.path.exists(frame):
                os.remove(frame)
            os.makedirs(os.path.dirname(stamp), exist_ok=True)
            with open(stamp, "w") as f:
                f.write(digest + "\n")

    def _forward_warnings(self, anim):
        for w in list(anim.run.warnings):
            if w not in anim.reported:
                anim.reported.add(w)
                self._warn(w)

    def _load(self, scene, path):
        r = scene.render
        result = self.begin_result(0, 0, self.resolution_x, self.resolution_y)
        try:
            x = y = 0
            if r.use_border and r.use_crop_to_border:
                full_x = int(r.resolution_x * r.resolution_percentage / 100)
                full_y = int(r.resolution_y * r.resolution_percentage / 100)
                x, y = int(r.border_min_x * full_x), int(r.border_min_y * full_y)
            result.layers[0].load_from_file(path, x=x, y=y)
        finally:
            self.end_result(result)

    def _finished(self, anim):
        run = anim.run
        line = "streyes: frames %d-%d in %.2f s of CPU" % (run.first, run.last, run.cpu_seconds or 0.0)
        print(line)
        self.update_stats("", line)
