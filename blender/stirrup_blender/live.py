# Live: while on, the rider follows the horse as its keys are edited or the frame changes (docs/blender.md,
# "Live"). A long-running `stirrup live` (cli/cmd_live.cpp, scene/live_rider.h) holds the characters,
# read and seated once, and the horse's motion frame by frame; the add-on hands it the horse as Blender
# evaluates it and poses the rider's bones from what comes back, one JSON line each way.
#
# The rider at a frame reads the horse over about a second around it (the travel fitted to its trunk), so
# the program keeps every frame of the horse: at first the horse's action as exported, then each frame as
# Blender shows it. The current frame goes over fresh on every update; after an edit of the horse the other
# frames are stale until a timer has evaluated them again, a few a tick, the nearest first, each tick ending
# with the current frame's rider from the refreshed motion.
#
# While live is on the rider's action is set aside (kept in scene.stirrup.live_saved_action and given back
# when it is turned off): her bones show the live pose. Off, no handler, timer or process is left.
import json
import subprocess
import time

import bpy
import numpy as np

from . import controls, export, layer, program, ride, tack, transforms

_session = None
_errors = []
REFRESH_BUDGET_S = 0.04  # of a timer tick spent evaluating stale frames of the horse


def report_error(text):
    _errors.append(text)
    print("stirrup live: " + text)


def last_error():
    return _errors[-1] if _errors else ""


class Session:
    def __init__(self, context):
        work = export.work_dir(context)
        p = ride.Prepared(context, work)
        scene = context.scene
        self.first, self.last = min(scene.frame_start, p.first), max(scene.frame_end, p.first)
        scene_file = p.write_scene()
        args = [program.find_program(context), "live", scene_file, "--first", str(self.first), "--last", str(self.last)]
        self.proc = subprocess.Popen(args, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, bufsize=1)
        ready = self.proc.stdout.readline()
        if not ready:
            err = self.proc.stderr.read()
            self.proc.wait()
            raise program.StirrupError(program.last_line(err) or "stirrup live stopped before it was ready")
        ready = json.loads(ready)
        p.keep_new_maps()  # the program is ready: the mappings it was given are the scene's now
        self.horse_joints, self.rider_joints = ready["horse_joints"], ready["rider_joints"]
        self.horse_name, self.rider_name = p.horse.name, p.rider.name
        self.horse_at_export = transforms.np_matrix(p.horse_at_export)
        # The horse's joints among its pose bones, and what takes each one's pose to its deformation.
        names = [b.name for b in p.horse.pose.bones]
        self.horse_index = np.array([names.index(n) if n in names else -1 for n in self.horse_joints], dtype=np.int64)
        rest = transforms.bone_matrices(p.horse.data.bones, "matrix_local")
        self.rest_inv = np.array([np.linalg.inv(rest[i]) if i >= 0 else np.eye(4) for i in self.horse_index])
        self.rider_poser = transforms.Poser(p.rider, self.rider_joints, p.rider_at_export)
        self.rider_order = [self.rider_joints.index(n) for n in self.rider_poser.names]
        # A control rig is posed through its controls, as Ride keys them (controls.py): held at their targets by
        # the helper armature's constraints, so that the evaluation that draws the frame is the only one; the
        # helper and the constraints stay until live is turned off.
        # The tack's points (tack.py) move with her: posed from the deformations stirrup sends with hers.
        self.tack_rig, self.tack_poser, self.tack_order = tack.rig_of(scene), None, []
        tack_joints = ready.get("tack_joints", [])
        if self.tack_rig is not None and tack_joints:
            names = [n for n in tack_joints if n in self.tack_rig.data.bones]
            self.tack_poser = transforms.Poser(self.tack_rig, names, np.eye(4))
            self.tack_order = [tack_joints.index(n) for n in self.tack_poser.names]
        self.solver = None
        plan = controls.plan_for(p.rider, scene.stirrup.limbs, ride.controls_text(context))
        if plan is not None:
            self.solver = controls.Solver(p.rider, plan)
            self.solver.apply_sets()
            self.solver.open(context)
        self.stale = set()
        self.busy = False
        self.frame_changed = False
        self.last_ms = 0.0
        self.updates = 0

    def horse(self):
        return bpy.data.objects.get(self.horse_name)

    def rider(self):
        return bpy.data.objects.get(self.rider_name)

    def horse_frame(self, depsgraph):
        """The horse as Blender shows it now: each joint's deformation in the exported file's glTF world,
        G O (pose) L^-1 O0^-1 G^-1 (transforms.py)."""
        ev = self.horse().evaluated_get(depsgraph)
        pose = transforms.bone_matrices(ev.pose.bones, "matrix")[np.maximum(self.horse_index, 0)]
        back = np.linalg.inv(self.horse_at_export) @ transforms.G_INV
        d = (transforms.G @ transforms.np_matrix(ev.matrix_world)) @ pose @ self.rest_inv @ back
        d[self.horse_index < 0] = np.eye(4)
        return np.round(d.transpose(0, 2, 1).reshape(-1, 16), 9).tolist()  # column by column, as glTF

    def ask(self, request):
        self.proc.stdin.write(json.dumps(request) + "\n")
        self.proc.stdin.flush()
        line = self.proc.stdout.readline()
        if not line:
            raise program.StirrupError(program.last_line(self.proc.stderr.read()) or "stirrup live stopped")
        answer = json.loads(line)
        if "error" in answer:
            raise program.StirrupError(answer["error"])
        return answer

    def pose_rider(self, answer):
        rider = self.rider()
        d = np.array(answer["rider"], dtype=np.float64).reshape(-1, 4, 4).transpose(0, 2, 1)[self.rider_order]
        if self.solver is None:
            self.rider_poser.set_pose(rider, self.rider_poser.bases(rider, d[None])[0])
        else:
            pose = self.rider_poser.pose_matrices(rider, d[None])[0]
            targets = self.solver.targets({n: pose[k] for k, n in enumerate(self.rider_poser.names)})
            self.solver.hold_at(targets)
        if self.tack_poser is not None and "tack" in answer:
            t = np.array(answer["tack"], dtype=np.float64).reshape(-1, 4, 4).transpose(0, 2, 1)[self.tack_order]
            self.tack_poser.set_pose(self.tack_rig, self.tack_poser.bases(self.tack_rig, t[None])[0])
        self.last_ms = answer.get("ms", 0.0)
        self.updates += 1

    def update(self, scene, depsgraph, sets=()):
        """The current frame's horse handed over when stirrup's copy of it is stale (with any other frames
        refreshed), and the rider posed. During playback with no edit, stirrup holds every frame as Blender
        shows it (the export it started from, exact: export.exact_joints), so a frame change asks only for her."""
        frame = scene.frame_current
        sets = list(sets)
        if self.first <= frame <= self.last and frame in self.stale:
            sets.append({"frame": frame, "horse": self.horse_frame(depsgraph)})
            self.stale.discard(frame)
        self.busy = True
        try:
            self.pose_rider(self.ask({"set": sets, "get": frame}))
        finally:
            self.busy = False

    def refresh(self, scene, budget_s=REFRESH_BUDGET_S):
        """Evaluates stale frames of the horse, the nearest to the current first, for about budget_s; then
        the current frame's rider. Returns whether frames are still stale."""
        current = scene.frame_current
        start = time.perf_counter()
        sets = []
        self.busy = True
        try:
            for f in sorted(self.stale, key=lambda f: abs(f - current)):
                scene.frame_set(f)
                sets.append({"frame": f, "horse": self.horse_frame(bpy.context.evaluated_depsgraph_get())})
                self.stale.discard(f)
                if time.perf_counter() - start > budget_s:
                    break
            scene.frame_set(current)
        finally:
            self.busy = False
        self.update(scene, bpy.context.evaluated_depsgraph_get(), sets)
        return bool(self.stale)

    def close(self):
        if self.solver is not None:
            self.solver.close()
            self.solver = None
        if self.proc.poll() is None:
            self.proc.stdin.close()
            try:
                self.proc.wait(timeout=5)
            except subprocess.TimeoutExpired:
                self.proc.kill()


def _safely(f):
    def run(*args):
        if _session is None or _session.busy:
            return None
        try:
            return f(*args)
        except (program.StirrupError, OSError, ValueError) as e:
            report_error(str(e))
            return None
    run.__name__ = f.__name__
    return run


@_safely
def _on_frame(scene, depsgraph):
    if scene.stirrup.rider is None or _session.rider() is None:
        return
    _session.frame_changed = True
    _session.update(scene, depsgraph)


@_safely
def _on_depsgraph(scene, depsgraph):
    horse = _session.horse()
    if horse is None:
        return
    watched = {horse, horse.data}
    if horse.animation_data and horse.animation_data.action:
        watched.add(horse.animation_data.action)
    action = horse.animation_data.action if horse.animation_data else None
    ids = {u.id.original for u in depsgraph.updates}
    # A key edited updates the action; the horse posed by hand updates the object. A frame change may
    # update the object too (the action played), which the frame's own handler has answered.
    touched = bool(ids & watched)
    edited = (action is not None and action in ids) or (touched and not _session.frame_changed)
    if touched:
        _session.frame_changed = False
    if not edited:
        return
    _session.stale = set(range(_session.first, _session.last + 1))  # the current frame goes over at once, below
    _session.update(scene, depsgraph)
    if not bpy.app.timers.is_registered(_refresh_tick):
        bpy.app.timers.register(_refresh_tick, first_interval=0.05)


def _refresh_tick():
    if _session is None or not _session.stale:
        return None
    try:
        more = _session.refresh(bpy.context.scene)
    except (program.StirrupError, OSError, ValueError) as e:
        report_error(str(e))
        return None
    return 0.02 if more else None


def refresh_all(context):
    """Every stale frame refreshed now (a script's or a test's: timers run only in Blender's event loop)."""
    while _session is not None and _session.stale:
        _session.refresh(context.scene, budget_s=1e9)


def handlers_registered():
    return _on_frame in bpy.app.handlers.frame_change_post or _on_depsgraph in bpy.app.handlers.depsgraph_update_post


def start(context):
    global _session
    stop(context)
    _errors.clear()
    session = Session(context)
    rider = session.rider()
    s = context.scene.stirrup
    if rider.animation_data and rider.animation_data.action:
        s.live_saved_action = rider.animation_data.action
        rider.animation_data.action = None
    for arm in (rider, session.tack_rig):
        track = layer.track_of(arm) if arm is not None else None
        if track is not None:
            track.mute = True  # the ride's layer would pose her (and the tack) over the live pose
    _session = session
    bpy.app.handlers.frame_change_post.append(_on_frame)
    bpy.app.handlers.depsgraph_update_post.append(_on_depsgraph)
    _session.update(context.scene, context.evaluated_depsgraph_get())


def stop(context):
    global _session
    for h, lst in ((_on_frame, bpy.app.handlers.frame_change_post), (_on_depsgraph, bpy.app.handlers.depsgraph_update_post)):
        while h in lst:
            lst.remove(h)
    if bpy.app.timers.is_registered(_refresh_tick):
        bpy.app.timers.unregister(_refresh_tick)
    if _session is not None:
        _session.close()
        _session = None
        restore(context.scene.stirrup)


def restore(s):
    """Her action and the ride's layer as they were before Live."""
    rider = s.rider
    if rider is not None and s.live_saved_action is not None:
        rider.animation_data_create()
        rider.animation_data.action = s.live_saved_action
        s.live_saved_action = None
    for arm in (rider, tack.rig_of_quietly(s.id_data)):
        track = layer.track_of(arm) if arm is not None else None
        if track is not None:
            track.mute = False


def stop_all():
    stop(bpy.context)


def session():
    return _session


class STIRRUP_OT_live_refresh(bpy.types.Operator):
    """Evaluate every frame of the horse again now and pose the rider (Live does it by itself after an edit)"""
    bl_idname = "stirrup.live_refresh"
    bl_label = "Refresh live"

    @classmethod
    def poll(cls, context):
        return _session is not None

    def execute(self, context):
        _session.stale = set(range(_session.first, _session.last + 1))
        try:
            refresh_all(context)
        except program.StirrupError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        return {"FINISHED"}


classes = [STIRRUP_OT_live_refresh]
