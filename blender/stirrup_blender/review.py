# Review movie: the shot as it stands in Blender (the animator's own touches to the rider included)
# rendered by `stirrup render SHOT.glb` as its side, perspective or close movie at review quality, written
# to the path given, the progress in Blender's status bar (docs/blender.md, "Review movie").
import os
import re
import subprocess
import threading
import time

import bpy

from . import check, export, mapping, program

# A whole record of the bar `stirrup render --progress` draws on stderr, a record a frame
# (cli/progress.h): "render NAME [###...] DONE/TOTAL  FPS fps  Ns left".
_PROGRESS = re.compile(r"(\d+)/(\d+)  [\d.]+ fps")
_running = []  # the renders running beside Blender's window (one at a time)


def rendering():
    """Whether a review movie is being rendered beside Blender's window."""
    return bool(_running)


class Progress:
    """The render's progress in Blender's status bar (window_manager.progress_begin/update/end): the
    percentage of the frames rendered, updated frame by frame as stirrup reports them."""

    def __init__(self, wm):
        self.wm = wm

    def begin(self):
        self.wm.progress_begin(0, 100)

    def update(self, done, total):
        self.wm.progress_update(100 * done // total)

    def end(self):
        self.wm.progress_end()


class Render:
    """A running `stirrup render`, its progress read from the bar it draws on stderr, a record a frame."""

    def __init__(self, context, camera, movie):
        path, _, frames, self.new_maps = check.export_shot(context, "review-shot.glb")  # kept once the movie is made
        out = os.path.join(export.work_dir(context), "review-frames")
        args = [program.find_program(context), "render", path, "--camera", camera, "--preset", "review", "--movie", movie,
                "--out", out, "--frames", frames, "--progress"]
        self.proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        self.done, self.total, self.err = 0, 0, ""
        self.frames = []  # (done, total) of every frame reported and not yet taken, in order
        self.lock = threading.Lock()
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self):
        pending = ""  # the bar's record being written: read only once it ends (a record may span two reads)
        for chunk in iter(lambda: self.proc.stderr.read(64), ""):
            self.err += chunk
            *records, pending = re.split(r"[\r\n]", pending + chunk)
            for record in records:
                found = _PROGRESS.search(record)
                if found:
                    with self.lock:
                        self.done, self.total = int(found[1]), int(found[2])
                        self.frames.append((self.done, self.total))

    def report(self, progress):
        """Hands `progress` every frame reported since the last call, in order."""
        with self.lock:
            frames, self.frames = self.frames, []
        for done, total in frames:
            if total:
                progress.update(done, total)

    def finished(self):
        if self.proc.poll() is None:
            return False
        self.reader.join(timeout=5)
        if self.proc.returncode != 0:
            lines = [l for l in self.err.replace("\r", "\n").splitlines() if l.strip() and not _PROGRESS.search(l)]
            raise program.StirrupError(lines[-1].strip() if lines else "stirrup render failed (exit %d)" % self.proc.returncode)
        return True


class STIRRUP_OT_review_movie(bpy.types.Operator):
    """Render stirrup's review movie of the shot as it stands (side, perspective or close view)"""
    bl_idname = "stirrup.review_movie"
    bl_label = "Review movie"

    filepath: bpy.props.StringProperty(name="Movie", subtype="FILE_PATH", description="The movie to write (.mp4)")
    filter_glob: bpy.props.StringProperty(default="*.mp4", options={"HIDDEN"})
    camera: bpy.props.EnumProperty(name="View", items=[("", "Panel's", "")] + [(k, k, "") for k in ("side", "persp", "close")],
                                   default="", options={"SKIP_SAVE"})

    @classmethod
    def poll(cls, context):
        return not _running

    def _start(self, context):
        if not self.filepath:
            raise program.StirrupError("no movie named (expected a file path ending in .mp4)")
        movie = bpy.path.abspath(self.filepath)
        os.makedirs(os.path.dirname(movie) or ".", exist_ok=True)
        self.movie = movie
        return Render(context, self.camera or context.scene.stirrup.camera, movie)

    def execute(self, context):
        # In Blender's window (after the file browser too) the render runs beside the interface, its
        # progress in the status bar; a script's or a headless Blender's call waits for it.
        if not bpy.app.background and context.window is not None:
            return self._modal_start(context)
        progress = Progress(context.window_manager)
        progress.begin()
        try:
            render = self._start(context)
            while not render.finished():
                time.sleep(0.1)
                render.report(progress)
            render.report(progress)  # the frames read after the last look
        except program.StirrupError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        finally:
            progress.end()
        mapping.keep_new(context, render.new_maps)
        self.report({"INFO"}, "stirrup wrote " + self.movie)
        return {"FINISHED"}

    def invoke(self, context, event):
        if not self.filepath:
            self.filepath = bpy.path.ensure_ext(bpy.path.display_name_from_filepath(bpy.data.filepath) or "shot", ".mp4")
            context.window_manager.fileselect_add(self)
            return {"RUNNING_MODAL"}
        return self._modal_start(context)

    def _modal_start(self, context):
        try:
            self.render = self._start(context)
        except program.StirrupError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        wm = context.window_manager
        self.timer = wm.event_timer_add(0.2, window=context.window)
        self.progress = Progress(wm)
        self.progress.begin()
        wm.modal_handler_add(self)
        _running.append(self.render)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        if event.type == "ESC":
            self.render.proc.terminate()
            return self._end(context, "render stopped", {"WARNING"}, {"CANCELLED"})
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        try:
            if not self.render.finished():
                self.render.report(self.progress)
                if self.render.total:
                    context.workspace.status_text_set("stirrup: rendering %s, frame %d of %d (Esc stops)" %
                                                      (os.path.basename(self.movie), self.render.done, self.render.total))
                return {"RUNNING_MODAL"}
        except program.StirrupError as e:
            return self._end(context, str(e), {"ERROR"}, {"CANCELLED"})
        self.render.report(self.progress)  # the frames read after the last tick
        mapping.keep_new(context, self.render.new_maps)
        return self._end(context, "stirrup wrote " + self.movie, {"INFO"}, {"FINISHED"})

    def _end(self, context, line, level, result):
        if self.render in _running:
            _running.remove(self.render)
        wm = context.window_manager
        wm.event_timer_remove(self.timer)
        self.progress.end()
        context.workspace.status_text_set(None)
        self.report(level, line)
        return result


classes = [STIRRUP_OT_review_movie]
