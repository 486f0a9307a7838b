"""Resolve ROS package names to directories without ROS installed.

One chain, first hit wins: explicit mappings (`--package NAME=PATH`, config), the ament index under
AMENT_PREFIX_PATH, ROS_PACKAGE_PATH, the package that encloses the input, then a scan for package.xml
files around the input (the enclosing workspace). The resolver also knows the roots that files may be read from (the sandbox confines includes,
YAML and meshes to them).
"""
from __future__ import annotations

import os
import re
from pathlib import Path

_NAME = re.compile(rb"<name>\s*([^<\s]+)\s*</name>")
_SKIP_DIRS = {".git", "build", "install", "log", "node_modules", "__pycache__", ".venv", ".tox"}
SCAN_DEPTH = 6
SCAN_LIMIT = 5000  # directories visited at most


def package_name(package_xml: Path) -> str | None:
    try:
        with open(package_xml, "rb") as f:
            head = f.read(65536)
    except OSError:
        return None
    m = _NAME.search(head)
    return m.group(1).decode("utf-8", "replace") if m else None


def _below(path: str, base: str) -> bool:
    return path == base or path.startswith(base.rstrip(os.sep) + os.sep)


def leaves_cwd(path: str | os.PathLike, roots=()) -> bool:
    """`path` is written below the working directory but really lies outside it (and outside `roots`): a
    symbolic link, of the file or of a folder on the way, that a pull request could point at any file of the
    machine that runs the check (CI runs in the checkout)."""
    lexical = os.path.abspath(path)
    cwd = os.getcwd()
    if not _below(lexical, cwd):
        return False
    real = os.path.realpath(lexical)
    return not any(_below(real, os.path.realpath(r)) for r in (cwd, *roots))


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
    found: dict[str, Path] = {}
    visited = 0
    stack = [(root, 0)]
    while stack and visited < SCAN_LIMIT:
        d, depth = stack.pop()
        visited += 1
        try:
            entries = sorted(os.scandir(d), key=lambda e: e.name, reverse=True)
        except OSError:
            continue
        for e in entries:
            if e.name == "package.xml" and e.is_file():
                name = package_name(Path(e.path))
                if name and (name not in found or _closer(Path(d), found[name], near)):
                    found[name] = Path(d)
            elif depth < SCAN_DEPTH and e.is_dir(follow_symlinks=False) and e.name not in _SKIP_DIRS \
                    and not e.name.startswith("."):
                stack.append((Path(e.path), depth + 1))
    return found


def _closer(a: Path, b: Path, near: Path | None) -> bool:
    if near is None:
        return False

    def shared(p: Path) -> int:
        return len(os.path.commonpath([str(p), str(near)]))

    return shared(a) > shared(b)


class Resolver:
    def __init__(self, explicit: dict[str, str] | None = None, near: Path | None = None,
                 environ: dict | None = None):
        env = os.environ if environ is None else environ
        self.explicit = {k: Path(v).resolve() for k, v in (explicit or {}).items()}
        self._ament = [Path(p) for p in env.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
        self._ros = [Path(p) for p in env.get("ROS_PACKAGE_PATH", "").split(os.pathsep) if p]
        self.workspace = workspace_root(near) if near is not None else None
        self.near = near.resolve() if near is not None else None
        self._scanned: dict[str, Path] | None = None
        self._ros_scanned: dict[str, Path] | None = None
        self._own_pkg: tuple | None = None
        self.used: dict[str, Path] = {}

    def find(self, name: str) -> Path | None:
        hit = self._find(name)
        if hit is not None:
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
        if self.workspace is not None:
            if self._scanned is None:
                self._scanned = scan(self.workspace, self.near)
            if name in self._scanned:
                return self._scanned[name]
        return None

    def _own(self) -> tuple[str | None, Path | None]:
        """Name and folder of the package that encloses the input."""
        if self._own_pkg is None:
            self._own_pkg = own_package(self.near)
        return self._own_pkg

    def roots(self) -> list[Path]:
        """Folders that files may be read from."""
        out = [p.resolve() for p in self.explicit.values()]
        if self.workspace is not None:
            out.append(self.workspace.resolve())
        out.extend(p.resolve() for p in self.used.values())
        seen, uniq = set(), []
        for p in out:
            if p not in seen:
                seen.add(p)
                uniq.append(p)
        return uniq

    def allowed(self, path: str | Path) -> bool:
        real = Path(os.path.realpath(path))
        return any(real == r or r in real.parents for r in self.roots())

    def source_layout(self, path: str | Path) -> Path | None:
        """The source file behind an install-layout path, when `path` does not exist.

        CMake commonly installs `description/urdf` to `share/PKG/urdf`, so `$(find PKG)/urdf/x.xacro`
        names `PKG/description/urdf/x.xacro` in a source checkout. Look one or two folders down inside
        the package; use the match only when it is unique.
        """
        p = Path(os.path.abspath(path))
        for root in list(self.used.values()) + list(self.explicit.values()):
            root = Path(os.path.abspath(root))
            if root not in p.parents:
                continue
            rel = p.relative_to(root)
            hits = [c for c in root.glob(f"*/{rel}") if c.is_file()]
            if not hits:
                hits = [c for c in root.glob(f"*/*/{rel}") if c.is_file()]
            if len(hits) == 1:
                return hits[0]
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
