"""Resolve ROS package names to directories without ROS installed.

One chain, first hit wins: explicit mappings (`--package NAME=PATH`, config), the ament index under
AMENT_PREFIX_PATH, ROS_PACKAGE_PATH, the package that encloses the input, then a scan for package.xml
files around the input (the enclosing workspace). The resolver also knows the roots that files may be read from
(the sandbox confines includes, YAML and meshes to them).
"""
from __future__ import annotations

import os
import re
from pathlib import Path

from urdfcheck.core import lazyre, walk

_NAME = lazyre.compile(rb"<name>\s*([^<\s]+)\s*</name>")
SCAN_DEPTH = 6
SCAN_LIMIT = 5000  # directories visited at most


def _listed_name(package_xml: Path, root, link: bool = True) -> str | None:
    """`package_name` of a package.xml a workspace scan below `root` listed: the scan looks at folders beside the
    checkout, not yet roots of the run, so the read is not confined to them, but to `root` (never a link out).
    `link`: the entry is a symbolic link; one that is not lies where the walk found it, below `root` (the walk
    never enters a linked folder: core.walk), so its real path is not looked up (an lstat per path component:
    most of a run's file-system calls in a repository of fifty packages)."""
    from urdfcheck.core import door

    if link and not _below(os.path.realpath(package_xml), real(root)):
        return None
    with door.unconfined():
        return package_name(package_xml)


def package_name(package_xml: Path) -> str | None:
    try:
        from urdfcheck.core import door

        head = door.read_bytes(package_xml, limit=65536)
    except OSError:
        return None
    m = _NAME.search(head)
    return m.group(1).decode("utf-8", "replace") if m else None


def _below(path: str, base: str) -> bool:
    return path == base or path.startswith(base.rstrip(os.sep) + os.sep)


def leaves_cwd(path: str | os.PathLike, roots=(), cache: dict | None = None) -> bool:
    """`path` is written below the working directory but really lies outside it (and outside `roots`): a
    symbolic link, of the file or of a folder on the way, that a pull request could point at any file of the
    machine that runs the check (CI runs in the checkout). `cache`: real paths of folders already resolved, for
    a caller that asks about many files of one tree (a folder's real path is the same for all its files)."""
    lexical = os.path.abspath(path)
    cwd = os.getcwd()
    if not _below(lexical, cwd):
        return False
    if cache is None:
        cache = {}

    def real_dir(d: str) -> str:
        got = cache.get(d)
        if got is None:
            got = cache[d] = walk.real(d)
        return got

    head, tail = os.path.split(lexical)
    real = os.path.realpath(lexical) if os.path.islink(lexical) else os.path.join(real_dir(head), tail)
    return not any(_below(real, real_dir(r)) for r in (cwd, *roots))


def enclosing_package(path: Path) -> Path | None:
    """The nearest directory at or above `path` that holds a package.xml."""
    p = path if path.is_dir() else path.parent
    for d in (p, *p.parents):
        if (d / "package.xml").is_file():
            return d
    return None


def own_package(path: str | os.PathLike) -> tuple[str | None, Path | None]:
    """Name and folder of the package that encloses `path` ((None, None) outside any package)."""
    d = enclosing_package(Path(os.path.abspath(path)))
    return (package_name(d / "package.xml"), d) if d is not None else (None, None)


def workspace_root(path: Path) -> Path:
    """The folder to scan for sibling packages: above the outermost package enclosing `path`."""
    p = (path if path.is_dir() else path.parent).resolve()
    outer = None
    for d in (p, *p.parents):
        if (d / "package.xml").is_file():
            outer = d
    if outer is None:
        return p
    return outer.parent if outer.parent != outer else outer


def scan(root: Path, near: Path | None = None) -> dict[str, Path]:
    """name -> package folder below `root`. When a name occurs twice, the folder nearest `near` wins."""
    from urdfcheck.core.walk import folders

    found: dict[str, Path] = {}
    for d, entries in folders(root, max_dirs=SCAN_LIMIT, max_depth=SCAN_DEPTH):
        for e in entries:
            if e.name == "package.xml" and e.is_file():
                name = _listed_name(Path(e.path), root, e.is_symlink())
                if name and (name not in found or _closer(Path(d), found[name], near)):
                    found[name] = Path(d)
    return found


WORKSPACE_LIMIT = 50_000  # directories visited at most when scanning a named workspace
_WORKSPACES: dict[str, dict[str, list[Path]]] = {}


def workspace_packages(root: str | os.PathLike) -> dict[str, list[Path]]:
    """name -> every folder holding a package.xml of that name, at any depth below `root` (a workspace the
    user named). Hidden and build folders are skipped; the scan is done once per root and process."""
    key = os.path.abspath(root)
    got = _WORKSPACES.get(key)
    if got is not None:
        return got
    from urdfcheck.core.walk import folders

    found: dict[str, list[Path]] = {}
    for d, entries in folders(key, max_dirs=WORKSPACE_LIMIT):
        for e in entries:
            if e.name == "package.xml" and e.is_file(follow_symlinks=False):
                name = _listed_name(Path(e.path), key, link=False)
                if name:
                    found.setdefault(name, []).append(Path(d))
    _WORKSPACES[key] = found
    return found


def nearest(folders: list[Path], near: Path | None) -> Path:
    """The folder sharing the longest path prefix with `near` (the first one on a tie)."""
    best = folders[0]
    for f in folders[1:]:
        if _closer(f, best, near):
            best = f
    return best


def workspace_map(root: str | os.PathLike, near: str | os.PathLike | None = None) -> dict[str, str]:
    """name -> folder for every package below `root`; a name found twice resolves to the copy nearest `near`
    (a model in one repository prefers its own repository's package). Usable as an explicit package map."""
    n = Path(os.path.abspath(near)) if near is not None else None
    return {name: str(nearest(dirs, n)) for name, dirs in workspace_packages(root).items()}


def _closer(a: Path, b: Path, near: Path | None) -> bool:
    if near is None:
        return False

    def shared(p: Path) -> int:
        return len(os.path.commonpath([str(p), str(near)]))

    return shared(a) > shared(b)


_RESOLVED: dict[str, Path] = {}


def forget() -> None:
    """Drop the remembered workspace scans and resolved folders (a forked worker whose reads are recorded looks
    afresh; `core.walk.forget` drops the run's other memos: listings, real paths, sub-folders)."""
    _WORKSPACES.clear()
    _RESOLVED.clear()


real = walk.real  # os.path.realpath, remembered for the run (core.walk)


def _subdirs(folder: str) -> list[str]:
    """The sub-folders of `folder` (links to folders too), listed once in a run."""
    return walk.run_cached("subdirs", folder, lambda: _list_subdirs(folder))


def _list_subdirs(folder: str) -> list[str]:
    got = []
    try:
        with os.scandir(folder) as it:
            for e in it:
                try:
                    if e.is_dir():
                        got.append(e.path)
                except OSError:
                    continue
    except OSError:
        pass
    return got


def _ancestors(path: str) -> list[str]:
    """The folders above an absolute, normalized `path`, nearest first, up to the file system's root."""
    out = []
    end = len(path)
    while True:
        end = path.rfind(os.sep, 0, end)
        if end <= 0:
            out.append(os.sep)
            return out
        out.append(path[:end])


def layout_hits(root: str, rel: str) -> list[str]:
    """The files `rel` names one folder down inside `root`, or else two (`root/*/rel`, `root/*/*/rel`): where
    CMake's install layout (`share/PKG/urdf`) has the source checkout's file (`PKG/description/urdf`). The
    folders are listed once a run; `rel` is a name, not a pattern, and never leads out of the folder it is
    joined to (an include's `$(find P)/../x` is the model's text: nothing outside the package is looked at)."""
    rel = os.path.normpath(rel)
    if os.path.isabs(rel) or rel == os.curdir or rel.split(os.sep, 1)[0] == os.pardir:
        return []
    head = os.path.dirname(rel)
    for depth in (1, 2):
        folders = _subdirs(root) if depth == 1 else [g for d in _subdirs(root) for g in _subdirs(d)]
        if head:  # the folders that hold rel's folder, once per folder name: a robot's meshes share a few
            folders = _holding(root, depth, head, folders)
        hits = [c for c in (os.path.join(d, rel) for d in folders) if os.path.isfile(c)]
        if hits:
            return hits
    return []


def _holding(root: str, depth: int, head: str, folders: list[str]) -> list[str]:
    return walk.run_cached("layout_heads", (root, depth, head),
                           lambda: [d for d in folders if os.path.isdir(os.path.join(d, head))])


def _resolved(path) -> Path:
    """Path(path).resolve(), remembered: a workspace map of a hundred packages is given to every model."""
    key = os.fspath(path)
    got = _RESOLVED.get(key)
    if got is None:
        if len(_RESOLVED) > 10_000:
            _RESOLVED.clear()
        got = _RESOLVED[key] = Path(key).resolve()
    return got


class Resolver:
    def __init__(self, explicit: dict[str, str] | None = None, near: Path | None = None,
                 environ: dict | None = None, workspace: str | os.PathLike | None = None):
        env = os.environ if environ is None else environ
        # a workspace the user named: every package below it, at any depth, resolves before the scan
        self.named_workspace = Path(os.path.abspath(workspace)) if workspace is not None else None
        self.explicit = {k: _resolved(v) for k, v in (explicit or {}).items()}
        self._ament = [Path(p) for p in env.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
        self._ros = [Path(p) for p in env.get("ROS_PACKAGE_PATH", "").split(os.pathsep) if p]
        self.workspace = workspace_root(near) if near is not None else None
        self.near = near.resolve() if near is not None else None
        self._scanned: dict[str, Path] | None = None
        self._ros_scanned: dict[str, Path] | None = None
        self._own_pkg: tuple | None = None
        self.used: dict[str, Path] = {}
        from urdfcheck.core import door

        # the folders this resolver lets files be read from are the run's roots too (core.door)
        # (not the workspace around the input, which may be the folder above the checkout: its packages become
        # roots one by one, as `find` resolves them)
        for root in (*self.explicit.values(), self.named_workspace):
            if root is not None:
                door.add_root(root)

    def find(self, name: str) -> Path | None:
        hit = self._find(name)
        if hit is not None:
            if name not in self.used:
                from urdfcheck.core import door

                door.add_root(hit)  # a package the run resolved: its files may be read (core.door)
            self.used[name] = hit
        return hit

    def _find(self, name: str) -> Path | None:
        if name in self.explicit:
            return self.explicit[name]
        for prefix in self._ament:
            if (prefix / "share" / "ament_index" / "resource_index" / "packages" / name).exists():
                return prefix / "share" / name
        if self._ros:
            if self._ros_scanned is None:
                self._ros_scanned = {}
                for p in self._ros:
                    for k, v in scan(p).items():
                        self._ros_scanned.setdefault(k, v)
            if name in self._ros_scanned:
                return self._ros_scanned[name]
        if self.near is not None and name == self._own()[0]:
            return self._own()[1]  # `$(find own_package)`, the usual case, needs no workspace scan
        if self.named_workspace is not None:
            dirs = workspace_packages(self.named_workspace).get(name)
            if dirs:
                return nearest(dirs, self.near)
        if self.workspace is not None:
            if self._scanned is None:
                self._scanned = scan(self.workspace, self.near)
            if name in self._scanned:
                return self._scanned[name]
        return self._below_cwd(name)

    def _below_cwd(self, name: str) -> Path | None:
        """Last resort: the packages below the working directory, the folder the user runs in (CI: the
        checkout), when the input lies below it and its own repository lacks the package (a description that
        includes a package of a repository beside it). Scanned once per process, on the first miss."""
        if self.near is None:
            return None
        cwd = os.getcwd()
        if not _below(str(self.near), cwd) or (self.workspace is not None and _below(cwd, str(self.workspace))):
            return None  # outside the working directory, or the repository scan covered it already
        dirs = workspace_packages(cwd).get(name)
        return nearest(dirs, self.near) if dirs else None

    def _own(self) -> tuple[str | None, Path | None]:
        """Name and folder of the package that encloses the input."""
        if self._own_pkg is None:
            self._own_pkg = own_package(self.near)
        return self._own_pkg

    def roots(self) -> list[Path]:
        """Folders that files may be read from."""
        key = len(self.used)  # the roots only grow when a package is found
        cached = getattr(self, "_roots", None)
        if cached is not None and cached[0] == key:
            return cached[1]
        out = list(self.explicit.values())  # resolved already
        if self.workspace is not None:
            out.append(self.workspace.resolve())
        if self.named_workspace is not None:
            out.append(self.named_workspace.resolve())
        out.extend(_resolved(p) for p in self.used.values())
        uniq = list(dict.fromkeys(out))
        self._roots = (key, uniq, [str(p) for p in uniq])
        return uniq

    def allowed(self, path: str | Path) -> bool:
        where = real(os.fspath(path))
        self.roots()
        roots = self._roots[2]
        if len(roots) < 8:
            return any(where == r or where.startswith(r.rstrip(os.sep) + os.sep) for r in roots)
        # a workspace map: the path's few ancestors looked up, not every root compared (once per mesh)
        memo = walk.run_memo("root_sets")
        got = memo.get(id(self)) if memo is not None else None
        if got is None or got[0] is not roots:
            got = (roots, frozenset(roots))
            if memo is not None:
                memo[id(self)] = got
        return where in got[1] or any(a in got[1] for a in _ancestors(where))

    def source_layout(self, path: str | Path) -> Path | None:
        """The source file behind an install-layout path, when `path` does not exist.

        CMake commonly installs `description/urdf` to `share/PKG/urdf`, so `$(find PKG)/urdf/x.xacro`
        names `PKG/description/urdf/x.xacro` in a source checkout. Look one or two folders down inside
        the package; use the match only when it is unique.
        """
        p = os.path.abspath(path)
        key = (len(self.used), len(self.explicit))  # both only grow
        # remembered in the run's memo, not on the resolver: the lint cache keys expansions on its attributes
        memo = walk.run_memo("layout_roots")
        cached = memo.get(id(self)) if memo is not None else None
        if cached is None or cached[0] is not self or cached[1] != key:
            roots = [os.path.abspath(r) for r in (*self.used.values(), *self.explicit.values())]
            order: dict[str, int] = {}
            for i, r in enumerate(roots):
                order.setdefault(r, i)
            cached = (self, key, order)
            if memo is not None:
                memo[id(self)] = cached
        order = cached[2]
        above = set(_ancestors(p))
        for root in sorted((r for r in above if r in order), key=order.__getitem__):  # the roots' own order
            hits = layout_hits(root, os.path.relpath(p, root))
            if len(hits) == 1:
                return Path(hits[0])
        return None

    def resolve_uri(self, uri: str, base_dir: Path) -> tuple[Path | None, str | None]:
        """Resolve a package://, file:// or relative URI. Returns (path, problem)."""
        if uri.startswith("package://"):
            rest = uri[len("package://"):]
            name, _, sub = rest.partition("/")
            root = self.find(name)
            if root is None:
                return None, f"package {name!r} not found"
            path = root / sub
            if self.allowed(path) and not path.exists():  # `..` may leave the roots: never stat outside
                path = self.source_layout(path) or path
            return path, None
        if uri.startswith("file://"):
            return Path(uri[len("file://"):]), None
        if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*://", uri):
            return None, f"unsupported URI scheme in {uri!r}"
        return base_dir / uri, None


# --- unresolved packages, all of them in one run -------------------------------------------------------
_PKG_REF = lazyre.compile(r"\$\(\s*find(?:-pkg-share)?\s+([A-Za-z0-9_]+)\s*\)|package://([A-Za-z0-9_]+)/")
_XINCLUDE = lazyre.compile(r"""<\s*xacro:include\b[^>]*?\bfilename\s*=\s*(["'])(.*?)\1""", re.S)
MAX_REF_FILES = 500
MAX_REF_BYTES = 4 * 1024 * 1024


def missing_packages(entries, find) -> dict[str, list[tuple[str, int]]]:
    """Every package name that model files reference (`$(find X)`, `$(find-pkg-share X)`, `package://X/`) and
    `find(name)` cannot resolve, with each (file, line) that references it, in first-seen order.

    Read as text, without expanding: starting from `entries`, the includes whose file name is literal or
    `$(find known_package)/literal` are followed (the source layout too: `share/P/urdf` may be `P/description/urdf`).
    An expansion stops at its first unknown package; this names them all, so one run lists every package
    that is missing (`find` returns a folder or None)."""
    missing: dict[str, list[tuple[str, int]]] = {}
    known: dict[str, Path | None] = {}

    def lookup(name: str) -> Path | None:
        if name not in known:
            known[name] = find(name)
        return known[name]

    for path, text in literal_includes(entries, lookup):
        for m in _PKG_REF.finditer(text):
            name = m.group(1) or m.group(2)
            if lookup(name) is None:
                places = missing.setdefault(name, [])
                where = (path, text.count("\n", 0, m.start()) + 1)
                if where not in places:
                    places.append(where)
    return missing


def _literal_include(ref: str, includer: str, lookup, allow=None) -> str | None:
    m = re.match(r"^\$\(\s*find\s+([A-Za-z0-9_]+)\s*\)(.*)$", ref)
    if m:
        root = lookup(m.group(1))
        rest = m.group(2).lstrip("/")
        if root is None or "$" in rest:
            return None
        cand = os.path.join(str(root), rest)
        if allow is not None and not allow(os.path.abspath(cand)):
            return None  # not even looked at
        if not os.path.isfile(cand):  # install layout vs source layout
            hits = layout_hits(os.path.abspath(str(root)), rest) if rest else []
            cand = hits[0] if len(hits) == 1 else cand
        return os.path.abspath(cand)
    if "$" in ref or not ref:
        return None
    return os.path.abspath(os.path.join(os.path.dirname(includer), ref))


def literal_includes(entries, find, max_files: int = MAX_REF_FILES, allow=None):
    """(path, text) of `entries` and of every file they include through a literal `xacro:include` (a literal
    name or `$(find known_package)/literal`), breadth first, each once, read as text without expanding: what
    the unresolved packages, a library's robots and a model's Gazebo parameter files are found from.
    `allow(path)`: whether an included file may be looked at at all (asked before any stat or read)."""
    from urdfcheck.core import door  # a regular file inside the run's roots only: a FIFO must not block

    queue, seen = [os.path.abspath(e) for e in entries], set()
    while queue and len(seen) < max_files:
        path = queue.pop(0)
        if path in seen:
            continue
        if allow is not None and seen and not allow(path):
            continue
        seen.add(path)
        try:
            text = door.read_bytes(path, limit=MAX_REF_BYTES)[:MAX_REF_BYTES].decode("utf-8", "replace")
        except OSError:
            continue
        yield path, text
        for m in _XINCLUDE.finditer(text):
            target = _literal_include(m.group(2).strip(), path, find, allow)
            if target is not None and target not in seen:
                queue.append(target)


def included_files(entry, find, max_files: int = MAX_REF_FILES) -> set[str]:
    """The files a model reads through its literal includes (itself included): what a library file's robots
    are found by."""
    return {os.path.realpath(path) for path, _ in literal_includes([entry], find, max_files)}
