# glTF binaries read and written without Blender's importer: what stirrup writes (a --rider-only file) is
# read key by key, and what Blender's exporter writes is rewritten for stirrup (the shot's armatures named
# and placed in stirrup's world). glTF 2.0: a GLB is a 12-byte header, a JSON chunk and a BIN chunk.
import json
import struct

import numpy as np

_COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
_TYPES = {5126: np.float32, 5123: np.uint16, 5121: np.uint8, 5125: np.uint32, 5122: np.int16, 5120: np.int8}


class Glb:
    def __init__(self, path):
        data = open(path, "rb").read()
        if data[:4] != b"glTF":
            raise ValueError("%s: not a glTF binary" % path)
        length = struct.unpack_from("<I", data, 12)[0]
        self.path = path
        self.json = json.loads(data[20:20 + length])
        rest = 20 + length
        self.bin = data[rest + 8:rest + 8 + struct.unpack_from("<I", data, rest)[0]] if rest + 8 <= len(data) else b""

    def accessor(self, index):
        """An accessor's elements as an (count, components) float64 array (dense, no sparse: what exporters write)."""
        a = self.json["accessors"][index]
        view = self.json["bufferViews"][a["bufferView"]]
        n = _COMPONENTS[a["type"]]
        dtype = np.dtype(_TYPES[a["componentType"]])
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        stride = view.get("byteStride", 0) or n * dtype.itemsize
        raw = np.frombuffer(self.bin, dtype=np.uint8, count=stride * (a["count"] - 1) + n * dtype.itemsize, offset=start)
        rows = np.lib.stride_tricks.as_strided(raw, shape=(a["count"], n * dtype.itemsize), strides=(stride, 1))
        return np.ascontiguousarray(rows).view(dtype).reshape(a["count"], n).astype(np.float64)

    def set_accessor(self, index, values):
        """Overwrites a float accessor's elements in place with `values` (count, components)."""
        a = self.json["accessors"][index]
        if a["componentType"] != 5126 or "sparse" in a:
            raise ValueError("%s: accessor %d is not dense floats" % (self.path, index))
        view = self.json["bufferViews"][a["bufferView"]]
        n = _COMPONENTS[a["type"]]
        values = np.asarray(values, dtype=np.float32).reshape(a["count"], n)
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        stride = view.get("byteStride", 0) or 4 * n
        data = bytearray(self.bin)
        for k in range(a["count"]):
            data[start + k * stride:start + k * stride + 4 * n] = values[k].tobytes()
        self.bin = bytes(data)
        if "min" in a:
            a["min"], a["max"] = values.min(axis=0).tolist(), values.max(axis=0).tolist()

    def append_accessor(self, values, component_type, kind):
        """A new accessor holding `values` (count, components) in a buffer view of its own at the end of the
        binary chunk; returns its index."""
        dtype = np.dtype(_TYPES[component_type])
        data = np.ascontiguousarray(np.asarray(values).astype(dtype))
        self.bin += b"\0" * (-len(self.bin) % 4)
        views = self.json.setdefault("bufferViews", [])
        views.append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": data.nbytes})
        self.bin += data.tobytes()
        self.json["buffers"][0]["byteLength"] = len(self.bin)
        accessors = self.json.setdefault("accessors", [])
        a = {"bufferView": len(views) - 1, "componentType": component_type, "count": len(data), "type": kind}
        if kind in ("SCALAR", "VEC2", "VEC3", "VEC4") and component_type == 5126:
            a["min"], a["max"] = data.reshape(len(data), -1).min(axis=0).tolist(), data.reshape(len(data), -1).max(axis=0).tolist()
        accessors.append(a)
        return len(accessors) - 1

    def channels(self, node):
        """{path: output accessor} of the animation channels that key `node`."""
        out = {}
        for a in self.json.get("animations", []):
            for ch in a["channels"]:
                if ch["target"].get("node") == node:
                    out[ch["target"]["path"]] = a["samplers"][ch["sampler"]]["output"]
        return out

    def parents(self):
        parent = [-1] * len(self.json.get("nodes", []))
        for i, n in enumerate(self.json.get("nodes", [])):
            for c in n.get("children", []):
                parent[c] = i
        return parent

    def start_time(self):
        """The first key time of any animation (seconds); None without animation."""
        times = [self.json["accessors"][s["input"]].get("min", [None])[0]
                 for a in self.json.get("animations", []) for s in a["samplers"]]
        times = [t for t in times if t is not None]
        return min(times) if times else None

    def key_count(self):
        """The most keys any animation track has (a Blender export samples every track at every frame)."""
        return max([self.json["accessors"][s["input"]]["count"] for a in self.json.get("animations", []) for s in a["samplers"]] or [0])

    def scene_extras(self):
        scenes = self.json.get("scenes", [{}])
        return scenes[self.json.get("scene", 0)].get("extras", {}) if scenes else {}

    def write(self, path):
        body = json.dumps(self.json, separators=(",", ":")).encode()
        body += b" " * (-len(body) % 4)
        binary = self.bin + b"\0" * (-len(self.bin) % 4)
        out = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(body) + (8 + len(binary) if binary else 0))
        out += struct.pack("<I4s", len(body), b"JSON") + body
        if binary:
            out += struct.pack("<I4s", len(binary), b"BIN\0") + binary
        open(path, "wb").write(out)


def trs_matrices(t, r, s):
    """(n, 4, 4) matrices from n translations, rotations (x, y, z, w) and scales: T * R * S."""
    t, r, s = np.atleast_2d(t), np.atleast_2d(r), np.atleast_2d(s)
    r = r / np.linalg.norm(r, axis=1, keepdims=True)
    x, y, z, w = r[:, 0], r[:, 1], r[:, 2], r[:, 3]
    m = np.zeros((len(r), 4, 4))
    m[:, 0, 0] = 1 - 2 * (y * y + z * z); m[:, 0, 1] = 2 * (x * y - z * w); m[:, 0, 2] = 2 * (x * z + y * w)
    m[:, 1, 0] = 2 * (x * y + z * w); m[:, 1, 1] = 1 - 2 * (x * x + z * z); m[:, 1, 2] = 2 * (y * z - x * w)
    m[:, 2, 0] = 2 * (x * z - y * w); m[:, 2, 1] = 2 * (y * z + x * w); m[:, 2, 2] = 1 - 2 * (x * x + y * y)
    m[:, :3, :3] *= s[:, None, :]
    m[:, :3, 3] = t
    m[:, 3, 3] = 1.0
    return m


def quaternions(m):
    """Unit quaternions (x, y, z, w) of rotation matrices (n, 3, 3), each on the side of the one before."""
    out = np.empty((len(m), 4))
    for k, r in enumerate(m):
        t = np.trace(r)
        if t > 0:
            w = np.sqrt(1.0 + t) / 2
            q = [(r[2, 1] - r[1, 2]) / (4 * w), (r[0, 2] - r[2, 0]) / (4 * w), (r[1, 0] - r[0, 1]) / (4 * w), w]
        else:
            i = int(np.argmax(np.diag(r)))
            j, l = (i + 1) % 3, (i + 2) % 3
            v = np.sqrt(max(1e-12, 1.0 + r[i, i] - r[j, j] - r[l, l])) / 2
            q = [0.0, 0.0, 0.0, (r[l, j] - r[j, l]) / (4 * v)]
            q[i], q[j], q[l] = v, (r[j, i] + r[i, j]) / (4 * v), (r[l, i] + r[i, l]) / (4 * v)
        q = np.array(q) / np.linalg.norm(q)
        if k and np.dot(q, out[k - 1]) < 0:
            q = -q
        out[k] = q
    return out


def node_rest(node):
    if "matrix" in node:
        return np.array(node["matrix"], dtype=np.float64).reshape(4, 4).T  # glTF is column-major
    return trs_matrices(node.get("translation", [0, 0, 0]), node.get("rotation", [0, 0, 0, 1]), node.get("scale", [1, 1, 1]))[0]


def keyed_worlds(glb):
    """Every node's world matrix at every key of the file's animations (all keyed at the same times, as
    stirrup's bakes are): (key times, {node: (keys, 4, 4)})."""
    nodes = glb.json["nodes"]
    anims = glb.json.get("animations", [])
    times = None
    tracks = {}
    for a in anims:
        for ch in a["channels"]:
            s = a["samplers"][ch["sampler"]]
            t = glb.accessor(s["input"])[:, 0]
            if times is None:
                times = t
            elif len(t) != len(times) or np.abs(t - times).max() > 1e-6:
                raise ValueError("%s: the tracks are keyed at different times (expected one key a frame)" % glb.path)
            tracks[(ch["target"]["node"], ch["target"]["path"])] = glb.accessor(s["output"])
    if times is None:
        raise ValueError("%s: no animation" % glb.path)
    n = len(times)
    local = {}
    for i, node in enumerate(nodes):
        if "matrix" in node or not any((i, p) in tracks for p in ("translation", "rotation", "scale")):
            local[i] = np.broadcast_to(node_rest(node), (n, 4, 4))
            continue
        t = tracks.get((i, "translation"), np.tile(node.get("translation", [0, 0, 0]), (n, 1)))
        r = tracks.get((i, "rotation"), np.tile(node.get("rotation", [0, 0, 0, 1]), (n, 1)))
        s = tracks.get((i, "scale"), np.tile(node.get("scale", [1, 1, 1]), (n, 1)))
        local[i] = trs_matrices(t, r, s)
    parent = glb.parents()
    world = {}

    def world_of(i):
        if i not in world:
            world[i] = local[i] if parent[i] < 0 else world_of(parent[i]) @ local[i]
        return world[i]
    for i in range(len(nodes)):
        world_of(i)
    return times, world


def inverse_binds(glb, skin=0):
    """{joint name: inverse bind matrix} of a skin."""
    s = glb.json["skins"][skin]
    nodes = glb.json["nodes"]
    if "inverseBindMatrices" not in s:
        return {nodes[j]["name"]: np.eye(4) for j in s["joints"]}
    ibm = glb.accessor(s["inverseBindMatrices"]).reshape(-1, 4, 4).transpose(0, 2, 1)  # column-major
    return {nodes[j]["name"]: ibm[k] for k, j in enumerate(s["joints"])}


def static_world(glb, node):
    """A node's world matrix as the file stands it without its animation (its own and its parents' rest)."""
    nodes = glb.json["nodes"]
    parent = glb.parents()
    m = node_rest(nodes[node])
    i = parent[node]
    while i >= 0:
        m = node_rest(nodes[i]) @ m
        i = parent[i]
    return m


def armature_world(glb, name):
    """The static world (glTF) of the armature node named `name` as Blender's exporter wrote it: the node its
    skin's top joint hangs from. Its skin's inverse binds are the joints' rest under it, so this, not the
    object's matrix at the current frame (an object keyed to travel has moved), is where the armature stood
    for the file's bind."""
    nodes = glb.json["nodes"]
    parent = glb.parents()
    for skin in glb.json.get("skins", []):
        joints = set(skin["joints"])
        for j in skin["joints"]:
            a = parent[j]
            if j in joints and a not in joints and a >= 0 and nodes[a].get("name") == name:
                return static_world(glb, a)
    raise ValueError("%s: no armature node named %s above a skin" % (glb.path, name))
