# Check: `stirrup check` on the shot as it stands in Blender (docs/check.md, "A baked shot"), a timeline
# marker "stirrup: RULE" at every frame a rule flags, the counts and findings in the panel. The add-on's
# own markers are replaced each time; the user's are never touched.
import json
import os

import bpy

from . import export, gltf_files, mapping, program, ride, tack

MARKER = "stirrup: "


def export_shot(context, name):
    """The horse and rider exported as one shot stirrup reads (export.shot), their mappings as kept (or made
    now); returns (path, Blender's frame of the shot's frame 1, the shot's frames in the scene's frame range
    as stirrup's --frames, mappings made now)."""
    horse, rider = ride.chosen(context)
    program.find_program(context)
    work = export.work_dir(context)
    maps, new = mapping.for_both(context, work)
    path = os.path.join(work, name)
    glb = export.shot(context, horse, rider, maps["horse"], maps["rider"], path, tack_rig=tack.rig_of(context.scene))
    start = glb.start_time()
    fps = ride.fps_of(context.scene)
    scene = context.scene
    if start is None:  # nothing keyed: the scene as it stands at the current frame, one frame
        return path, scene.frame_current, "1", new
    first = int(round(start * fps))
    a, b = max(1, scene.frame_start - first + 1), min(glb.key_count(), scene.frame_end - first + 1)
    if b < a:
        raise program.StirrupError("the scene's frame range %d-%d holds none of the shot's keyed frames %d-%d" %
                                   (scene.frame_start, scene.frame_end, first, first + glb.key_count() - 1))
    return path, first, "%d-%d" % (a, b), new


def check(context):
    path, first, frames, new = export_shot(context, "check-shot.glb")
    s = context.scene.stirrup
    _, out = program.run(["check", path, "--json", "--profile", s.profile, "--frames", frames], context, ok_codes=(0, 1, 2))
    report = json.loads(out)
    mapping.keep_new(context, new)
    markers = context.scene.timeline_markers
    for m in [m for m in markers if m.name.startswith(MARKER)]:
        markers.remove(m)
    s.findings.clear()
    placed = set()
    for f in report.get("findings", []):
        frame = None if f.get("frame") is None else f["frame"] + first - 1
        item = s.findings.add()
        item.frame, item.rule, item.severity, item.text = frame if frame is not None else first, f["rule"], f["severity"], f["text"]
        if frame is not None and f["severity"] != "note" and (frame, f["rule"]) not in placed:
            placed.add((frame, f["rule"]))
            markers.new(MARKER + f["rule"], frame=frame)
    by_rule = ", ".join("%s %d" % (r, c["failures"] + c["warnings"]) for r, c in sorted(report.get("rules", {}).items())
                        if c["failures"] + c["warnings"])
    s.check_summary = "%d frames: %d failures, %d warnings, %d notes%s" % (
        report.get("frames", 0), report["failures"], report["warnings"], report["notes"], (" (" + by_rule + ")") if by_rule else "")
    s.check_unmeasured = ", ".join(dict.fromkeys(u["rule"] for u in report.get("unmeasured", [])))
    return "stirrup check: " + s.check_summary


class STIRRUP_OT_check(bpy.types.Operator):
    """Check the shot with stirrup: a timeline marker at every flagged frame, the findings in the panel"""
    bl_idname = "stirrup.check"
    bl_label = "Check"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        try:
            line = check(context)
        except program.StirrupError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"WARNING"} if context.scene.stirrup.findings else {"INFO"}, line)
        return {"FINISHED"}


classes = [STIRRUP_OT_check]
