"""YAML with line numbers, for untrusted consumer files (parameter files, YAML launch files, the config).

`parse_yaml(text, file)` / `load_yaml(path)` return a `YamlDoc`: plain Python values (`doc.data`) plus the
`Location` of every key and value by key path (`doc.loc("node", "ros__parameters", "wheel_radius")`).

Safety:

* size, nesting and alias expansion are refused first by `core.yamldoor` (the one YAML door, with the
  limits stated once), so libyaml's recursive C composer is safe;
* only nodes are composed; no constructor runs on collections and no tag is honoured beyond the YAML core
  schema scalars (an unknown or `!!python/...` tag leaves the scalar as its plain text);
* aliases are expanded by our own walk, which counts every node it produces (a second bound, by the same
  `max_nodes`) and refuses documents that refer to themselves.

Every failure is a `ConsumerError(message, Location)`, never a traceback.
"""
from __future__ import annotations

import os

from urdfcheck.consumers.common import ConsumerError
from urdfcheck.consumers.yamldoc import YamlDoc
from urdfcheck.core import yamldoor
from urdfcheck.core.findings import Location
from urdfcheck.core.yamlimport import yaml

# the guards and their limits are core.yamldoor's (the one YAML door); these name the consumer defaults
MAX_BYTES = yamldoor.CONSUMER.max_bytes
MAX_NODES = yamldoor.CONSUMER.max_nodes
_MERGE_TAG = "tag:yaml.org,2002:merge"
_STR_TAG = "tag:yaml.org,2002:str"
_CORE_SCALARS = {
    "tag:yaml.org,2002:null",
    "tag:yaml.org,2002:bool",
    "tag:yaml.org,2002:int",
    "tag:yaml.org,2002:float",
    "tag:yaml.org,2002:str",
    "tag:yaml.org,2002:timestamp",
}


def _mark_loc(file: str, mark) -> Location:
    if mark is None:
        return Location(file)
    return Location(file, mark.line + 1, mark.column + 1)


class _Builder:
    def __init__(self, file: str, max_nodes: int):
        self.file = file
        self.max_nodes = max_nodes
        self.count = 0
        self.value_locs: dict = {}
        self.key_locs: dict = {}
        self.notes: list = []
        self._ctor = yaml.constructor.SafeConstructor()
        self._stack: set[int] = set()

    def _tick(self, node) -> None:
        self.count += 1
        if self.count > self.max_nodes:
            raise ConsumerError(
                f"YAML expands to more than {self.max_nodes} nodes (alias bomb?); refused",
                _mark_loc(self.file, node.start_mark),
            )

    def scalar(self, node: yaml.ScalarNode):
        if node.tag in _CORE_SCALARS:
            try:
                return self._ctor.construct_scalar(node) if node.tag == _STR_TAG else self._construct(node)
            except Exception:  # noqa: BLE001 - odd scalar (bad timestamp...): keep the text
                return node.value
        return node.value  # unknown / non-core tag: plain text, never executed

    def _construct(self, node):
        value = self._ctor.construct_object(node, deep=False)
        if node.tag == "tag:yaml.org,2002:timestamp":
            return node.value  # keep the text; a datetime is no use to us
        return value

    def build(self, node, path: tuple, depth: int = 0):
        self._tick(node)
        if depth > yamldoor.MAX_DEPTH:
            raise ConsumerError(f"YAML nested deeper than {yamldoor.MAX_DEPTH} levels; refused",
                                _mark_loc(self.file, node.start_mark))
        self.value_locs[path] = _mark_loc(self.file, node.start_mark)
        if isinstance(node, yaml.ScalarNode):
            return self.scalar(node)
        key = id(node)
        if key in self._stack:
            raise ConsumerError("YAML alias refers to itself (recursive structure); refused",
                                _mark_loc(self.file, node.start_mark))
        self._stack.add(key)
        try:
            if isinstance(node, yaml.SequenceNode):
                return [self.build(item, path + (i,), depth + 1) for i, item in enumerate(node.value)]
            if isinstance(node, yaml.MappingNode):
                return self.mapping(node, path, depth)
        finally:
            self._stack.discard(key)
        return None

    def _key(self, knode):
        self._tick(knode)
        if isinstance(knode, yaml.ScalarNode):
            k = self.scalar(knode)
        else:  # a collection used as a key: keep its text form, unusable as a parameter name anyway
            k = f"<{type(knode).__name__}>"
        try:
            hash(k)
        except TypeError:
            k = str(k)
        return k

    def mapping(self, node: yaml.MappingNode, path: tuple, depth: int, out: dict | None = None) -> dict:
        """Build a mapping into `out`. Keys already in `out` are kept (that is how merge keys work:
        explicit keys win, and earlier merged mappings win over later ones)."""
        merging = out is not None
        out = {} if out is None else out
        merges = []
        for knode, vnode in node.value:
            if isinstance(knode, yaml.ScalarNode) and knode.tag == _MERGE_TAG:
                merges.append(vnode)
                continue
            k = self._key(knode)
            if merging and k in out:
                continue
            if k in out:
                if isinstance(out[k], dict) and isinstance(vnode, yaml.MappingNode):
                    # rcl reads parameter files event by event: a repeated node key adds to the node
                    self.notes.append((f"duplicate key {k!r}; the two mappings are merged",
                                       _mark_loc(self.file, knode.start_mark)))
                    self._tick(vnode)
                    self.key_locs[path + (k,)] = _mark_loc(self.file, knode.start_mark)
                    _deep_update(out[k], self.mapping(vnode, path + (k,), depth + 1))
                    continue
                self.notes.append((f"duplicate key {k!r}; the last one wins", _mark_loc(self.file, knode.start_mark)))
                n = len(path) + 1
                for table in (self.value_locs, self.key_locs):
                    for p in [p for p in table if p[:n] == path + (k,)]:
                        del table[p]
            self.key_locs[path + (k,)] = _mark_loc(self.file, knode.start_mark)
            out[k] = self.build(vnode, path + (k,), depth + 1)
        for mnode in merges:
            sources = mnode.value if isinstance(mnode, yaml.SequenceNode) else [mnode]
            for src in sources:
                self._tick(src)
                if not isinstance(src, yaml.MappingNode):
                    raise ConsumerError("merge key '<<' needs a mapping or a list of mappings",
                                        _mark_loc(self.file, src.start_mark))
                key = id(src)
                if key in self._stack:
                    raise ConsumerError("YAML alias refers to itself (recursive structure); refused",
                                        _mark_loc(self.file, src.start_mark))
                self._stack.add(key)
                try:
                    self.mapping(src, path, depth + 1, out)
                finally:
                    self._stack.discard(key)
        return out


def _deep_update(dst: dict, src: dict) -> None:
    for k, v in src.items():
        if isinstance(v, dict) and isinstance(dst.get(k), dict):
            _deep_update(dst[k], v)
        else:
            dst[k] = v


def _refusal(e, file: str) -> ConsumerError:
    """A core.yamldoor refusal, worded for a consumer file (C007 at the place)."""
    if e.what == "size":
        return ConsumerError(f"file is larger than {e.limit} bytes; refused", Location(file))
    loc = Location(file, e.line, e.column) if e.line is not None else Location(file)
    if e.what == "depth":
        return ConsumerError(f"YAML nested deeper than {e.limit} levels; refused", loc)
    return ConsumerError(f"YAML expands to more than {e.limit} nodes through aliases (a YAML bomb); refused", loc)


def parse_yaml(text: str | bytes, file: str, *, max_bytes: int = MAX_BYTES, max_nodes: int = MAX_NODES) -> YamlDoc:
    """Parse one YAML document (the first non-empty one of a stream). Raises ConsumerError."""
    limits = yamldoor.Limits(max_bytes, max_nodes)
    try:
        if isinstance(text, bytes):
            yamldoor.check_size(len(text), limits)
            try:
                text = text.decode("utf-8-sig")
            except UnicodeDecodeError as e:
                line = text.count(b"\n", 0, e.start) + 1
                raise ConsumerError(f"not valid UTF-8 ({e.reason})", Location(file, line)) from None
        # the door bounds size, nesting (so libyaml's recursive C composer, ~10x faster than the pure-Python one,
        # is safe) and alias expansion
        root = yamldoor.compose_first(text, limits)
    except yamldoor.Refused as e:
        raise _refusal(e, file) from None
    except yaml.MarkedYAMLError as e:
        mark = e.problem_mark or e.context_mark
        msg = " ".join(x for x in (e.context, e.problem) if x) or "YAML syntax error"
        raise ConsumerError(f"YAML syntax error: {msg}", _mark_loc(file, mark)) from None
    except yaml.YAMLError as e:
        raise ConsumerError(f"YAML error: {e}", Location(file)) from None
    except RecursionError:
        raise ConsumerError("YAML nested too deeply; refused", Location(file)) from None
    if root is None:
        return YamlDoc(file, None)
    b = _Builder(file, max_nodes)
    try:
        data = b.build(root, ())
    except RecursionError:
        raise ConsumerError("YAML nested too deeply; refused", Location(file)) from None
    return YamlDoc(file, data, b.value_locs, b.key_locs, b.notes)


def load_yaml(path: str | os.PathLike, *, max_bytes: int = MAX_BYTES, max_nodes: int = MAX_NODES,
              runner: bool = False) -> YamlDoc:
    """Read and parse a YAML file. Raises ConsumerError (unreadable, too large, bad YAML, bomb). `runner`: the
    file is the runner's (core.door), as a config named or found above the checkout is."""
    from urdfcheck.consumers.common import read_capped

    file = str(path)
    return parse_yaml(read_capped(file, max_bytes, runner=runner), file, max_bytes=max_bytes, max_nodes=max_nodes)
