# The spaces the add-on moves between, and bones posed from stirrup's deformations.
#
# Blender's world is Z up; glTF's (every file the add-on exports or reads) is Y up: Blender's exporter
# writes (x, y, z) as (x, z, -y). A mapping (`stirrup character map`, rig/mapping/character_mapping.h) takes a
# file's glTF world to stirrup's (cm, +X the horse's travel, +Y up): its rows are forward, up and
# forward x up, times scale_cm, then offset_cm.
#
# stirrup hands a joint's pose over as a deformation D: the matrix that takes the joint's skin from its
# rest in a file's glTF world to its posed place in that world (glTF: joint world * inverse bind, which
# is what skinning multiplies a vertex by). A bone of an armature whose object stood at O0 (Blender
# world) when it was exported deforms its mesh by O (pose matrix) L^-1 O0^-1, L the bone's rest in the
# armature; so the bone's pose matrix that deforms as D does, the object now at O, is
#     P = O^-1  G^-1 D G  O0 L.
# This holds whatever axes the exporter gives the glTF joint, which is why deformations, not joint
# matrices, cross between Blender and stirrup.
import bpy
import numpy as np
from mathutils import Matrix

G = np.array([[1.0, 0, 0, 0], [0, 0, 1.0, 0], [0, -1.0, 0, 0], [0, 0, 0, 1.0]])  # Blender world -> glTF world
G_INV = G.T


def np_matrix(m):
    return np.array([list(row) for row in m], dtype=np.float64)


def mapping_matrix(scale_cm, forward, up, offset_cm):
    """A mapping's file-to-stirrup matrix (rig::mappingToRig)."""
    f = np.array(forward, dtype=np.float64)
    u = np.array(up, dtype=np.float64)
    f, u = f / np.linalg.norm(f), u / np.linalg.norm(u)
    m = np.eye(4)
    m[0, :3], m[1, :3], m[2, :3] = f, u, np.cross(f, u)
    m[:3, :3] *= scale_cm
    m[:3, 3] = offset_cm
    return m


def mapping_parts(m):
    """(scale_cm, forward, up, offset_cm) of a similarity matrix; None when it is not one (a shear, a
    mirror or a scale that differs by axis)."""
    a = m[:3, :3]
    det = np.linalg.det(a)
    if det <= 0:
        return None
    s = det ** (1.0 / 3.0)
    r = a / s
    if np.abs(r @ r.T - np.eye(3)).max() > 1e-5:
        return None
    return s, r[0].tolist(), r[1].tolist(), m[:3, 3].tolist()


def bone_matrices(collection, attr):
    """Every item's 4x4 `attr` of a bpy collection (bones, pose bones) as an (n, 4, 4) array, in one call."""
    buf = np.empty(len(collection) * 16, dtype=np.float32)
    collection.foreach_get(attr, buf)
    return buf.reshape(-1, 4, 4).transpose(0, 2, 1).astype(np.float64)  # Blender's matrices are column-major


class Poser:
    """Poses an armature's bones from deformations (glTF world, one per bone named), the armature object
    having stood at `object_at_export` (Blender world) when the files were exported. Whatever stays the
    same from frame to frame is worked out once, so a live update is a few array products."""

    def __init__(self, arm, names, object_at_export):
        index = {b.name: i for i, b in enumerate(arm.data.bones)}
        self.names = [n for n in names if n in index]
        self.index = np.array([index[n] for n in self.names], dtype=np.int64)
        rest = bone_matrices(arm.data.bones, "matrix_local")
        ls = rest[self.index]
        self.after = G @ np_matrix(object_at_export) @ ls  # G O0 L
        # Blender's parent relation (inherited rotation and scale): P = P_parent (L_parent^-1 L) basis, so
        # basis = (L_parent^-1 L)^-1 P_parent^-1 P; a root's is L^-1 P.
        mine = {n: k for k, n in enumerate(self.names)}
        self.parent, self.outside = [], []
        k_mats = []
        for k, n in enumerate(self.names):
            bone = arm.data.bones[n]
            if bone.parent is None:
                self.parent.append(-1)
                k_mats.append(np.linalg.inv(ls[k]))
                continue
            self.parent.append(mine.get(bone.parent.name, -2))
            if bone.parent.name not in mine:
                self.outside.append((k, index[bone.parent.name]))
            k_mats.append(np.linalg.inv(np.linalg.inv(rest[index[bone.parent.name]]) @ ls[k]))
        self.parent = np.array(self.parent, dtype=np.int64)
        self.k = np.array(k_mats)

    def stack(self, deformations):
        """{name: (frames, 4, 4)} -> (frames, bones, 4, 4) in this poser's order."""
        return np.stack([deformations[n] for n in self.names], axis=1)

    def pose_matrices(self, arm, d):
        """The pose matrix (armature space) of every bone (frames, bones, 4, 4) that deforms as d (frames,
        bones, 4, 4) does, the armature now where it stands."""
        return (np.linalg.inv(np_matrix(arm.matrix_world)) @ G_INV) @ d @ self.after

    def bases(self, arm, d):
        """matrix_basis of every bone (frames, bones, 4, 4) from deformations d (frames, bones, 4, 4), the
        armature now where it stands; a parent outside the bones posed as it stands now."""
        return self.bases_from_pose(arm, self.pose_matrices(arm, d))

    def bases_from_pose(self, arm, p):
        """matrix_basis of every bone (frames, bones, 4, 4) that gives it the pose matrix p (frames, bones, 4,
        4), through Blender's parent relation."""
        pp = np.broadcast_to(np.eye(4), p.shape).copy()
        has = self.parent >= 0
        pp[:, has] = p[:, self.parent[has]]
        if self.outside:
            now = bone_matrices(arm.pose.bones, "matrix")
            for k, i in self.outside:
                pp[:, k] = now[i]
        return self.k @ np.linalg.inv(pp) @ p

    def set_pose(self, arm, basis):
        """Poses the bones as `basis` (bones, 4, 4), the others as they are (no keys)."""
        all_bases = bone_matrices(arm.pose.bones, "matrix_basis")
        all_bases[self.index] = basis
        arm.pose.bones.foreach_set("matrix_basis", all_bases.transpose(0, 2, 1).astype(np.float32).ravel())
        arm.update_tag(refresh={"DATA"})  # foreach_set runs no property update: the pose must be evaluated again


def unsupported_bones(arm, names):
    """Bones whose parent relation is not the one bases() inverts (inherited rotation and full scale,
    location in the bone's own axes), or that constraints move: posing them would not show."""
    out = []
    for n in names:
        b = arm.data.bones.get(n)
        if b is None:
            continue
        if not b.use_inherit_rotation or b.inherit_scale != "FULL" or not b.use_local_location:
            out.append(n)
        elif any(c.influence > 0 and not c.mute for c in arm.pose.bones[n].constraints):
            out.append(n)
    return out


def _rotation_channels(pb, quats, prev_euler):
    """The pose bone's rotation channels for each quaternion, in its rotation mode: (data path, values per
    frame as rows)."""
    mode = pb.rotation_mode
    if mode == "QUATERNION":
        rows = []
        for q in quats:
            if rows and np.dot(rows[-1], q) < 0:
                q = -q  # the short way between keys
            rows.append(np.array(q))
        return "rotation_quaternion", rows
    if mode == "AXIS_ANGLE":
        rows = []
        for q in quats:
            axis, angle = q.to_axis_angle()
            rows.append([angle, axis.x, axis.y, axis.z])
        return "rotation_axis_angle", rows
    rows = []
    prev = prev_euler
    for q in quats:
        e = q.to_euler(mode, prev) if prev is not None else q.to_euler(mode)
        rows.append(list(e))
        prev = e
    return "rotation_euler", rows


def _at_rest(path, values, atol):
    rest = {"location": 0.0, "scale": 1.0, "rotation_euler": 0.0}
    if path == "rotation_quaternion":
        return np.allclose(values, [1.0, 0.0, 0.0, 0.0], atol=atol) or np.allclose(values, [-1.0, 0.0, 0.0, 0.0], atol=atol)
    if path == "rotation_axis_angle":
        return np.allclose(values[:, 0], 0.0, atol=atol)
    return np.allclose(values, rest[path], atol=atol)


def key_action(arm, name, frames, names, bases, skip_rest=False, rest_atol=1e-7):
    """A new action named `name` keying the bones `names` at `frames` as `bases` (frames, bones, 4, 4) has
    them: location, rotation in the bone's mode and scale, LINEAR between frames. With skip_rest, a channel
    within rest_atol of rest on every frame is not keyed (a control the ride leaves alone stays the
    animator's)."""
    action = bpy.data.actions.new(name)
    action.id_root = "OBJECT"
    frames = np.asarray(frames, dtype=np.float64)
    for k, bname in enumerate(names):
        pb = arm.pose.bones[bname]
        mats = bases[:, k]
        locs, quats, scales = [], [], []
        for m in mats:
            loc, q, sc = Matrix(m.tolist()).decompose()
            locs.append(list(loc))
            quats.append(q)
            scales.append(list(sc))
        rot_path, rots = _rotation_channels(pb, quats, None)
        base = 'pose.bones["%s"].' % bname.replace("\\", "\\\\").replace('"', '\\"')
        for path, rows in (("location", locs), (rot_path, rots), ("scale", scales)):
            values = np.asarray(rows, dtype=np.float64)
            if skip_rest and _at_rest(path, values, rest_atol):
                continue
            for i in range(values.shape[1]):
                fc = action.fcurves.new(base + path, index=i, action_group=bname)
                fc.keyframe_points.add(len(frames))
                co = np.empty(2 * len(frames))
                co[0::2], co[1::2] = frames, values[:, i]
                fc.keyframe_points.foreach_set("co", co)
                fc.keyframe_points.foreach_set("interpolation", [1] * len(frames))  # LINEAR
                fc.update()
    return action


def key_properties(action, frames, values):
    """Keys custom properties ({(bone, property): value}) at the first and last of `frames`, CONSTANT."""
    for (bone, prop), value in values.items():
        path = 'pose.bones["%s"]["%s"]' % (bone.replace('"', '\\"'), prop)
        fc = action.fcurves.new(path, index=0, action_group=bone)
        ends = [frames[0], frames[-1]] if frames[-1] != frames[0] else [frames[0]]
        fc.keyframe_points.add(len(ends))
        fc.keyframe_points.foreach_set("co", [x for f in ends for x in (f, value)])
        fc.keyframe_points.foreach_set("interpolation", [0] * len(ends))  # CONSTANT
        fc.update()
