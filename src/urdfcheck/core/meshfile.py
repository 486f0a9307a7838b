"""Mesh files read for their vertices and triangles (issue 41: millimetre meshes, U012; self-collision on meshes,
G006), every byte through the door.

Read: binary and ASCII STL, Wavefront OBJ (`v` and `f` lines), COLLADA (the POSITION source of each `<mesh>`, its
`<triangles>`/`<polylist>` indices, the `<node>` transforms of the scene that places it, and `<unit meter>`).
Any other format, a file larger than `MAX_BYTES`, more than `MAX_VERTICES` vertices, or a file that does not read
as its format gives None: the rules that use meshes then say nothing about it (a guess from half a mesh is worse
than none).

Coordinates are the file's, in metres as the file means them (COLLADA's unit applied), before the URDF's
`scale`. STL and OBJ carry no unit: ROS (RViz, MoveIt's geometric_shapes, Gazebo) reads their numbers as metres.
"""
from __future__ import annotations

import math
import os
import struct

from urdfcheck.core import door, lazyre

MAX_BYTES = 32 * 1024**2
MAX_VERTICES = 1_500_000  # an STL repeats each vertex per triangle: 500,000 triangles, a 25 MB binary STL
MAX_INDICES = 6_000_000  # triangle corners (OBJ faces, COLLADA <p>): 2,000,000 triangles
FORMATS = (".stl", ".obj", ".dae")
_CACHE_POINTS = 4_000_000  # vertices kept between the rules of a run (about 100 MB), oldest dropped first


class Mesh:
    """`points`: an (N, 3) float array; `triangles`: an (M, 3) array of indices into it (M may be 0);
    `lo`, `hi`: the corners of the bounding box; `up`: COLLADA's <up_axis> when it is not Z_UP (loaders
    disagree on whether to turn such a mesh: its size holds, its orientation is uncertain), else ""."""

    __slots__ = ("points", "triangles", "lo", "hi", "up")

    def __init__(self, points, triangles):
        self.points = points
        self.triangles = triangles
        self.up = ""
        self.lo = tuple(float(x) for x in points.min(axis=0))
        self.hi = tuple(float(x) for x in points.max(axis=0))

    def __len__(self) -> int:
        return len(self.points)

    def bounds(self) -> tuple[tuple[float, ...], tuple[float, ...]]:
        return self.lo, self.hi


_cache: dict[tuple, Mesh | None] = {}


def _mesh(points, triangles=None) -> Mesh | None:
    """A Mesh of flat coordinates and flat triangle indices, or None: no points, too many, not finite, or
    triangles that name points not there (then the points alone)."""
    import numpy as np

    pts = np.asarray(points, dtype=float)
    if pts.size == 0 or pts.size % 3 or pts.size > 3 * MAX_VERTICES or not np.isfinite(pts).all():
        return None
    pts = pts.reshape(-1, 3)
    tris = np.asarray(triangles if triangles is not None else (), dtype=np.int64)
    if tris.size % 3 or (tris.size and (tris.min() < 0 or tris.max() >= len(pts))):
        tris = np.zeros(0, dtype=np.int64)
    return Mesh(pts, tris.reshape(-1, 3))


def read(path) -> Mesh | None:
    """The mesh at `path`, or None (format not read, too large, malformed, refused by the door). Kept per real
    path, size and modification time: the rules of one run that read the same mesh read the file once."""
    ext = os.path.splitext(os.fspath(path))[1].lower()
    if ext not in FORMATS:
        return None
    try:
        real = door.confine(path)
        st = os.stat(real)
    except OSError:
        return None
    if st.st_size > MAX_BYTES:
        return None
    key = (real, st.st_size, st.st_mtime_ns)
    if key in _cache:
        return _cache[key]
    try:
        data = door.read_bytes(path, limit=MAX_BYTES)
    except OSError:
        return None
    try:
        mesh = _PARSERS[ext](data) if len(data) <= MAX_BYTES else None
    except (ValueError, SyntaxError, struct.error, IndexError, OverflowError, MemoryError, RecursionError):
        mesh = None  # lxml's XMLSyntaxError is a SyntaxError
    _cache[key] = mesh
    while len(_cache) > 1 and sum(len(m) for m in _cache.values() if m is not None) > _CACHE_POINTS:
        _cache.pop(next(iter(_cache)))
    return mesh


# --- STL -------------------------------------------------------------------------------------------------
_ASCII_VERTEX = lazyre.compile(rb"vertex\s+(\S+)\s+(\S+)\s+(\S+)")


def _stl(data: bytes) -> Mesh | None:
    import numpy as np

    if len(data) >= 84:
        n = struct.unpack_from("<I", data, 80)[0]
        if len(data) == 84 + 50 * n:  # binary, whatever its header says (many start with "solid")
            if 3 * n > MAX_VERTICES:
                return None
            rec = np.dtype([("normal", "<f4", 3), ("v", "<f4", 9), ("attr", "<u2")])
            return _mesh(np.frombuffer(data, dtype=rec, count=n, offset=84)["v"].ravel(), np.arange(3 * n))
    if not data.lstrip()[:5].lower() == b"solid":
        return None
    pts: list[float] = []
    for m in _ASCII_VERTEX.finditer(data):
        pts.extend(float(x) for x in m.groups())
        if len(pts) > 3 * MAX_VERTICES:
            return None
    n = len(pts) // 9
    return _mesh(pts[:9 * n], range(3 * n))


# --- OBJ -------------------------------------------------------------------------------------------------
def _obj(data: bytes) -> Mesh | None:
    pts: list[float] = []
    tris: list[int] = []
    for line in data.split(b"\n"):
        line = line.strip()
        if line.startswith(b"v "):
            xyz = line.split()[1:4]
            if len(xyz) != 3:
                return None
            pts.extend(float(x) for x in xyz)
            if len(pts) > 3 * MAX_VERTICES:
                return None
        elif line.startswith(b"f "):
            idx = []
            for tok in line.split()[1:]:
                i = int(tok.split(b"/")[0])
                idx.append(i - 1 if i > 0 else len(pts) // 3 + i)
            for k in range(1, len(idx) - 1):  # a polygon as a fan of triangles
                tris.extend((idx[0], idx[k], idx[k + 1]))
            if len(tris) > MAX_INDICES:
                return None
    return _mesh(pts, tris)


# --- COLLADA ---------------------------------------------------------------------------------------------
def _local(tag) -> str:
    return tag.rpartition("}")[2] if isinstance(tag, str) else ""


def _floats(text: str | None) -> list[float]:
    return [float(x) for x in (text or "").split()]


def _matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def _node_matrix(node) -> list[list[float]]:
    """A COLLADA <node>'s own transform: its <matrix>, <translate>, <rotate> and <scale> children in order."""
    m = [[float(i == j) for j in range(4)] for i in range(4)]
    for child in node:
        tag, v = _local(child.tag), _floats(child.text)
        if tag == "matrix" and len(v) == 16:
            t = [v[0:4], v[4:8], v[8:12], v[12:16]]
        elif tag == "translate" and len(v) == 3:
            t = [[1, 0, 0, v[0]], [0, 1, 0, v[1]], [0, 0, 1, v[2]], [0, 0, 0, 1]]
        elif tag == "scale" and len(v) == 3:
            t = [[v[0], 0, 0, 0], [0, v[1], 0, 0], [0, 0, v[2], 0], [0, 0, 0, 1]]
        elif tag == "rotate" and len(v) == 4:
            x, y, z, deg = v
            n = math.sqrt(x * x + y * y + z * z)
            if n < 1e-12:
                continue
            x, y, z = x / n, y / n, z / n
            c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
            C = 1 - c
            t = [[c + x * x * C, x * y * C - z * s, x * z * C + y * s, 0],
                 [y * x * C + z * s, c + y * y * C, y * z * C - x * s, 0],
                 [z * x * C - y * s, z * y * C + x * s, c + z * z * C, 0], [0, 0, 0, 1]]
        else:
            continue
        m = _matmul(m, t)
    return m


def _geometry(geom) -> tuple[list[float], list[int]] | None:
    """(flat points, flat triangle indices) of a COLLADA <geometry>'s <mesh>: the POSITION source of its
    <vertices>, and the VERTEX indices of its <triangles> and <polylist> (a polygon as a fan)."""
    mesh = next((c for c in geom if _local(c.tag) == "mesh"), None)
    if mesh is None:
        return None
    sources = {c.get("id"): c for c in mesh if _local(c.tag) == "source"}
    pts: list[float] = []
    verts_id = None
    for c in mesh:
        if _local(c.tag) != "vertices":
            continue
        verts_id = c.get("id")
        for inp in c:
            if _local(inp.tag) == "input" and inp.get("semantic") == "POSITION":
                src = sources.get((inp.get("source") or "").lstrip("#"))
                arr = next((x for x in src.iter() if _local(x.tag) == "float_array"), None) if src is not None else None
                if arr is not None:
                    pts = _floats(arr.text)
        break
    if not pts or len(pts) % 3:
        return None
    tris: list[int] = []
    for prim in mesh:
        kind = _local(prim.tag)
        if kind not in ("triangles", "polylist"):
            continue
        inputs = [x for x in prim if _local(x.tag) == "input"]
        stride = 1 + max((int(x.get("offset") or 0) for x in inputs), default=0)
        at = next((int(x.get("offset") or 0) for x in inputs if x.get("semantic") == "VERTEX"
                   and (x.get("source") or "").lstrip("#") == verts_id), None)
        p = next((x for x in prim if _local(x.tag) == "p"), None)
        if at is None or p is None:
            continue
        words = (p.text or "").split()
        if len(tris) + len(words) // stride > MAX_INDICES:
            raise ValueError("too many triangles")
        idx = [int(x) for x in words[at::stride]]
        if kind == "triangles":
            tris += idx[: len(idx) - len(idx) % 3]
        else:
            vcount = next((x for x in prim if _local(x.tag) == "vcount"), None)
            k = 0
            for n in (int(x) for x in (vcount.text or "").split()) if vcount is not None else ():
                poly = idx[k:k + n]
                k += n
                for j in range(1, len(poly) - 1):
                    tris += (poly[0], poly[j], poly[j + 1])
    return pts, tris


def _dae(data: bytes) -> Mesh | None:
    from urdfcheck.core import xmlfront
    from urdfcheck.core.lxmlimport import etree

    root = etree.fromstring(data, xmlfront.parser())
    unit = 1.0
    asset = next((c for c in root if _local(c.tag) == "asset"), None)
    for c in asset if asset is not None else ():
        if _local(c.tag) == "unit" and c.get("meter"):
            unit = float(c.get("meter"))
    if not (math.isfinite(unit) and unit > 0):
        return None
    up = next((c.text or "" for c in (asset if asset is not None else ()) if _local(c.tag) == "up_axis"), "")
    up = up.strip() if up.strip() not in ("", "Z_UP") else ""
    geoms = {g.get("id"): g for g in root.iter() if _local(g.tag) == "geometry"}
    placed: list[tuple[str, list]] = []  # (geometry id, 4x4 world matrix)

    def walk(node, m, depth):
        if depth > 64:
            raise ValueError("nodes nested too deep")
        m = _matmul(m, _node_matrix(node))
        for c in node:
            tag = _local(c.tag)
            if tag == "instance_geometry":
                placed.append(((c.get("url") or "").lstrip("#"), m))
            elif tag == "node":
                walk(c, m, depth + 1)

    eye = [[float(i == j) for j in range(4)] for i in range(4)]
    scenes = [s for s in root.iter() if _local(s.tag) == "visual_scene"]
    for scene in scenes[:1]:
        for node in scene:
            if _local(node.tag) == "node":
                walk(node, eye, 0)
    if not scenes:
        placed = [(gid, eye) for gid in geoms]
    import numpy as np

    parts: list = []
    tris: list = []
    count = 0
    read_geoms: dict[str, tuple | None] = {}
    for gid, m in placed:
        if gid not in geoms:
            continue
        if gid not in read_geoms:
            got = _geometry(geoms[gid])
            read_geoms[gid] = (np.asarray(got[0], dtype=float).reshape(-1, 3), got[1]) if got else None
        entry = read_geoms[gid]
        if entry is None:
            continue
        gp, gt = entry
        if count + len(gp) > MAX_VERTICES:
            return None
        rot, move = np.asarray(m, dtype=float)[:3, :3], np.asarray(m, dtype=float)[:3, 3]
        parts.append(unit * (gp @ rot.T + move))
        if gt and min(gt) >= 0 and max(gt) < len(gp):  # indices past the source: this geometry's points alone
            tris.append(np.asarray(gt, dtype=np.int64) + count)
        count += len(gp)
    if not parts:
        return None
    mesh = _mesh(np.concatenate(parts).ravel(), np.concatenate(tris) if tris else None)
    if mesh is not None:
        mesh.up = up[:16]
    return mesh


_PARSERS = {".stl": _stl, ".obj": _obj, ".dae": _dae}
