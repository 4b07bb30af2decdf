# A rider's controls keyed so that her deform bones, evaluated with every constraint of her rig, land where
# stirrup puts them (docs/blender.md, "Riding a Rigify rig").
#
# stirrup hands over a pose for each deform bone (transforms.Poser: the pose matrix, armature space, that
# deforms her body as stirrup's skin does). A control rig does not let those be keyed: a rig Rigify generated
# drives its DEF- bones from its ORG- and control bones through constraints. So each control is given a
# target worked out from the deform bones' targets (a Plan), and the controls are solved to their targets:
#
#   follow  the control moves with a deform bone as it stood at rest: target = T[def] L[def]^-1 L[ctrl]
#           (Rigify's FK controls, IK hand and foot, torso, chest, neck, head, shoulders: each a copy of an ORG
#           bone, which its DEF bone copies; "convert_pose_matrix_via_rest_delta" in Rigify's snapping)
#   twist   an IK chain's base: its rest carried by the turn that takes the limb's plane at rest (hip, knee,
#           ankle) to its plane in the pose. With the goal in that plane, Blender's IK bends the chain only in
#           it, so the knee lands in the plane (Rigify's ik2fk snap searches the same angle numerically:
#           correct_rotation)
#   pole    an IK pole: its rest head carried by the same turn, its rotation left at rest (Rigify's
#           match_pole_target places it in the plane too)
#   set     a custom property keyed to a value (Rigify's IK_FK switch: 0 IK, 1 FK)
#
# Solving: a control's pose depends on its parent, which in Rigify is a mechanism bone driven by other
# controls. Every control is held at its target for one evaluation by a temporary Copy Transforms to a
# helper armature posed at the targets; Blender then evaluates each parent as it will be, and each
# control's own values are its target taken into its parent's space (Object.convert_space, POSE to LOCAL:
# Blender's visual keying). Rigify's IK chain bones scale by up to 2 % under IK stretch; as Rigify's
# correct_scale does, the twist base is scaled until its IK result has the scale of the pose (1).
import json

import bpy
import numpy as np
from mathutils import Matrix

from . import program, transforms

SOLVE_CONSTRAINT = "stirrup solve"
HELPER = "stirrup solve targets"
SCALE_TOLERANCE = 1e-5  # the IK base's result scale within this of 1 (Rigify's correct_scale stops at 1 %)
SCALE_PASSES = 6

RIGIFY_HUMAN_BONES = ("torso", "hips", "chest", "neck", "head", "foot_ik.L", "foot_ik.R", "hand_ik.L", "hand_ik.R",
                      "thigh_parent.L", "thigh_parent.R", "upper_arm_parent.L", "upper_arm_parent.R")
LIMBS = (  # (switch bone, IK base, pole, IK end, FK chain controls, deform bones upper/lower/end, tail (toe))
    ("thigh_parent", "thigh_ik", "thigh_ik_target", "foot_ik", ("thigh_fk", "shin_fk", "foot_fk"), ("thigh", "shin", "foot"), "toe"),
    ("upper_arm_parent", "upper_arm_ik", "upper_arm_ik_target", "hand_ik", ("upper_arm_fk", "forearm_fk", "hand_fk"),
     ("upper_arm", "forearm", "hand"), None),
)


class Plan:
    """What to key on a control rig, and how each control's target comes from the deform bones' targets."""

    def __init__(self, kind):
        self.kind = kind
        self.follow = {}  # control -> deform bone
        self.twist = {}  # control -> (upper, lower, end) deform bones
        self.pole = {}  # control -> (upper, lower, end) deform bones
        self.set = {}  # (bone, property) -> value

    def controls(self):
        return list(self.follow) + list(self.twist) + list(self.pole)

    def deform_bones(self):
        out = set(self.follow.values())
        for chain in list(self.twist.values()) + list(self.pole.values()):
            out.update(chain)
        return out

    def describe(self):
        return "%d controls of %s" % (len(self.controls()), self.kind)


def _side(name, s):
    return "%s.%s" % (name, s)


def is_rigify_like(arm):
    """Whether the armature has the controls of the human Rigify generates (torso, hips, IK feet...)."""
    return all(n in arm.data.bones for n in RIGIFY_HUMAN_BONES)


def rigify_human_plan(arm, limbs="IK"):
    """The plan for a human Rigify generated (rigs.spines.basic_spine, super_head, limbs.leg/arm, super_copy
    shoulders; Blender 3.4's Rigify and later): the torso moving with her pelvis, the hips left to it, the
    chest with her chest, the spine's FK controls taking the bend between, the neck and head controls theirs,
    the limbs in IK (the feet and hands on their IK controls, the knee and elbow by the IK base's twist or the
    pole, whichever the rig's pole_vector switch says, heel and spin controls left at rest) or in FK; the
    switch keyed to the mode. Fingers and face are left as they are."""
    bones = arm.data.bones
    pb = arm.pose.bones
    plan = Plan("Rigify's human rig (%s limbs)" % limbs)

    def follow(ctrl, deform):
        if ctrl in bones and deform in bones:
            plan.follow[ctrl] = deform

    follow("torso", "DEF-spine")
    follow("hips", "DEF-spine")
    follow("chest", "DEF-spine.003")
    for k in range(4):
        suffix = "" if k == 0 else ".%03d" % k
        follow("spine_fk" + suffix, "DEF-spine" + suffix)
    follow("neck", "DEF-spine.004")
    follow("head", "DEF-spine.006")
    for s in ("L", "R"):
        follow(_side("shoulder", s), _side("DEF-shoulder", s))
        for switch, base, pole, end, fk, deform, tail in LIMBS:
            chain = tuple(_side("DEF-" + d, s) for d in deform)
            plan.set[(_side(switch, s), "IK_FK")] = 0.0 if limbs == "IK" else 1.0
            tail_def = _side("DEF-" + tail, s) if tail else None
            if limbs == "FK":
                for ctrl, d in zip(fk, chain):
                    follow(_side(ctrl, s), d)
                if tail:  # Rigify 3.0 and later: toe_fk / toe_ik; before: one toe control
                    follow(_side(tail + "_fk", s) if _side(tail + "_fk", s) in bones else _side(tail, s), tail_def)
                continue
            follow(_side(end, s), chain[2])
            if tail:
                follow(_side(tail + "_ik", s) if _side(tail + "_ik", s) in bones else _side(tail, s), tail_def)
            # The IK base keyed in both modes: its twist holds the knee's plane without a pole; with one (the
            # rig's pole_vector switch) the pole does, and the base is keyed for the scale that keeps the
            # chain its length (Rigify's ik2fk: correct_scale after match_pole_target).
            plan.twist[_side(base, s)] = chain
            if pb[_side(switch, s)].get("pole_vector", 0):
                plan.pole[_side(pole, s)] = chain
    return plan


def mapping_plan(arm, text):
    """A plan named in the rider mapping's controls (a JSON object, docs/blender.md, "Other control rigs"):
    {"follow": {CONTROL: DEFORM_BONE}, "twist": {CONTROL: [UPPER, LOWER, END]}, "pole": {CONTROL: [...]},
    "set": {"BONE[\\"PROPERTY\\"]": VALUE}}."""
    try:
        data = json.loads(text)
    except ValueError as e:
        raise program.StirrupError("the rider mapping's controls: not JSON (%s)" % e)
    if not isinstance(data, dict):
        raise program.StirrupError("the rider mapping's controls: expected a JSON object with follow, twist, pole, set")
    unknown = sorted(set(data) - {"follow", "twist", "pole", "set"})
    if unknown:
        raise program.StirrupError("the rider mapping's controls: unknown field %s (expected follow, twist, pole, set)" % unknown[0])
    plan = Plan("her rig (named in the rider mapping)")
    bones = arm.data.bones

    def bone(name, what):
        if not isinstance(name, str) or name not in bones:
            raise program.StirrupError("the rider mapping's controls: %s %r is not a bone of %s" % (what, name, arm.name))
        return name

    for ctrl, d in data.get("follow", {}).items():
        plan.follow[bone(ctrl, "follow")] = bone(d, "follow %s:" % ctrl)
    for field in ("twist", "pole"):
        for ctrl, chain in data.get(field, {}).items():
            if not isinstance(chain, list) or len(chain) != 3:
                raise program.StirrupError("the rider mapping's controls: %s %s: expected [upper, lower, end] deform bones" % (field, ctrl))
            getattr(plan, field)[bone(ctrl, field)] = tuple(bone(d, "%s %s:" % (field, ctrl)) for d in chain)
    for path, value in data.get("set", {}).items():
        b, _, prop = path.partition("[")
        prop = prop.rstrip("]").strip("\"'")
        if not prop or not isinstance(value, (int, float)):
            raise program.StirrupError("the rider mapping's controls: set %s: expected BONE[\"PROPERTY\"]: NUMBER" % path)
        plan.set[(bone(b, "set"), prop)] = float(value)
    if not plan.controls():
        raise program.StirrupError("the rider mapping's controls name no control to key")
    return plan


def _constraint_driven(arm, names):
    return [n for n in names if any(c.influence > 0 and not c.mute for c in arm.pose.bones[n].constraints)]


def plan_for(arm, limbs="IK", controls_text=""):
    """The plan for riding `arm`: None when her deform bones are her own to key (a skeleton imported from
    glTF or FBX, a meta-rig); else the plan for her controls. Refuses, in one line, a rig it cannot key."""
    deform = [b.name for b in arm.data.bones if b.use_deform]
    if controls_text.strip():
        return mapping_plan(arm, controls_text)
    if is_rigify_like(arm):
        if arm.data.get("rig_id") is None:
            raise program.StirrupError("the rider, %s, has the controls of a rig Rigify generated (torso, foot_ik.L, ...) but no "
                                       "rig_id: regenerate it with Rigify, or name her controls in the rider mapping" % arm.name)
        # (Rigify drives some constraints' mute itself, the IK with and without a pole: those do not count)
        driven = {fc.data_path for fc in arm.animation_data.drivers} if arm.animation_data else set()
        cons = [c for pb in arm.pose.bones for c in pb.constraints if c.path_from_id("mute") not in driven]
        if cons and all(c.mute for c in cons):
            raise program.StirrupError("the rider, %s, is a Rigify rig with every constraint muted: its controls move nothing "
                                       "(unmute them and ride again)" % arm.name)
        freed = [n for n in deform if arm.pose.bones[n].constraints and all(c.mute for c in arm.pose.bones[n].constraints)]
        if freed:
            raise program.StirrupError("the rider, %s, is a Rigify rig whose deform bones' constraints are muted (%s%s): Ride keys "
                                       "her controls, which move those bones only through them; unmute them and ride again" %
                                       (arm.name, ", ".join(freed[:3]), ", ... %d in all" % len(freed) if len(freed) > 3 else ""))
        return rigify_human_plan(arm, limbs)
    driven = _constraint_driven(arm, deform)
    if driven:
        raise program.StirrupError("the rider, %s, has deform bones driven by constraints Ride cannot key through (%s%s): name "
                                   "her controls in the rider mapping (docs/blender.md, \"Other control rigs\")" %
                                   (arm.name, ", ".join(driven[:3]), ", ... %d in all" % len(driven) if len(driven) > 3 else ""))
    return None


def _plane_frame(h, k, a, sign):
    """A frame at h: Y along h->k, X the normal of the plane (h, k, a) times sign."""
    y = (k - h) / np.linalg.norm(k - h)
    n = np.cross(k - h, a - h)
    n = n / np.linalg.norm(n)
    x = sign * n
    f = np.eye(4)
    f[:3, 0], f[:3, 1], f[:3, 2], f[:3, 3] = x, y, np.cross(x, y), h
    return f


class Solver:
    """Solves a plan's controls on `arm` to targets worked out from deform bones' targets (pose matrices,
    armature space). Holds the helper armature and the temporary constraints until close()."""

    def __init__(self, arm, plan):
        self.arm, self.plan = arm, plan
        self.rest = {b.name: transforms.np_matrix(b.matrix_local) for b in arm.data.bones}
        self.names = plan.controls()
        self.index = {n: i for i, n in enumerate(self.names)}
        self.plane_rest = {}
        for ctrl, chain in list(plan.twist.items()) + list(plan.pole.items()):
            heads = [self.rest[d][:3, 3] for d in chain]
            # the sign that makes the frame's X the control's X at rest (the knee's hinge axis)
            sign = 1.0 if np.dot(np.cross(heads[1] - heads[0], heads[2] - heads[0]), self.rest[ctrl][:3, 0]) >= 0 else -1.0
            self.plane_rest[ctrl] = (sign, np.linalg.inv(_plane_frame(*heads, sign)))
        self.helper = None
        self.constraints = []
        self.scale = {n: np.ones(3) for n in plan.twist}  # the twist bases' IK scale, carried frame to frame

    # --- targets -------------------------------------------------------------------------------------
    def targets(self, t):
        """{control: target pose matrix} for deform targets t ({deform bone: pose matrix})."""
        out = {}
        for ctrl, d in self.plan.follow.items():
            out[ctrl] = t[d] @ np.linalg.inv(self.rest[d]) @ self.rest[ctrl]
        for ctrl, chain in list(self.plan.twist.items()) + list(self.plan.pole.items()):
            sign, f0_inv = self.plane_rest[ctrl]
            turn = _plane_frame(*[t[d][:3, 3] for d in chain], sign) @ f0_inv
            if ctrl in self.plan.twist:
                out[ctrl] = turn @ self.rest[ctrl]
            else:
                m = self.rest[ctrl].copy()
                m[:3, 3] = (turn @ np.append(self.rest[ctrl][:3, 3], 1.0))[:3]
                out[ctrl] = m
        return out

    # --- the helper armature and the temporary constraints ------------------------------------------
    # They hold the controls from open() to close(): turning a constraint on and off makes Blender build
    # its dependency graph anew, which costs more than an evaluation.
    def open(self, context):
        arm = self.arm
        data = bpy.data.armatures.new(HELPER)
        helper = bpy.data.objects.new(HELPER, data)
        context.scene.collection.objects.link(helper)
        helper.matrix_world = arm.matrix_world
        view_layer = context.view_layer
        was_active = view_layer.objects.active
        view_layer.objects.active = helper
        bpy.ops.object.mode_set(mode="EDIT")
        for n in self.names:
            eb = data.edit_bones.new(n)
            eb.head, eb.tail = (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)
            eb.matrix = Matrix(self.rest[n].tolist())
        bpy.ops.object.mode_set(mode="OBJECT")
        view_layer.objects.active = was_active
        helper.hide_render = True
        self.helper = helper
        self.helper_rest_inv = np.linalg.inv(transforms.bone_matrices(data.bones, "matrix_local"))
        self.helper_order = np.array([self.index[b.name] for b in data.bones], dtype=np.int64)
        for n in self.names:
            c = arm.pose.bones[n].constraints.new("COPY_TRANSFORMS")
            c.name = SOLVE_CONSTRAINT
            c.target, c.subtarget = helper, n
            self.constraints.append((n, c))

    def close(self):
        for n, c in self.constraints:
            pb = self.arm.pose.bones.get(n)
            if pb is not None and c.name in pb.constraints:
                pb.constraints.remove(c)
        self.constraints = []
        if self.helper is not None:
            data = self.helper.data
            bpy.data.objects.remove(self.helper)
            bpy.data.armatures.remove(data)
            self.helper = None

    def _pose_helper(self, targets):
        """The helper's bones at the targets (one foreach_set)."""
        m = np.stack([targets[self.names[i]] for i in self.helper_order])
        basis = self.helper_rest_inv @ m
        self.helper.pose.bones.foreach_set("matrix_basis", basis.transpose(0, 2, 1).astype(np.float32).ravel())
        self.helper.update_tag(refresh={"DATA"})

    # --- solving -------------------------------------------------------------------------------------
    def apply_sets(self):
        for (bone, prop), value in self.plan.set.items():
            self.arm.pose.bones[bone][prop] = value

    def hold_at(self, targets):
        """Live: the controls held at the targets by the helper's constraints, for Blender's next evaluation
        (the one that draws the frame: no evaluation of its own). Each twist base's scale is corrected from
        the IK result the last evaluation showed."""
        pbs = self.arm.pose.bones
        held = dict(targets)
        for n in self.plan.twist:
            got = np.array(pbs[n].matrix.to_scale())
            if np.all(np.abs(got - 1.0) < 0.1):  # an evaluation of the held pose (not a frame before live)
                self.scale[n] = self.scale[n] / got
            held[n] = targets[n] @ np.diag(list(self.scale[n]) + [1.0])
        self._pose_helper(held)

    def held_bases(self, context, targets):
        """Each control's own values (matrix_basis) that put it at its target, the rig evaluated once with
        every control held there: {control: Matrix}. A twist base is held at its target scaled by its scale
        from the frame before, and the scale its IK result then shows corrects that scale (as Rigify's
        correct_scale does, a pass a frame: frame to frame the scale barely changes)."""
        held = dict(targets)
        for n in self.plan.twist:
            held[n] = targets[n] @ np.diag(list(self.scale[n]) + [1.0])
        self._pose_helper(held)
        context.view_layer.update()
        pbs = self.arm.pose.bones
        for n in self.plan.twist:
            self.scale[n] = self.scale[n] / np.array(pbs[n].matrix.to_scale())
            held[n] = targets[n] @ np.diag(list(self.scale[n]) + [1.0])
        convert = self.arm.convert_space
        return {n: convert(pose_bone=pbs[n], matrix=Matrix(held[n].tolist()), from_space="POSE", to_space="LOCAL")
                for n in self.names}

    def set_bases(self, bases):
        pbs = self.arm.pose.bones
        for n, m in bases.items():
            pbs[n].matrix_basis = m

    def settle_scale(self, context, bases, passes=SCALE_PASSES):
        """Sets the bases and evaluates the rig until every twist base's IK result has scale 1 (at most
        `passes` more corrections); returns the bases as set."""
        pbs = self.arm.pose.bones
        self.set_bases(bases)
        for _ in range(passes):
            if not self.plan.twist:
                break
            context.view_layer.update()
            got = {n: np.array(pbs[n].matrix.to_scale()) for n in self.plan.twist}
            if max(float(np.abs(g - 1.0).max()) for g in got.values()) < SCALE_TOLERANCE:
                break
            for n in self.plan.twist:
                self.scale[n] = self.scale[n] / got[n]
                loc, rot, _ = bases[n].decompose()
                bases[n] = Matrix.LocRotScale(loc, rot, list(self.scale[n]))
            self.set_bases(bases)
        return bases


def deform_heads(arm, names):
    """The deform bones' heads (armature space) as Blender evaluated them: (n, 3)."""
    pbs = arm.pose.bones
    return np.array([pbs[n].head for n in names])


def clear_leftovers():
    """Removes a solve's helper and constraints left in a file (saved while Live was on): on loading a .blend."""
    for obj in [o for o in bpy.data.objects if o.name.startswith(HELPER)]:
        data = obj.data
        bpy.data.objects.remove(obj)
        if data is not None and data.users == 0:
            bpy.data.armatures.remove(data)
    for obj in bpy.data.objects:
        if obj.type == "ARMATURE" and obj.pose is not None:
            for pb in obj.pose.bones:
                for c in [c for c in pb.constraints if c.name.startswith(SOLVE_CONSTRAINT)]:
                    pb.constraints.remove(c)
