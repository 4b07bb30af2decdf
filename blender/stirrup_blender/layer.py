# The ride as a layer the animator works over (docs/blender.md, "The ride layer"): Ride's keys go to an action
# in an NLA track of their own, "stirrup ride", below everything of hers: her other tracks, and her active
# action, which Blender blends on top with Combine (a rotation she keys turns the ridden pose further, a
# location she keys moves it further). A second Ride replaces only the track's strip.
#
# Blender's glTF exporter plays only the active action (it turns the NLA off while it samples), so a
# layered armature is exported through a flattened copy: every channel of the stack, as Blender blends it,
# keyed at every frame in one temporary action (flattened()).
import contextlib
import math

import bpy

TRACK = "stirrup ride"
OWNER = "stirrup_ride"  # the custom property marking an action as a ride's (its value: the armature's name)


def track_of(arm):
    ad = arm.animation_data
    return ad.nla_tracks.get(TRACK) if ad is not None else None


def ride_action(arm):
    """The action in the ride's track, or None."""
    t = track_of(arm)
    return t.strips[0].action if t is not None and len(t.strips) else None


def _copy_track(src, dst):
    for attr in ("mute", "lock", "is_solo"):
        setattr(dst, attr, getattr(src, attr))
    for st in src.strips:
        new = dst.strips.new(st.name, int(st.frame_start), st.action)
        for attr in ("action_frame_start", "action_frame_end", "frame_start", "frame_end", "blend_type", "blend_in",
                     "blend_out", "extrapolation", "influence", "use_animated_influence", "mute", "repeat", "scale",
                     "use_reverse", "use_auto_blend", "use_sync_length"):
            try:
                setattr(new, attr, getattr(st, attr))
            except (AttributeError, TypeError, RuntimeError):
                pass


def _bottom_track(arm):
    """A new track named TRACK below her others. Blender adds a track only on top, so her tracks are made
    again above it, each strip with its settings."""
    ad = arm.animation_data
    theirs = [(t.name, t) for t in ad.nla_tracks]
    track = ad.nla_tracks.new()
    track.name = TRACK
    for name, old in theirs:
        new = ad.nla_tracks.new(prev=ad.nla_tracks[-1])
        _copy_track(old, new)
        ad.nla_tracks.remove(old)
        new.name = name
    return track


def put(arm, action, first_frame):
    """The ride's action in its track (made below her others the first time), her active action blended on
    top with Combine. Returns the action it replaced (None the first time)."""
    ad = arm.animation_data_create()
    action[OWNER] = arm.name
    track = track_of(arm)
    old = None
    if track is None:
        track = _bottom_track(arm) if len(ad.nla_tracks) else ad.nla_tracks.new()
        track.name = TRACK
    else:
        for st in list(track.strips):
            old = old or st.action
            track.strips.remove(st)
    strip = track.strips.new(TRACK, int(first_frame), action)
    strip.blend_type = "REPLACE"
    strip.extrapolation = "HOLD"
    ad.use_nla = True
    ad.action_blend_type = "COMBINE"
    if ad.action is not None and ad.action.get(OWNER):  # a ride keyed as her active action by an older add-on
        ad.action = None
    return old


def drop_if_unused(action):
    if action is not None and action.users == 0:
        bpy.data.actions.remove(action)


def layered(arm):
    """Whether the armature plays NLA tracks (beside or without an active action)."""
    ad = arm.animation_data
    return ad is not None and ad.use_nla and any(not t.mute and len(t.strips) for t in ad.nla_tracks)


@contextlib.contextmanager
def set_aside(arm):
    """Her animation off (active action and NLA), her pose as it was, for the duration; all given back."""
    ad = arm.animation_data
    saved = None
    if ad is not None:
        saved = (ad.action, ad.use_nla)
        ad.action = None
        ad.use_nla = False
    pose = [pb.matrix_basis.copy() for pb in arm.pose.bones]
    props = {(pb.name, k): pb[k] for pb in arm.pose.bones for k in pb.keys() if isinstance(pb[k], (int, float))}
    try:
        yield
    finally:
        for pb, m in zip(arm.pose.bones, pose):
            pb.matrix_basis = m
        for (b, k), v in props.items():
            arm.pose.bones[b][k] = v
        if saved is not None:
            ad.action, ad.use_nla = saved


@contextlib.contextmanager
def own_keys_aside(arm):
    """Her active action (her own keys over the ride) off for the duration: the ride's layer alone plays."""
    ad = arm.animation_data
    saved = ad.action if ad is not None else None
    if saved is not None:
        ad.action = None
    try:
        yield
    finally:
        if saved is not None:
            ad.action = saved


def _channels(arm):
    """Every (data path, index) any action of the stack keys, in a stable order."""
    ad = arm.animation_data
    actions = [ad.action] if ad.action is not None else []
    actions += [st.action for t in ad.nla_tracks if not t.mute for st in t.strips if st.action is not None]
    seen = {}
    for a in actions:
        for fc in a.fcurves:
            seen.setdefault((fc.data_path, fc.array_index), fc.group.name if fc.group else "")
    return seen


def stack_frames(arm):
    """The frames the armature's stack covers: from the first of its strips and active action to the last."""
    ad = arm.animation_data
    ranges = [tuple(ad.action.frame_range)] if ad.action is not None else []
    ranges += [(st.frame_start, st.frame_end) for t in ad.nla_tracks if not t.mute for st in t.strips]
    return list(range(int(math.floor(min(r[0] for r in ranges))), int(math.ceil(max(r[1] for r in ranges))) + 1))


@contextlib.contextmanager
def flattened(context, arm):
    """For the duration, the armature plays one temporary action holding its whole stack as Blender blends
    it, keyed at every frame the stack covers (as the exporter samples an action: over its own frames), with
    the NLA off: what the glTF exporter can sample. Nothing happens to an armature that plays no NLA track."""
    if not layered(arm):
        yield
        return
    frames = stack_frames(arm)
    ad = arm.animation_data
    channels = _channels(arm)
    scene = context.scene
    now = scene.frame_current
    values = {c: [] for c in channels}
    for f in frames:
        scene.frame_set(f)
        for (path, index) in channels:
            try:
                v = arm.path_resolve(path)
            except ValueError:
                continue
            values[(path, index)].append(v[index] if hasattr(v, "__len__") else v)
    flat = bpy.data.actions.new(arm.name + "_stirrup_flat")
    for (path, index), group in channels.items():
        vs = values[(path, index)]
        if len(vs) != len(frames):
            continue
        fc = flat.fcurves.new(path, index=index, action_group=group)
        fc.keyframe_points.add(len(frames))
        co = [x for pair in zip(frames, vs) for x in pair]
        fc.keyframe_points.foreach_set("co", co)
        fc.keyframe_points.foreach_set("interpolation", [1] * len(frames))  # LINEAR
        fc.update()
    saved = (ad.action, ad.use_nla, ad.action_blend_type)
    ad.use_nla = False
    ad.action = flat
    ad.action_blend_type = "REPLACE"
    scene.frame_set(now)
    try:
        yield
    finally:
        ad.action, ad.use_nla, ad.action_blend_type = saved
        bpy.data.actions.remove(flat)
        scene.frame_set(now)
