"""Zero-config discovery of what to lint in a package directory.

* entry models: every `.urdf`, and every `.xacro` whose root element is `<robot>`, that is not included by
  another xacro of the package (`xacro:include filename="..."`, matched on the path tail) and that does more
  than define macros/properties (a library has only `xacro:macro`/`property`/`arg`/`include` children, also
  inside `xacro:if`/`unless`, at least one macro or property, and expands to an empty robot; it is linted
  through the robots that include it, never alone);
* parameter YAML: `*.yaml`/`*.yml` in any `config/`, `params/` or `param/` directory;
* launch files: names ending in one of `LAUNCH_SUFFIXES` (`*.launch`, `*.launch.xml`, `*.launch.py`,
  `*_launch.py`, ...) in any `launch/` directory.

Hidden directories and the folders ROS's tools skip by their marker files (COLCON_IGNORE, AMENT_IGNORE,
CATKIN_IGNORE, which colcon writes into its build/install/log bases; core.walk), never by name, are skipped; at most
`max_files` files are looked at. Output lists are sorted. Files are only read (and the xacro ones only their
first `HEAD_BYTES` for the root check), never expanded.
"""
from __future__ import annotations

import os
import re

from urdfcheck.core import lazyre, xmlfront
from urdfcheck.core.lxmlimport import etree
from urdfcheck.core.records import TupleRecord
from urdfcheck.core.walk import SKIP_DIRS  # noqa: F401  (read from here too)

PARAM_DIRS = {"config", "params", "param"}
LAUNCH_DIRS = {"launch"}
# the one list of launch-file endings (plan/plan.py, plan/deployments.py and the pre-commit hooks' `files` read it;
# `_launch.py` is ROS 2's other convention: realsense2_camera's rs_launch.py)
LAUNCH_SUFFIXES = (".launch", ".launch.xml", ".launch.py", ".launch.yaml", ".launch.yml", "_launch.py")
_ROLES = (".urdf", ".xacro", ".yaml", ".yml") + LAUNCH_SUFFIXES  # the endings `_scan` sorts by role
MAX_FILES = 20_000
HEAD_BYTES = 4 * 1024 * 1024

_COMMENT = lazyre.compile(r"<!--.*?(?:-->|\Z)", re.S)
_INCLUDE = lazyre.compile(r"""<\s*xacro:include\b[^>]*?\bfilename\s*=\s*(["'])(.*?)\1""", re.S)
_ROOT = lazyre.compile(r"<\s*([A-Za-z_][\w:.-]*)")
_DEFINITION_TAGS = {"macro", "property", "arg", "include"}
_XACRO_NS = ("http://www.ros.org/wiki/xacro", "http://ros.org/wiki/xacro", "http://wiki.ros.org/xacro")


class Discovered(TupleRecord):
    root: str
    models: tuple[str, ...]
    params: tuple[str, ...]
    launch: tuple[str, ...]
    libraries: tuple[str, ...] = ()  # xacro files skipped as included or macro-only
    truncated: bool = False  # the walk stopped at max_files: what lies beyond was not looked at
    # robots by their root whose text suggests no link (fragments, SRDF-like): expanded, a library only when the
    # expansion has no link (plan.robots); never in `models`, never a silent skip
    probes: tuple[str, ...] = ()
    # libraries because another file includes them, that may hold links: the run checks that a model read them
    included: tuple[str, ...] = ()
    # (fragment, includer): files another file may include where discovery cannot follow (a legacy or commented
    # include, a computed name): probes, and linted through their includers when named (plan.plan)
    hints: tuple = ()


def _walk(root: str, max_files: int, cut: list | None = None):
    from urdfcheck.core.walk import files, folders

    n = 0
    for dirpath, entries in folders(root):
        for f in files(entries):
            n += 1
            if n > max_files:
                if cut is not None:
                    cut.append(dirpath)
                return
            yield dirpath, f


def _read_head(path: str, trusted: bool = False, cache: dict | None = None) -> str:
    from urdfcheck.load.packages import leaves_cwd

    # a committed symlink out of the checkout: its target is none of our business
    if not trusted and leaves_cwd(path, cache=cache):
        return ""
    try:
        from urdfcheck.core import door
        from urdfcheck.core.safeio import decode_model_text

        # a regular file only (a FIFO must not block); a UTF-16 model is found, then reported by the loader
        return decode_model_text(door.read_bytes(path, limit=HEAD_BYTES)[:HEAD_BYTES])
    except OSError:
        return ""


def _root_tag(text: str) -> str | None:
    i = 0
    while True:
        m = _ROOT.search(text, i)
        if not m:
            return None
        # skip <?xml ...?>, <!-- -->, <!DOCTYPE>
        before = text[m.start(): m.start() + 2]
        if before.startswith("<?") or before.startswith("<!"):
            i = m.end()
            continue
        start = text.rfind("<!--", 0, m.start())
        if start != -1 and text.find("-->", start) > m.start():
            i = text.find("-->", start) + 3
            continue
        return m.group(1)


def _is_library(text: str, includes: bool = False) -> bool:
    """Only definitions at the top level (macros, properties, args; with `includes`, includes too): without
    includes it expands to an empty robot, certainly; with them, the expansion tells (a probe)."""
    try:
        root = etree.fromstring(text.encode("utf-8"), xmlfront.parser(comments=False))
    except etree.XMLSyntaxError:
        return False  # let the linter report it
    kids = [c for c in root if isinstance(c.tag, str)]
    if not kids:
        return False
    defs = _definitions(kids, 0)
    # macros or properties only (an `xacro:if` holding only definitions counts): a library, certainly (its
    # expansion is an empty robot). An include may bring a robot body: such a file is expanded to tell
    # with `includes`, a file of includes only (uuv_simulator's snippets.xacro: the macro libraries of a package
    # in one include) is a probe too: its expansion has no link unless an included file brings a robot body
    return defs is not None and (bool(defs & {"macro", "property"}) or (includes and defs == {"include"})) and (
        includes or "include" not in defs)


def _definitions(kids, depth: int) -> set[str] | None:
    """The definition tags among `kids`, or None when one of them is not a definition."""
    found: set[str] = set()
    for c in kids:
        q = etree.QName(c)
        if q.namespace not in _XACRO_NS:
            return None
        if q.localname in _DEFINITION_TAGS:
            found.add(q.localname)
        elif q.localname in ("if", "unless") and depth < 8:
            inner = _definitions([k for k in c if isinstance(k.tag, str)], depth + 1)
            if inner is None:
                return None
            found |= inner
        else:
            return None
    return found


_SRDF = lazyre.compile(r"<\s*(?:disable_collisions|group|group_state|virtual_joint|end_effector|passive_joint)\b")


def _no_links(text: str) -> bool:
    """A xacro that can produce no <link>: none written and nothing included (materials, colours): a fragment
    for other files to include, like a .urdf without links (ros2_control_demos' diffbot.materials.xacro)."""
    return not re.search(r"<\s*link\b", text) and not re.search(r"<\s*xacro:include\b", text)


def _is_srdf(text: str) -> bool:
    """MoveIt SRDF written as xacro (root <robot> too): SRDF elements (<group>, <disable_collisions>, ...)
    and no <link> of its own. Never a URDF model (`*.srdf.xacro` is skipped by name already)."""
    return bool(_SRDF.search(text)) and not re.search(r"<\s*link\b", text)


def _included_files(ref: str, includer: str, xacros: _Xacros) -> set[str]:
    """Package xacro files an include reference may point at.

    A plain relative reference resolves against the including file. A `$(find pkg)/a/b.xacro` reference
    matches files whose path ends with `a/b.xacro` (source and install layouts differ, so the package
    prefix is not used); when none does, any file called `b.xacro`.
    """
    ref = ref.strip().replace("\\", "/")
    if not ref:
        return set()
    if "$(" not in ref and "${" not in ref:
        cand = os.path.normpath(ref if os.path.isabs(ref) else os.path.join(os.path.dirname(includer), ref))
        return {cand} if cand in xacros.paths else set()
    tail = re.sub(r"^.*\)", "", ref).lstrip("/")  # text after the last substitution
    if "${" in tail or not tail:
        return set()
    tail_parts = [p for p in tail.split("/") if p not in ("", ".")]
    if not tail_parts:
        return set()
    def ends_with(path: str) -> bool:
        parts = path.replace("\\", "/").split("/")
        return parts[-len(tail_parts):] == tail_parts
    named = xacros.by_name.get(tail_parts[-1], ())  # a path that ends with the tail has its file name
    hits = {x for x in named if ends_with(x)}
    if not hits:
        hits = {x for x in named if os.path.basename(x) == tail_parts[-1]}
    return hits


# an include that may bring a file in although discovery cannot follow it literally: the legacy unprefixed
# <include filename=...> (xacro before ROS Jade), and an include written in a comment (a drop-in alternative)
_LEGACY = lazyre.compile(r"""<\s*include\b[^>]*?\bfilename\s*=\s*(["'])(.*?)\1""", re.S)
_COMMENTED = lazyre.compile(r"<!--(.*?)(?:-->|\Z)", re.S)
_SUBST = lazyre.compile(r"\$\{[^}]*\}|\$\([^)]*\)")
_FIND_PATH = lazyre.compile(r"""\$\(\s*find\s+[\w-]+\s*\)/[^"'<>\s$]+\.xacro\b""")


def _fragment_hints(text: str, includer: str, xacros: _Xacros) -> set[str]:
    """Package xacro files that another file may include where discovery does not follow it: a legacy
    `<include filename>`, an include inside a comment (a drop-in alternative), a name computed from arguments
    or properties (`sensors/${sensor}.urdf.xacro`, matched as a pattern). They are fragments until their
    expansion says otherwise (plan.robots: probes)."""
    import fnmatch

    out: set[str] = set()
    bare = _COMMENT.sub("", text)
    refs = [m.group(2) for m in _LEGACY.finditer(bare)]
    # a path handed to a macro or property (`thruster_layout="$(find pkg)/urdf/aft.xacro"`) that the macro then
    # includes (`<xacro:include filename="${thruster_layout}"/>`): vrx's thruster layouts
    refs.extend(m.group(0) for m in _FIND_PATH.finditer(_INCLUDE.sub("", bare)))
    for c in _COMMENTED.finditer(text):
        refs.extend(m.group(2) for m in _INCLUDE.finditer(c.group(1)))
    for ref in refs:
        out |= _included_files(ref, includer, xacros)
    for m in _INCLUDE.finditer(_COMMENT.sub("", text)):
        ref = m.group(2).strip().replace("\\", "/")
        tail = re.sub(r"^\$\(\s*find[^)]*\)", "", ref).lstrip("/")
        if "${" not in tail and "$(" not in tail:
            continue
        pattern = _SUBST.sub("*", tail)
        literal = pattern.replace("*", "").replace("/", "").replace(".", "")
        if len(literal) < 3 or pattern.strip("*/") == "":
            continue  # `${name}.xacro` says too little to pick files by
        parts = pattern.split("/")
        base = os.path.dirname(includer) if not ref.startswith("$(") else None
        for x in xacros.paths:
            xs = x.replace("\\", "/").split("/")
            if len(xs) >= len(parts) and fnmatch.fnmatchcase("/".join(xs[-len(parts):]), "/".join(parts)) and (
                    base is None or os.path.normpath(x).startswith(os.path.normpath(base) + os.sep)):
                out.add(x)
    return out


class _Xacros:
    """A package's xacro files, looked up by path and by file name (an include is matched against all of them:
    a workspace holds a thousand)."""

    def __init__(self, paths: list[str]):
        self.paths = set(paths)
        self.by_name: dict[str, list[str]] = {}
        for p in paths:
            self.by_name.setdefault(p.replace("\\", "/").rsplit("/", 1)[-1], []).append(p)


def several_models(package_dir: str | os.PathLike, *, max_files: int = MAX_FILES, trusted: bool = False
                   ) -> tuple[bool, tuple[str, ...], tuple[str, ...]]:
    """(more than one entry model, parameter files, launch files) of a package: what consumer discovery needs.
    Two `.urdf` files with links already make it several, which `discover` would find by reading every xacro
    of the package (a collection of robots such as example-robot-data: 70 files read and parsed)."""
    root, urdfs, xacros, params, launches, _ = _scan(package_dir, max_files)
    from urdfcheck.load.packages import leaves_cwd

    real_dirs: dict = {}
    seen = 0
    for p in urdfs:  # a model, as `discover` decides: linked out of the working directory, or with a <link>
        if (not trusted and leaves_cwd(p, cache=real_dirs)) or re.search(r"<\s*link\b",
                                                                         _read_head(p, trusted, real_dirs)):
            seen += 1
            if seen > 1:
                return True, tuple(sorted(params)), tuple(sorted(launches))
    found = discover(package_dir, max_files=max_files, trusted=trusted)
    return len(found.models) > 1, found.params, found.launch


def _scan(package_dir, max_files: int):
    """(root, urdfs, xacros, params, launches, cut): the package's files by name and folder, none read."""
    root = os.path.abspath(str(package_dir))
    urdfs, xacros, params, launches = [], [], [], []
    parts_of: dict[str, list[str]] = {}  # dirpath -> its folders below root (relpath per file was slow)
    cut: list = []
    for dirpath, f in _walk(root, max_files, cut):
        low = f.lower()
        if not low.endswith(_ROLES):  # meshes, textures, sources: most of a package's files (half the time)
            continue
        path = os.path.join(dirpath, f)
        parts = parts_of.get(dirpath)
        if parts is None:
            rel = os.path.relpath(dirpath, root)
            parts = parts_of[dirpath] = [] if rel == os.curdir else rel.replace("\\", "/").split("/")
        if low.endswith(".urdf"):
            urdfs.append(path)
        elif low.endswith(".xacro"):
            if not low.endswith(".srdf.xacro"):  # MoveIt's semantic description (also <robot>): not a URDF
                xacros.append(path)
        elif low.endswith((".yaml", ".yml")) and not low.endswith((".launch.yaml", ".launch.yml")) \
                and any(p in PARAM_DIRS for p in parts):
            params.append(path)
        if low.endswith(LAUNCH_SUFFIXES) and any(p in LAUNCH_DIRS for p in parts):
            launches.append(path)
    return root, urdfs, xacros, params, launches, cut


_REMEMBERED: list[dict] = []  # one memo per run in progress (see `remembering`)


class remembering:
    """Within this block, `discover` walks and reads each package once: the planner, consumer discovery and the
    open-world checks ask about the same packages in one run (the run enters it; files do not change under
    it). Outside, every call looks afresh (a long-lived process lints again after edits)."""

    def __enter__(self):
        from urdfcheck.core.walk import remembered

        _REMEMBERED.append({})
        self._listed = remembered()
        self._listed.__enter__()  # and each folder is listed once (core.walk), by whichever walk comes first

    def __exit__(self, *exc):
        self._listed.__exit__(*exc)
        _REMEMBERED.pop()


def discover(package_dir: str | os.PathLike, *, max_files: int = MAX_FILES, trusted: bool = False) -> Discovered:
    """The package's files by role. Unless `trusted`, nothing is read through a link out of the working
    directory (`packages.leaves_cwd`)."""
    if not _REMEMBERED:
        return _discover(package_dir, max_files, trusted)
    memo = _REMEMBERED[-1]
    key = (os.path.abspath(str(package_dir)), max_files, trusted)
    found = memo.get(key)
    if found is None:
        found = memo[key] = _discover(package_dir, max_files, trusted)
    return found


def _discover(package_dir, max_files: int, trusted: bool) -> Discovered:
    root, urdfs, xacros, params, launches, cut = _scan(package_dir, max_files)
    from urdfcheck.load.packages import leaves_cwd

    # a model file linked out of the working directory is listed as a model, so that the loader names it
    # (X014) instead of it silently dropping out of the run; nothing behind the link is read
    real_dirs: dict = {}  # one realpath per folder, not per file
    from urdfcheck.core import door

    models = [] if trusted else [p for p in urdfs + xacros if leaves_cwd(p, cache=real_dirs) or door.leaves(p)]
    urdfs = [p for p in urdfs if p not in models]
    xacros = [p for p in xacros if p not in models]
    texts = {p: _read_head(p, trusted, real_dirs) for p in xacros}
    included: set[str] = set()
    index = _Xacros(xacros)
    hinted: set[str] = set()  # fragments by another file's hint: expanded as probes, never robots by discovery
    hints = []
    for p, t in texts.items():
        for m in _INCLUDE.finditer(_COMMENT.sub("", t)):  # a commented-out include includes nothing
            included |= _included_files(m.group(2), p, index) - {p}
        got = _fragment_hints(t, p, index) - {p}
        hinted |= got
        hints.extend((f, p) for f in sorted(got))
    libs, probes, maybe = [], [], []
    for p in urdfs:  # a .urdf without any <link> is a fragment (materials, properties) for others to include
        (models if re.search(r"<\s*link\b", _read_head(p, trusted, real_dirs)) else libs).append(p)
    for p in xacros:
        tag = _root_tag(texts[p])
        robot = tag is not None and tag.split(":")[-1] == "robot"
        if p in included:
            libs.append(p)
            if robot and not _is_library(texts[p]):
                maybe.append(p)
            continue
        if not robot or _is_library(texts[p]):
            libs.append(p)
            continue
        if _is_srdf(texts[p]) or _no_links(texts[p]) or _is_library(texts[p], includes=True) or p in hinted:
            libs.append(p)  # by its text; the expansion decides (plan.robots)
            probes.append(p)
            continue
        models.append(p)
    return Discovered(root, tuple(sorted(models)), tuple(sorted(params)), tuple(sorted(launches)), tuple(sorted(libs)),
                      bool(cut), tuple(sorted(probes)), tuple(sorted(maybe)), tuple(hints))
