# Reduce keys: the ride's curves thinned by Blender's own decimation (Graph Editor > Key > Decimate, "Allowed
# Change" mode: bpy.ops.graph.decimate(mode="ERROR")) to the fewest keys that keep her joints within a
# tolerance in centimetres, measured in the world on the pose Blender evaluates (docs/blender.md, "Reducing
# keys").
#
# Decimation bounds each curve's change in its own units; her joints move by a location's change as it is and
# by a rotation's change times the reach of the bone (the farthest deform joint it carries). Each channel's
# allowance is the tolerance taken into its units that way, halved; the result is measured, and when a joint
# strays past the tolerance the allowances are halved and the dense curves decimated again.
import contextlib

import bpy
import numpy as np

from . import program

ATTEMPTS = 6


@contextlib.contextmanager
def _graph_editor(context):
    """A window area turned into a Graph Editor for the duration (headless Blender has a window too)."""
    window = context.window or (context.window_manager.windows[0] if context.window_manager.windows else None)
    if window is None:
        raise program.StirrupError("reduce keys needs a Blender window (none is open)")
    area = max(window.screen.areas, key=lambda a: a.width * a.height)
    was = area.type
    area.type = "GRAPH_EDITOR"
    try:
        region = [r for r in area.regions if r.type == "WINDOW"][0]
        with context.temp_override(window=window, screen=window.screen, area=area, region=region):
            yield area.spaces.active
    finally:
        area.type = was


@contextlib.contextmanager
def _only(context, arm, action):
    """`action` the armature's active action, the armature the only object selected and every bone of it
    selected (the Graph Editor shows only those), all put back afterwards."""
    ad = arm.animation_data
    saved = (ad.action, ad.use_nla)
    view_layer = context.view_layer
    was_selected = [o for o in view_layer.objects if o.select_get()]
    was_active = view_layer.objects.active
    bone_sel = [(b, b.select, b.hide) for b in arm.data.bones]
    for o in was_selected:
        o.select_set(False)
    arm.select_set(True)
    view_layer.objects.active = arm
    for b in arm.data.bones:
        b.select, b.hide = True, False
    ad.use_nla = False
    ad.action = action
    try:
        yield
    finally:
        ad.action, ad.use_nla = saved
        for b, sel, hide in bone_sel:
            b.select, b.hide = sel, hide
        arm.select_set(False)
        for o in was_selected:
            o.select_set(True)
        view_layer.objects.active = was_active


def _reach(arm, bone_name):
    """How far the bone's head is from the farthest deform joint it carries (armature units), at rest."""
    b = arm.data.bones[bone_name]
    head = np.array(b.head_local)
    tails = [np.array(c.head_local) for c in b.children_recursive if c.use_deform] + [np.array(b.tail_local)]
    return max(0.05, max(float(np.linalg.norm(t - head)) for t in tails))


def _allowance(arm, fc, tolerance):
    """The change a curve may make (its units) for a joint to move `tolerance` (armature units)."""
    path = fc.data_path
    if not path.startswith("pose.bones["):
        return tolerance
    bone = path.split('"')[1]
    if bone not in arm.data.bones:
        return tolerance
    if path.endswith("location"):
        return tolerance
    if path.endswith("]") or path.endswith("\"]"):  # a custom property (a switch): keep it as keyed
        return 0.0
    return tolerance / _reach(arm, bone)  # a rotation's radians (or a quaternion's half-angle) and a scale's ratio


def decimate(context, arm, action, tolerance, factor):
    """Decimates every curve of `action` with its allowance times `factor`."""
    groups = {}
    for fc in action.fcurves:
        a = _allowance(arm, fc, tolerance) * factor * 0.5
        if a > 0.0:
            groups.setdefault(round(a, 12), []).append(fc)
    with _only(context, arm, action), _graph_editor(context) as space:
        space.dopesheet.show_only_selected = True
        space.dopesheet.show_hidden = True
        for margin, curves in sorted(groups.items()):
            for fc in action.fcurves:
                on = fc in curves
                fc.select = on
                fc.hide = False
                for k in fc.keyframe_points:
                    k.select_control_point = on
            bpy.ops.graph.decimate(mode="ERROR", remove_error_margin=margin)


def key_count(action):
    return sum(len(fc.keyframe_points) for fc in action.fcurves)


def reduce(context, arm, action, tolerance, measure):
    """Thins `action` in place to within `tolerance` (armature units) of the dense keys' pose, as `measure()`
    (the worst joint distance, armature units, of the pose Blender evaluates over the ride's frames against
    stirrup's) says. Returns (keys before, keys after, worst distance left)."""
    dense = action.copy()
    before = key_count(action)
    factor, worst = 2.0, None  # from twice the allowance, halved until the joints keep within the tolerance
    try:
        for _ in range(ATTEMPTS):
            decimate(context, arm, action, tolerance, factor)
            worst = measure()
            if worst <= tolerance:
                break
            for fc, src in zip(action.fcurves, dense.fcurves):  # start again from the dense keys, allowing half
                fc.keyframe_points.clear()
                fc.keyframe_points.add(len(src.keyframe_points))
                co = np.empty(2 * len(src.keyframe_points))
                src.keyframe_points.foreach_get("co", co)
                fc.keyframe_points.foreach_set("co", co)
                fc.keyframe_points.foreach_set("interpolation", [1] * len(src.keyframe_points))
                fc.update()
            factor *= 0.5
        else:
            worst = measure()
    finally:
        bpy.data.actions.remove(dense)
    return before, key_count(action), worst
