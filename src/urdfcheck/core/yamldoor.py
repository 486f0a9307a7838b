"""The one door for YAML text (issue 42): every YAML urdfcheck reads from a checked tree, a recording or a config
is refused here, before anything is built from it, when it is too large, nests too deeply or expands through
aliases past a node budget (a "billion laughs" bomb). Each copy of these guards was where a hardening fix was made
once and missed once; the readers (`load.xacro.yamlguard`, `consumers.yamlsrc`) only word the refusal.

The limits are stated here once. They differ by use, as named `Limits`:

* `CONSUMER`: parameter files, YAML launch files, the config: a real one is a few KiB; every value keeps its
  location, so the node budget bounds the memory of the located document too;
* `XACRO`: what xacro's `load_yaml` reads, rosbag2's `metadata.yaml` and YAML recordings: xacro builds plain
  Python values (no locations), and a recording holds one node per sample, so both limits are higher.
"""
from __future__ import annotations

from urdfcheck.core import lazyre
from urdfcheck.core.records import TupleRecord
from urdfcheck.core.yamlimport import yaml

MAX_DEPTH = 256  # for every use: deeper than any real file, and far below the C composer's stack


class Limits(TupleRecord):
    max_bytes: int
    max_nodes: int


CONSUMER = Limits(2 * 1024 * 1024, 100_000)
XACRO = Limits(8 * 1024 * 1024, 1_000_000)

LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
_BRACKETS = lazyre.compile(r"[\[\]{}]")
_RUNS = lazyre.compile(r"[\[{][\[{\s,]*|(?:-[ \t]+)+")  # maximal runs of flow openers / block dashes


class Refused(Exception):
    """`what` is "size", "depth" or "bomb"; `limit` the number passed; `line`/`column` (1-based) where, if known."""

    def __init__(self, what: str, limit: int, line: int | None = None, column: int | None = None):
        super().__init__(f"YAML refused ({what}, limit {limit})")
        self.what = what
        self.limit = limit
        self.line = line
        self.column = column


def _at(what: str, limit: int, mark) -> Refused:
    if mark is None:
        return Refused(what, limit)
    return Refused(what, limit, mark.line + 1, mark.column + 1)


def check_size(size: int, limits: Limits) -> None:
    """For a reader that has the bytes before decoding them: the size limit counts bytes there."""
    if size > limits.max_bytes:
        raise Refused("size", limits.max_bytes)


def _refuse_deep(text: str) -> None:
    for m in _RUNS.finditer(text):  # linear guard for the usual shapes
        run = m.group()
        if run.count("[") + run.count("{") + run.count("-") > MAX_DEPTH:
            raise Refused("depth", MAX_DEPTH, text.count("\n", 0, m.start()) + 1)
    depth = 0
    for m in _BRACKETS.finditer(text):  # flow nesting with text between the brackets ([a, [b, [c ...)
        depth += 1 if m.group() in "[{" else -1
        if depth > MAX_DEPTH:
            raise Refused("depth", MAX_DEPTH, text.count("\n", 0, m.start()) + 1)
    # Compact block nesting (`? ? ? x`, 2 bytes a level) gets past the guards above and overflows the C composer's
    # stack (PyYAML's own is quadratic in the depth): count the depth on libyaml's event stream (not recursive).
    depth = 0
    try:
        for ev in yaml.parse(text, Loader=LOADER):
            if isinstance(ev, (yaml.SequenceStartEvent, yaml.MappingStartEvent)):
                depth += 1
                if depth > MAX_DEPTH:
                    raise _at("depth", MAX_DEPTH, ev.start_mark)
            elif isinstance(ev, (yaml.SequenceEndEvent, yaml.MappingEndEvent)):
                depth -= 1
    except yaml.YAMLError as e:
        # libyaml >= 0.2.6 stops at its own depth limit with a scanner error
        if "nesting depth" in str(e):
            raise _at("depth", MAX_DEPTH, getattr(e, "problem_mark", None)) from None
        # any other syntax error: the composer reports it, located


def _children(node):
    if isinstance(node, yaml.SequenceNode):
        return list(node.value)
    if isinstance(node, yaml.MappingNode):
        return [n for kv in node.value for n in kv]
    return []


def _refuse_bomb(root, budget: int) -> int:
    """The expanded node count of `root`, memoised (aliases share node objects), so a bomb is refused in time
    proportional to its text, before anything is expanded. Raises Refused at the smallest node still too big."""
    sizes: dict[int, int] = {}
    state: dict[int, int] = {}  # 1: on the stack, 2: done
    stack = [(root, False)]
    while stack:  # iterative post-order over unique nodes
        node, expanded = stack.pop()
        key = id(node)
        if expanded:
            total = 1 + sum(sizes.get(id(c), 1) for c in _children(node))
            sizes[key] = min(total, budget + 1)
            state[key] = 2
            continue
        if key in state:
            continue  # done already, or a cycle (counted once; the readers refuse cycles as they build)
        state[key] = 1
        stack.append((node, True))
        for c in _children(node):
            if id(c) not in state:
                stack.append((c, False))
    if sizes[id(root)] <= budget:
        return sizes[id(root)]
    node = root
    while True:  # descend to the smallest node that is still too big: that is where the bomb is
        big = [c for c in _children(node) if sizes.get(id(c), 1) > budget]
        if not big:
            break
        node = big[0]
    raise _at("bomb", budget, node.start_mark)


def compose_first(text: str, limits: Limits):
    """The node tree of the first non-empty document of `text` (None: no document), after the size, depth and
    alias guards. Raises Refused; a syntax error is PyYAML's (yaml.YAMLError), RecursionError left to the caller."""
    check_size(len(text), limits)
    _refuse_deep(text)
    root = None
    for node in yaml.compose_all(text, Loader=LOADER):
        if node is not None:
            root = node
            break
    if root is not None:
        _refuse_bomb(root, limits.max_nodes)
    return root


def check(text: str, limits: Limits) -> None:
    """Refuse `text` (Refused) before a reader builds Python values from it with PyYAML's own loaders (xacro's
    `load_yaml`, a recording, rosbag2's metadata): every document of the stream shares one node budget. A syntax
    error passes: the reader's loader reports it."""
    check_size(len(text), limits)
    _refuse_deep(text)
    if "&" not in text:
        return  # no anchor, no alias to expand
    budget = limits.max_nodes
    try:
        for node in yaml.compose_all(text, Loader=LOADER):
            if node is not None:
                budget -= _refuse_bomb(node, budget)
    except yaml.YAMLError:
        return
    except Refused as e:
        e.limit = limits.max_nodes  # the budget left for this document is the stream's
        raise
