# The tack in Blender (docs/blender.md, "The tack"): the saddle she sits on, the stirrups her feet are in and
# the reins in her hands, brought by Ride from stirrup's full bake of the shot into a collection of their own,
# "stirrup tack", replaced on each Ride and left alone when the horse has tack of its own.
#
# The bake (rig/io/gltf_bake.h) writes each part of the tack stirrup fits to a horse as a mesh of its own
# (extras "stirrup_tack": the part), skinned by the horse's skin: to the horse's own joints (the bridle on the
# head) and to the tack's points, joints the rig adds under them ("saddle" on the back, and "lStirrup",
# "rStirrup", "lRein", "rRein" under it, which stirrup moves to her feet and hands). Here the parts become
# meshes skinned to an armature of their own, "stirrup tack rig", whose bones are those joints: a bone for a
# joint of the horse copies the horse's bone (Copy Transforms: what hangs from it moves with the horse as
# Blender plays it), a tack point hangs from its parent as the bake keys it, frame by frame, in the ride's NLA
# layer (so the animator can key over it: the reins' slack); Live moves the tack points with her.
#
# Spaces: the bake is in stirrup's world (cm); the horse's file is its mapping H away (stirrup = H file);
# Blender's world is the file's through G (file = G blender). A point p of the bake's bind is G^-1 H^-1 p in
# Blender's world, and a bake deformation D (cm to cm) is G^-1 H^-1 D H G there.
import bpy
import numpy as np
from mathutils import Matrix

from . import gltf_files, layer, program, transforms

COLLECTION = "stirrup tack"
RIG = "stirrup tack rig"
MARK = "stirrup_tack"  # custom property on what Ride made: the collection (the horse's name), the rig, each part
FITS = "stirrup_fits"  # custom property on each part: the horse it fits
ROLE = "stirrup_role"  # custom property on each tack point's bone: its role (saddle, lStirrup ...)
POINT_ROLES = ("saddle", "lStirrup", "rStirrup", "lRein", "rRein")  # the horse's tack roles (docs/round-trip.md)


def point_roles(rig):
    """The tack rig's points: role -> bone name."""
    return {b[ROLE]: b.name for b in rig.data.bones if ROLE in b}


class BakedTack:
    """The tack of the horse in a full bake: its parts' meshes and the joints they are skinned to."""

    def __init__(self, path, horse_node="horse"):
        self.glb = glb = gltf_files.Glb(path)
        nodes = glb.json["nodes"]
        skins = glb.json.get("skins", [])
        k = [i for i, s in enumerate(skins) if nodes[s.get("skeleton", -1)].get("name") == horse_node]
        if not k:
            raise program.StirrupError("%s: no armature named %s" % (path, horse_node))
        self.skin = k[0]
        self.joint_nodes = skins[self.skin]["joints"]
        self.joint_names = [nodes[j]["name"] for j in self.joint_nodes]
        self.parts = [n for n in nodes if n.get("skin") == self.skin and "mesh" in n and MARK in n.get("extras", {})]
        self.points = self._points(nodes)

    def _points(self, nodes):
        """The tack points' joint names: the horse's role table's saddle, stirrup and rein joints (the bake names
        them "rig_saddle" ... on a horse with joints of those names already), else the roles' own names."""
        for n in nodes:
            extras = n.get("extras", {})
            if n.get("skin") != self.skin or MARK in extras:
                continue
            by_name, by_index = extras.get("stirrup_role_joints", {}), extras.get("stirrup_roles", {})
            names = [by_name.get(r) or (self.joint_names[by_index[r]] if isinstance(by_index.get(r), int) else None)
                     for r in POINT_ROLES]
            if all(isinstance(x, str) and x in self.joint_names for x in names):
                return tuple(names)
        return POINT_ROLES

    def primitives(self, node):
        """A part's primitives: [(positions (n, 3) cm, triangles (m, 3), joints (n, 4), weights (n, 4), base
        colour (4,))]."""
        glb = self.glb
        out = []
        for prim in glb.json["meshes"][node["mesh"]]["primitives"]:
            a = prim["attributes"]
            mat = glb.json.get("materials", [])[prim["material"]] if "material" in prim else {}
            colour = mat.get("pbrMetallicRoughness", {}).get("baseColorFactor", [0.8, 0.8, 0.8, 1.0])
            out.append((glb.accessor(a["POSITION"]), glb.accessor(prim["indices"]).astype(np.int64).reshape(-1, 3),
                        glb.accessor(a["JOINTS_0"]).astype(np.int64), glb.accessor(a["WEIGHTS_0"]), colour))
        return out

    def used_joints(self):
        """The joints any part weights, and every one's parents up to the first joint of the horse's own."""
        used = set()
        for node in self.parts:
            for _, _, joints, weights, _ in self.primitives(node):
                used.update(int(j) for j in np.unique(joints[weights > 0.0]))
        parents = self.glb.parents()
        index = {j: k for k, j in enumerate(self.joint_nodes)}
        out = set()
        for k in used:
            while k is not None and k not in out:
                out.add(k)
                k = index.get(parents[self.joint_nodes[k]]) if self.joint_names[k] in self.points else None
        return sorted(out)


class Fitted:
    """A bake's tack placed in Blender's world for a horse: its bones (rest in Blender's world), and the
    bake's deformations taken there."""

    def __init__(self, baked, horse, horse_at_export, h):
        self.baked, self.horse = baked, horse
        self.to_blender = transforms.G_INV @ np.linalg.inv(h)  # a bake point (cm) into Blender's world
        self.from_blender = np.linalg.inv(self.to_blender)
        self.ibm = gltf_files.inverse_binds(baked.glb, baked.skin)
        parents = baked.glb.parents()
        index = {j: k for k, j in enumerate(baked.joint_nodes)}
        self.bones = []  # (name, parent name or None, follows the horse's bone of that name, rest (4, 4))
        for k in baked.used_joints():
            name = baked.joint_names[k]
            p = index.get(parents[baked.joint_nodes[k]])
            follows = name not in baked.points
            if follows and name not in horse.data.bones:
                raise program.StirrupError("the tack hangs from %s, which is no bone of the horse, %s (was it renamed since "
                                           "it was mapped?)" % (name, horse.name))
            if follows:  # the horse's bone where it stood for the export, which is the bake's bind of that joint
                rest = transforms.np_matrix(horse_at_export) @ transforms.np_matrix(horse.data.bones[name].matrix_local)
            else:  # a tack point: at its bind place, in Blender's axes
                rest = np.eye(4)
                rest[:3, 3] = self.point(np.linalg.inv(self.ibm[name])[:3, 3])
            self.bones.append((name, baked.joint_names[p] if p is not None and not follows else None, follows, rest))
        self.names = [b[0] for b in self.bones]

    def point(self, p_cm):
        return (self.to_blender @ np.append(p_cm, 1.0))[:3]

    def deformations(self, worlds, keys=slice(None)):
        """(keys, bones, 4, 4) in Blender's world from the bake's joint worlds (metres under the centimetre
        root: S W IBM takes the bind, cm, to the pose, cm)."""
        s = np.diag([100.0, 100.0, 100.0, 1.0])
        out = []
        for name in self.names:
            w = worlds[self.baked.joint_nodes[self.baked.joint_names.index(name)]][keys]
            out.append(self.to_blender @ s @ w @ self.ibm[name] @ self.from_blender)
        return np.stack(out, axis=1)


def find(scene):
    """The tack collection Ride made (found by its mark, whatever it is named now), or None."""
    for c in scene.collection.children_recursive:
        if c.get(MARK):
            return c
    return None


def rig_of(scene):
    """The tack's rig for Check and Review movie: None without tack; refused in one line when the collection
    Ride made was emptied of it."""
    c = find(scene)
    if c is None:
        return None
    rigs = [o for o in c.objects if o.get(MARK) == "rig" and o.type == "ARMATURE"]
    if not rigs:
        raise program.StirrupError("the tack's collection \"%s\" holds no tack rig (emptied?): ride again for new tack after "
                                   "deleting the collection" % c.name)
    return rigs[0]


def rig_of_quietly(scene):
    """The tack's rig, or None (an emptied collection too)."""
    c = find(scene)
    rigs = [o for o in c.objects if o.get(MARK) == "rig"] if c is not None else []
    return rigs[0] if rigs else None


def check_replaceable(scene):
    """Ride replaces the tack it made: refused in one line when its collection was renamed or emptied (the
    animator's, then: she deletes it, or names it back, to ride again)."""
    c = find(scene)
    if c is None:
        return
    if c.name != COLLECTION:
        raise program.StirrupError("the tack's collection was renamed \"%s\": Ride replaces the tack it made; rename it "
                                   "\"%s\" again, or delete it, and ride again" % (c.name, COLLECTION))
    if not any(o.get(MARK) == "rig" for o in c.objects):
        raise program.StirrupError("the tack's collection \"%s\" is empty of its tack: delete it and ride again for new tack" % c.name)


def remove(collection):
    """The collection and everything Ride put in it: its objects, their meshes, armature, actions, materials."""
    for obj in list(collection.objects):
        data = obj.data
        actions = []
        if obj.animation_data:
            actions = [obj.animation_data.action] + [st.action for t in obj.animation_data.nla_tracks for st in t.strips]
        bpy.data.objects.remove(obj)
        if data is not None and data.users == 0:
            (bpy.data.meshes if isinstance(data, bpy.types.Mesh) else bpy.data.armatures).remove(data)
        for a in actions:
            layer.drop_if_unused(a)
    for m in [m for m in bpy.data.materials if m.get(MARK) and m.users == 0]:
        bpy.data.materials.remove(m)
    bpy.data.collections.remove(collection)


def build_rig(context, fitted, collection):
    """The tack's armature: a bone for each joint the parts weight, at its rest; a bone of the horse's copies
    the horse's bone."""
    data = bpy.data.armatures.new(RIG)
    rig = bpy.data.objects.new(RIG, data)
    rig[MARK] = "rig"
    collection.objects.link(rig)
    view_layer = context.view_layer
    was = view_layer.objects.active
    view_layer.objects.active = rig
    bpy.ops.object.mode_set(mode="EDIT")
    for name, _, _, rest in fitted.bones:
        eb = data.edit_bones.new(name)
        eb.head, eb.tail = (0.0, 0.0, 0.0), (0.0, 0.05, 0.0)
        eb.matrix = Matrix(rest.tolist())
    for name, parent, _, _ in fitted.bones:
        if parent is not None:
            data.edit_bones[name].parent = data.edit_bones[parent]
    bpy.ops.object.mode_set(mode="OBJECT")
    view_layer.objects.active = was
    for name, _, follows, _ in fitted.bones:
        if not follows:  # the role it plays, for the shot Check exports (export.shot)
            data.bones[name][ROLE] = POINT_ROLES[fitted.baked.points.index(name)]
        if follows:
            c = rig.pose.bones[name].constraints.new("COPY_TRANSFORMS")
            c.name = "follow the horse"
            c.target, c.subtarget = fitted.horse, name
    data.display_type = "STICK"
    return rig


def _material(colour, part):
    m = bpy.data.materials.new("stirrup %s" % part)
    m[MARK] = part
    m.diffuse_color = colour
    m.use_nodes = True
    bsdf = m.node_tree.nodes.get("Principled BSDF")
    if bsdf is not None:
        bsdf.inputs["Base Color"].default_value = colour
        bsdf.inputs["Roughness"].default_value = 0.35 if part in ("bit", "stirrup iron.L", "stirrup iron.R") else 0.7
        bsdf.inputs["Metallic"].default_value = 1.0 if part in ("bit", "stirrup iron.L", "stirrup iron.R") else 0.0
    return m


def build_part(fitted, node, rig, collection):
    """One part as a mesh skinned to the tack's rig: its vertices in Blender's world at the bake's bind, a
    vertex group a joint, a material a primitive."""
    baked = fitted.baked
    part = node["extras"][MARK]
    verts, faces, groups, mats, mat_of_face = [], [], {}, [], []
    for positions, tris, joints, weights, colour in baked.primitives(node):
        base = len(verts)
        verts += [fitted.point(p) for p in positions]
        faces += (tris + base).tolist()
        mats.append(_material(colour, part))
        mat_of_face += [len(mats) - 1] * len(tris)
        for v in range(len(positions)):
            for j, w in zip(joints[v], weights[v]):
                if w > 0.0:
                    groups.setdefault(baked.joint_names[int(j)], []).append((base + v, float(w)))
    mesh = bpy.data.meshes.new(node.get("name", part))
    mesh.from_pydata([tuple(v) for v in verts], [], faces)
    for m in mats:
        mesh.materials.append(m)
    mesh.polygons.foreach_set("material_index", mat_of_face)
    mesh.polygons.foreach_set("use_smooth", [True] * len(faces))
    obj = bpy.data.objects.new(part, mesh)
    obj[MARK] = part
    obj[FITS] = fitted.horse.name  # the Blender horse (the bake's extras name its armature there, "horse")
    collection.objects.link(obj)
    for name, vw in groups.items():
        g = obj.vertex_groups.new(name=name)
        for v, w in vw:
            g.add([v], w, "REPLACE")
    obj.parent = rig
    obj.modifiers.new("stirrup tack rig", "ARMATURE").object = rig
    return obj


def key_rig(rig, fitted, worlds, frames, name):
    """The tack points keyed at Blender's `frames` as the bake poses them (the bones that copy the horse's are
    posed by their constraint), in an action for the ride's layer."""
    d = fitted.deformations(worlds)  # (keys, bones, 4, 4)
    rest = np.stack([b[3] for b in fitted.bones])
    pose = d @ rest  # each bone's pose matrix (the rig object stands at the world's origin)
    parent = [fitted.names.index(b[1]) if b[1] is not None else -1 for b in fitted.bones]
    points = [k for k, b in enumerate(fitted.bones) if not b[2]]
    bases = []
    for k in points:
        p = parent[k]
        if p < 0:
            bases.append(np.linalg.inv(rest[k]) @ pose[:, k])
        else:  # Blender's parent relation: pose = pose_parent (rest_parent^-1 rest) basis
            bases.append(np.linalg.inv(np.linalg.inv(rest[p]) @ rest[k]) @ np.linalg.inv(pose[:, p]) @ pose[:, k])
    names = [fitted.names[k] for k in points]
    # (the bake's float32 leaves a rigid point a few micrometres from rest: not a key's worth)
    return transforms.key_action(rig, name, frames, names, np.stack(bases, axis=1), skip_rest=True, rest_atol=1e-5)


def prepare(shot_file, horse, horse_at_export, h):
    """The tack a full bake fits to the horse, placed for Blender (nothing in the scene changes yet), or None
    when the bake adds none (the horse has tack of its own)."""
    baked = BakedTack(shot_file)
    if not baked.parts:
        return None
    fitted = Fitted(baked, horse, horse_at_export, h)
    fitted.worlds = gltf_files.keyed_worlds(baked.glb)[1]
    return fitted


def bring(context, fitted, frames):
    """The prepared tack into the collection "stirrup tack" (the one Ride made before, found by its mark,
    replaced), its points keyed at Blender's `frames`; with no tack (None) the old collection is removed.
    Returns the collection, or None."""
    old = find(context.scene)
    if old is not None:
        remove(old)
    if fitted is None:
        return None
    collection = _collection(context.scene, fitted.horse)
    rig = build_rig(context, fitted, collection)
    for node in fitted.baked.parts:
        build_part(fitted, node, rig, collection)
    action = key_rig(rig, fitted, fitted.worlds, frames, "%s_stirrup_ride" % RIG)
    layer.put(rig, action, frames[0])
    return collection


def _collection(scene, horse):
    c = bpy.data.collections.new(COLLECTION)
    c[MARK] = horse.name
    scene.collection.children.link(c)
    return c
