"""ROS parameter files, read statically into per-node dotted parameter names with locations.

ROS 2 (`rcl` parameter files)::

    /ns/node:               # node key: "node", "/ns/node", "/**", "/**/node", nested "ns: node:" too
      ros__parameters:
        wheel_radius: 0.033
        linear.x.max_velocity: 1.0      # dotted keys and nested dicts both flatten to dotted names
        linear: {x: {min_velocity: -1.0}}

Node names are normalised to a leading "/" and single slashes ("/**/turtlebot3_node").

ROS 1 (`rosparam load` files) have no `ros__parameters`: each top-level key holding a mapping becomes a node
("/diffbot_controller"), top-level scalars go to the node "/". Nested mappings flatten to dotted names, so a
namespaced controller `ns: {ctrl: {type: ...}}` is node "/ns" with the parameter "ctrl.type".

Values are `Value(value, loc)`; lists are kept whole (one parameter).
"""
from __future__ import annotations

import os
import re
from collections.abc import Iterable

from urdfcheck.consumers.common import ConsumerError, Value
from urdfcheck.core.findings import Location
from urdfcheck.core.records import TYPE_CHECKING, Record

if TYPE_CHECKING:  # PyYAML is imported when a file is parsed, not with the readers (consumers/prefilter.py)
    from urdfcheck.consumers.yamlsrc import YamlDoc

ROS2_KEY = "ros__parameters"


class NodeParams(Record):
    # name: normalised: "/ns/node", "/**", "/" (ROS 1 globals)
    # loc: the node key
    _fields = ('name', 'loc', 'params', 'file')

    def __init__(self, name: str, loc: Location, params: dict[str, Value] | None = None, file: str = ""):
        self.name = name
        self.loc = loc
        self.params = {} if params is None else params
        self.file = file

    @property
    def namespace(self) -> str:
        ns = self.name.rsplit("/", 1)[0]
        return ns or "/"

    @property
    def basename(self) -> str:
        return self.name.rsplit("/", 1)[-1]

    def get(self, name: str) -> Value | None:
        return self.params.get(name)

    def value(self, name: str, default=None):
        v = self.params.get(name)
        return default if v is None else v.value

    def sub(self, prefix: str) -> dict[str, Value]:
        """Parameters under `prefix.` with the prefix removed."""
        p = prefix + "."
        return {k[len(p):]: v for k, v in self.params.items() if k.startswith(p)}


class ParamFile(Record):
    # dialect: "ros2" or "ros1" ("empty" for an empty document)
    # notes: (message, Location)
    _fields = ('path', 'dialect', 'nodes', 'doc', 'notes')

    def __init__(self, path: str,
                 dialect: str,
                 nodes: dict[str, NodeParams],
                 doc: YamlDoc | None = None,
                 notes: list | None = None):
        self.path = path
        self.dialect = dialect
        self.nodes = nodes
        self.doc = doc
        self.notes = [] if notes is None else notes

    def find_nodes(self, name: str) -> list[NodeParams]:
        """Nodes whose key applies to a node called `name` (basename or fully qualified; wildcards honoured)."""
        return [n for k, n in self.nodes.items() if node_key_matches(k, name)]


def normalise_node_name(parts: Iterable[str]) -> str:
    segs: list[str] = []
    for p in parts:
        segs.extend(s for s in str(p).split("/") if s)
    return "/" + "/".join(segs)


def _seg_match(pat: str, seg: str) -> bool:
    if "*" not in pat:
        return pat == seg
    return re.fullmatch("".join("[^/]*" if ch == "*" else re.escape(ch) for ch in pat), seg) is not None


def _segs_match(pats: list[str], segs: list[str]) -> bool:
    """rcl wildcards: `*` matches within one name token, `**` any number (also zero) of tokens."""
    if not pats:
        return not segs
    if pats[0] == "**":
        return any(_segs_match(pats[1:], segs[i:]) for i in range(len(segs) + 1))
    return bool(segs) and _seg_match(pats[0], segs[0]) and _segs_match(pats[1:], segs[1:])


def _split(name: str) -> list[str]:
    return [s for s in name.split("/") if s]


def node_key_matches(key: str, name: str) -> bool:
    """Does the parameter-file node key `key` apply to the node `name`?

    `name` may be fully qualified ("/ns/node") or a bare node name ("node"); a bare name matches any
    namespace, since the namespace a node runs in is often set by a launch file we only read partly.
    """
    kp = _split(key)
    if not name.startswith("/"):
        base = _split(name)[-1:] or [""]
        if not kp:
            return False
        if kp[-1] == "**":  # "/**" applies to every node
            return True
        return _seg_match(kp[-1], base[0])
    return _segs_match(kp, _split(name))


def _flatten(doc: YamlDoc, value, path: tuple, prefix: str, out: dict[str, Value]) -> None:
    if isinstance(value, dict) and value:
        for k, v in value.items():
            name = f"{prefix}.{k}" if prefix else str(k)
            _flatten(doc, v, path + (k,), name, out)
        return
    if prefix:
        items = tuple(doc.loc(*path, i) for i in range(len(value))) if isinstance(value, list) else ()
        out[prefix] = Value(value, doc.loc(*path), items=items)


def _find_ros2(doc: YamlDoc, value, path: tuple, nodes: dict[str, NodeParams], notes: list) -> None:
    if not isinstance(value, dict):
        return
    for k, v in value.items():
        if k == ROS2_KEY:
            name = normalise_node_name(str(p) for p in path) if path else "/"
            node = nodes.get(name)
            if node is None:
                node = nodes[name] = NodeParams(name, doc.key_loc(*path) if path else doc.loc(), file=doc.file)
            if isinstance(v, dict):
                _flatten(doc, v, path + (k,), "", node.params)
            elif v is not None:
                notes.append((f"'{ROS2_KEY}' of {name} is not a mapping", doc.loc(*path, k)))
        else:
            _find_ros2(doc, v, path + (k,), nodes, notes)


def _has_ros2_key(value, depth=0) -> bool:
    if not isinstance(value, dict) or depth > 16:
        return False
    return ROS2_KEY in value or any(_has_ros2_key(v, depth + 1) for v in value.values())


NOT_A_MAPPING = "a parameter file must be a mapping at the top level"


def foreign(path: str, error) -> bool:
    """A YAML file found in a config folder that is another tool's, not a ROS parameter file, so that failing to
    read it as one is no defect (issue 37): OpenCV's FileStorage (`%YAML:1.0`, which PyYAML refuses: camera
    calibrations, VINS configs), or a top-level sequence (ros_gz_bridge's topic list; no ROS parameter loader
    takes one). Said only of files found by their folder: a file a launch file or the model names stays C007."""
    if str(getattr(error, "message", error)).startswith(NOT_A_MAPPING):
        return True
    from urdfcheck.core.door import read_bytes

    try:
        head = read_bytes(path, limit=256)
    except OSError:
        return False
    return head.lstrip(b"\xef\xbb\xbf \t\r\n").startswith(b"%YAML:")


def params_from_doc(doc: YamlDoc) -> ParamFile:
    data = doc.data
    if data is None:
        return ParamFile(doc.file, "empty", {}, doc)
    if not isinstance(data, dict):
        raise ConsumerError(NOT_A_MAPPING, doc.loc())
    nodes: dict[str, NodeParams] = {}
    notes: list = list(doc.notes)
    if _has_ros2_key(data):
        _find_ros2(doc, data, (), nodes, notes)
        return ParamFile(doc.file, "ros2", nodes, doc, notes)
    glob = NodeParams("/", doc.loc(), file=doc.file)
    for k, v in data.items():
        if isinstance(v, dict):
            name = normalise_node_name([str(k)])
            node = nodes.setdefault(name, NodeParams(name, doc.key_loc(k), file=doc.file))
            _flatten(doc, v, (k,), "", node.params)
        else:
            items = tuple(doc.loc(k, i) for i in range(len(v))) if isinstance(v, list) else ()
            glob.params[str(k)] = Value(v, doc.loc(k), items=items)
    if glob.params:
        nodes["/"] = glob
    return ParamFile(doc.file, "ros1", nodes, doc, notes)


def read_params(path: str | os.PathLike, *, max_bytes: int | None = None) -> ParamFile:
    """Read a parameter file (at most max_bytes, default yamlsrc.MAX_BYTES). Raises ConsumerError."""
    if max_bytes is None and _AHEAD:
        got = _AHEAD[-1].get(str(path))
        if got is not None:  # parsed in the xacro worker, where PyYAML was imported already (`parse_ahead`)
            import pickle

            value = pickle.loads(got)  # a fresh copy for each reader, as a parse would give
            if isinstance(value, ConsumerError):
                raise value
            return value
    from urdfcheck.consumers.yamlsrc import MAX_BYTES, load_yaml

    if max_bytes is not None:
        return params_from_doc(load_yaml(path, max_bytes=max_bytes))
    # a run reads a package's parameter files once: two models of one config name the same controllers and
    # drivers (each model's consumers are read apart). Kept pickled: each reader gets a fresh copy, as a parse gives
    import pickle

    from urdfcheck.core.walk import run_memo

    memo = run_memo("params")
    key = str(path)
    got = memo.get(key) if memo is not None else None
    if got is None:
        try:
            value = params_from_doc(load_yaml(path, max_bytes=MAX_BYTES))
        except ConsumerError as e:
            value = e
        if memo is not None:
            try:
                memo[key] = pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
            except (pickle.PicklingError, TypeError, AttributeError, RecursionError):
                pass
    else:
        value = pickle.loads(got)
    if isinstance(value, ConsumerError):
        raise value
    return value


# --- parameter files parsed ahead, in the xacro worker ------------------------------------------------------
_AHEAD: list[dict] = []  # one store per run in progress: path (as the reader names it) -> pickled outcome


class parsed_ahead:
    """Within this block `read_params` answers from the store it yields (filled when the worker's parse arrives):
    the console then never imports PyYAML for a package's parameter files (17 ms), which the xacro worker has
    imported anyway. Outside, every read parses."""

    def __enter__(self) -> dict:
        _AHEAD.append({})
        return _AHEAD[-1]

    def __exit__(self, *exc):
        _AHEAD.pop()


def parse_ahead(paths: list[str]) -> dict:
    """In the xacro worker: each file read as `read_params` reads it, pickled ({path: bytes}); "observed": what
    was read, for the lint cache (core.observe). A file that fails otherwise than a ConsumerError is left out:
    the console reads it itself and says what went wrong."""
    import pickle

    from urdfcheck.core import observe

    out: dict = {}
    for p in paths:
        try:
            value = read_params(p)
        except ConsumerError as e:
            value = e
        except Exception:  # noqa: BLE001 - left to the console's own read
            continue
        try:
            out[p] = pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
        except Exception:  # noqa: BLE001
            continue
    return {"parsed": out, "observed": observe.take() if observe.active() else None}


def parse_params(text: str | bytes, file: str) -> ParamFile:
    from urdfcheck.consumers.yamlsrc import parse_yaml

    return params_from_doc(parse_yaml(text, file))


def merge_nodes(files: Iterable[ParamFile]) -> dict[str, NodeParams]:
    """Nodes of several files passed to the same process, in order: a later file's value wins."""
    out: dict[str, NodeParams] = {}
    for pf in files:
        for name, node in pf.nodes.items():
            cur = out.get(name)
            if cur is None:
                out[name] = NodeParams(name, node.loc, dict(node.params), node.file)
            else:
                cur.params.update(node.params)
    return out


def lookup(files: Iterable[ParamFile], key: str, node: str = "") -> Value | None:
    """Find a parameter by key path in parameter files (the last file that sets it wins).

    `key` is a dotted (or slash-separated) parameter name. With `node`, only nodes matching it are searched
    (ROS 2), or `node` is used as a key prefix (ROS 1). Without it, every node is searched and, for ROS 1,
    the key may also start with the top-level key ("diffbot_controller.wheel_radius").
    """
    key = key.strip().replace("/", ".").strip(".")
    found = None
    for pf in files:
        if pf.dialect == "ros2":
            cands = pf.find_nodes(node) if node else list(pf.nodes.values())
            for n in cands:
                if key in n.params:
                    found = n.params[key]
                    break
            continue
        full = (node.strip("/").replace("/", ".") + "." + key) if node else key
        hit = _ros1_lookup(pf, full)
        if hit is not None:
            found = hit
    return found


def _ros1_lookup(pf: ParamFile, dotted: str) -> Value | None:
    g = pf.nodes.get("/")
    if g is not None and dotted in g.params:
        return g.params[dotted]
    head, _, rest = dotted.partition(".")
    n = pf.nodes.get("/" + head)
    if n is not None and rest in n.params:
        return n.params[rest]
    return None
