# The mapping choices: made by `stirrup character map` the first time an armature is used, kept in the
# .blend (scene.stirrup.horse_map / rider_map, editable in the panel), and written back as the mapping
# file the program reads every time. A mapping takes the exported file's glTF world to stirrup's; the
# file's world carries the armature object's transform, so when the object has moved, turned or been
# scaled since, the mapping written is the kept one moved with it (H0 G O0 O^-1 G^-1): the same bones in
# the same place in stirrup's world, the choices kept.
import json
import os

import numpy as np

from . import export, program, transforms

KINDS = ("horse", "rider")


def _object_matrix(context, obj):
    return [v for row in export.world_at_export(context, obj) for v in row]


def stored(context, mp, obj):
    """The kept mapping, for obj as it stands now: a mapping file's JSON, or None when none was made for
    this armature. The object's place is where Blender's exporter puts it (export.world_at_export: an
    object keyed to travel is compared at the same frame each time)."""
    if mp.armature != obj.name or not mp.roles:
        return None
    h0 = transforms.mapping_matrix(mp.scale_cm, mp.forward, mp.up, mp.offset_cm)
    o0 = np.array(mp.object_matrix, dtype=np.float64).reshape(4, 4)
    o1 = np.array(_object_matrix(context, obj), dtype=np.float64).reshape(4, 4)
    h1 = h0 @ transforms.G @ o0 @ np.linalg.inv(o1) @ transforms.G_INV
    parts = transforms.mapping_parts(h1)
    if parts is None:
        raise program.StirrupError("%s: the armature has been scaled unevenly or mirrored since it was mapped "
                                   "(expected a move, turn or even scale); clear its mapping to map it again" % obj.name)
    scale, forward, up, offset = parts
    return {"scale_cm": scale, "forward": forward, "up": up, "offset_cm": offset,
            "roles": {r.role: r.joint for r in mp.roles}}


def made(kind, glb, work, context):
    """`stirrup character map` on the exported file: the mapping file's JSON and what the program said."""
    out = os.path.join(work, kind + "-auto-map.json")
    _, said = program.run(["character", "map", glb, "--as", kind, "-o", out], context)
    return json.load(open(out)), said


def write(kind, data, work):
    """Writes the mapping file stirrup reads; returns its path."""
    path = os.path.join(work, kind + "-map.json")
    body = {"comment": "written by the stirrup Blender add-on from the mapping kept in the .blend", "character": kind}
    body.update({k: data[k] for k in ("scale_cm", "forward", "up", "offset_cm", "roles")})
    json.dump(body, open(path, "w"), indent=2)
    return path


def keep(context, mp, obj, data, said):
    """Keeps a mapping `character map` made for obj in the .blend."""
    mp.armature = obj.name
    mp.scale_cm = data["scale_cm"]
    mp.forward, mp.up, mp.offset_cm = data["forward"], data["up"], data["offset_cm"]
    mp.object_matrix = _object_matrix(context, obj)
    mp.report = said.strip().splitlines()[0] if said.strip() else ""
    mp.roles.clear()
    for role, joint in data["roles"].items():
        r = mp.roles.add()
        r.role, r.joint = role, joint


def to_rig(data):
    return transforms.mapping_matrix(data["scale_cm"], data["forward"], data["up"], data["offset_cm"])


def for_both(context, work, exported=None):
    """The horse's and the rider's mappings as stirrup reads them now: the kept ones moved with their
    objects, or made by `character map` on a file exported for it (`exported`: kind -> the file already
    exported at rest or keyed; else one is exported at rest). Returns (kind -> mapping JSON, kind ->
    (JSON, what character map said) for those made now, to keep once the caller has succeeded)."""
    s = context.scene.stirrup
    maps, new = {}, {}
    for kind in KINDS:
        obj = getattr(s, kind)
        data = stored(context, getattr(s, kind + "_map"), obj)
        if data is None:
            glb = (exported or {}).get(kind) or export.export(context, [obj], os.path.join(work, kind + "-rest.glb"), False)
            data, said = made(kind, glb, work, context)
            new[kind] = (data, said)
        maps[kind] = data
    return maps, new


def keep_new(context, new):
    s = context.scene.stirrup
    for kind, (data, said) in new.items():
        keep(context, getattr(s, kind + "_map"), getattr(s, kind), data, said)
