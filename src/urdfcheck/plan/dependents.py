"""What depends on a file that is no robot: the targets a parameter file (YAML, cartographer's `.lua`, a MoveIt
`.srdf`) or a launch file that starts no robot, named by itself (the per-file pre-commit hook), stands for.

Such a file is no robot; a change to it matters to the robots and deployments that read it: the targets of its
workspace (the working directory when the file is below it, else its package) whose planned consumers read it
(controllers, drivers, launch parameters, included launch files), and the models of the package that holds it (a
model reads its own package's parameter files: `xacro.load_yaml`, the consumers found beside it). A config file
stands for its scope. A file nothing reads is an info line.

From a monorepo root (a workspace of many repositories) the workspace is not planned whole: only the launch files
that can reach the file are read (those naming its package or its file name, the launch files that name those,
and the launch files naming a model file (.urdf, .xacro) that names any of them: a Gazebo plugin's <parameters>,
until nothing new), with the workspace's packages resolvable, plus the models of its own package. A workspace
with a urdfcheck config is planned whole (a config may declare what reads the file).
"""
from __future__ import annotations

import os
from pathlib import Path

from urdfcheck.core.paths import shown

CONFIG_NAMES = ("urdfcheck.yaml", ".urdfcheck.yaml")
# files that change a contract without being a robot: parameters, cartographer's options, MoveIt's semantic model
SUFFIXES = (".yaml", ".yml", ".lua", ".srdf", ".srdf.xacro")
_KIND = {".yaml": "YAML", ".yml": "YAML", ".lua": ".lua", ".srdf": "SRDF", ".xacro": "SRDF"}
GREP_BYTES = 1024 * 1024  # a launch file is read this far for the names (a larger one is read by the planner)


def is_dependent(raw: str) -> bool:
    """A file named by itself that stands for the robots reading it (not a model, not an unusable name)."""
    return raw.lower().endswith(SUFFIXES)


def launch_or_readers(planner, raw: str, settings) -> list:
    """A launch file named by itself: the robots it starts; when it starts none (a controllers-only launch file
    that a bringup includes), the robots and deployments that read it, like a parameter file."""
    from urdfcheck.request.request import UsageError

    try:
        return planner.launch_targets(raw, settings)
    except UsageError:
        return targets_reading(planner, raw, settings, what="launch file that starts no robot and")


def targets_reading(planner, raw: str, settings, what: str | None = None) -> list:
    from urdfcheck.load.packages import enclosing_package

    path = os.path.abspath(raw)
    if os.path.basename(path) in CONFIG_NAMES:
        return planner.path_targets(os.path.dirname(path))
    here = os.path.abspath(planner.here)
    pkg = enclosing_package(Path(path).parent)
    ws = here if _below(path, here) else str(pkg or os.path.dirname(path))
    real = os.path.realpath(path)
    # no reader records a .lua, an SRDF or a launch file included under a condition: the launch files naming it
    named = set() if path.lower().endswith((".yaml", ".yml")) else _naming(planner, ws, path)
    out = []
    for t in _candidates(planner, ws, path, pkg, settings):
        own = enclosing_package(Path(os.path.abspath(t.path)).parent)
        if (own is not None and _below(real, os.path.realpath(own))) or real in _read_by(t) \
                or (t.deployment is not None and os.path.realpath(t.deployment.launch.file) in named):
            out.append(t)
    if not out:
        kind = what or f"{_KIND.get(os.path.splitext(path)[1].lower(), 'YAML')} file"
        planner.infos.append(f"{shown(raw)}: a {kind} that no robot or deployment of its "
                             "workspace reads: not linted")
    return out


def _candidates(planner, ws: str, path: str, pkg, settings) -> list:
    """The targets of `ws` that may read `path`: all of them when `ws` is the file's package (or holds a config),
    else the deployments of the launch files that can reach it and the own package's models."""
    if pkg is None or _below(ws, str(pkg)) or _listing(planner, ws)[1]:
        return planner.workspace_targets(ws)
    from urdfcheck.load.packages import own_package

    texts, models = _texts(planner, ws), _listing(planner, ws)[2]
    owners: dict[str, tuple] = {}

    def owner(p: str) -> tuple:
        folder = os.path.dirname(p)
        if folder not in owners:
            name, home = own_package(p)
            owners[folder] = (name.encode() if name else None, str(home) if home is not None else None)
        return owners[folder]

    # a file's name, as a launch file names it: with its package's name (find-pkg-share, get_package_share_directory)
    # or from inside that package; a package's name alone is a word of its own (a launch argument handed down an
    # include carries it). A generic name (bringup.launch.py) in another package names that package's own file:
    # from a corpus root, linorobot2's joy.yaml planned rosbot's simulation launch files through it.
    plain: set[bytes] = set()  # found anywhere: package names, names of files outside every package
    named_in: dict[bytes, set] = {}  # file name -> the (package name, package folder) of the files so named

    def add(p: str) -> None:
        name, home = owner(p)
        if home is None:
            plain.add(os.path.basename(p).encode())
            return
        named_in.setdefault(os.path.basename(p).encode(), set()).add((name, home))
        if name:
            plain.add(name)

    def names(p: str, text) -> bool:
        if text is None or any(w in text for w in plain):
            return True
        return any(w in text and any(_below(p, home) or (name and name in text) for name, home in where)
                   for w, where in named_in.items())

    add(path)
    chosen = {p for p in texts if _below(p, str(pkg))}  # the own package's launch files, whatever they name
    for p in chosen:
        add(p)
    reached: set[str] = set()
    grew = True
    while grew:  # the launch files naming a chosen one (an include), until nothing new
        grew = False
        # a model file naming a word reads it (a Gazebo plugin's <parameters>, an include, an argument's default):
        # the launch files naming that model deploy a reader (turtlebot4's launch file names its model, whose
        # include of create3.urdf.xacro names create3's control.yaml); an include may be relative, so any mention
        # of the file name counts here
        for p, text in models.items():
            if p not in reached and (text is None or any(w in text for w in (*plain, *named_in))):
                reached.add(p)
                add(p)
                grew = True
        for p, text in texts.items():
            if p not in chosen and names(p, text):
                chosen.add(p)
                add(p)
                grew = True
    from urdfcheck.plan.named import Named as _Named

    # as a plan of the whole workspace has them: these deployments found for `ws` (its packages resolvable), the
    # models they load linted through them only, the own package's other models with `ws`'s packages and variants
    root = os.path.abspath(ws)
    deps = planner.find(root, settings, files=sorted(chosen)) if chosen else []
    named = _Named(root, deps, {os.path.realpath(d.model) for d in deps})
    out = [planner.deployed(d, root, settings) for d in deps if not _below(d.launch.file, str(pkg))]
    return out + planner.discovered(str(pkg), planner.walk(str(pkg)), settings, named=named)


def _texts(planner, ws: str) -> dict:
    """The launch files of `ws` and their bytes (read once per run and workspace)."""
    return _listing(planner, ws)[0]


def _listing(planner, ws: str) -> tuple[dict, bool, dict]:
    """One pass over `ws` (as the deployment finder lists it): its launch files with their bytes, whether a
    urdfcheck config sits anywhere in it, and its model files (.urdf, .xacro) with their bytes."""
    memo = planner.__dict__.setdefault("_dependents_listing", {})
    if ws not in memo:
        from urdfcheck.core import door
        from urdfcheck.load.discover import _walk
        from urdfcheck.plan.deployments import _is_launch
        from urdfcheck.request.config import PYPROJECT, _pyproject_has_table

        # every plan of `ws` makes it a root of the run (its Resolver names it as the workspace): the name search
        # reads what that plan reads. Before, a launch file of a sibling repository was refused here, kept as "may
        # name the file" and planned: from a corpus root, 77 launch files for one SRDF macro.
        door.add_root(ws)
        texts, models, config = {}, {}, False
        for folder, name in _walk(os.path.abspath(ws), 20_000):  # plan.deployments.launch_files' walk
            if _is_launch(name):
                texts[os.path.join(folder, name)] = None
            elif name.lower().endswith((".urdf", ".xacro")):
                models[os.path.join(folder, name)] = None
            elif name in CONFIG_NAMES or (name == PYPROJECT and _pyproject_has_table(Path(folder, name))):
                config = True
        memo[ws] = ({p: _head(p) for p in texts}, config, {p: _head(p) for p in models})
    return memo[ws]


def _naming(planner, ws: str, path: str) -> set[str]:
    """The launch files of `ws` that name `path` (its file name, and its package's name unless they are in that
    package: a file of another package is found through it), and those that include them, named the same way."""
    from urdfcheck.load.packages import own_package

    texts = _texts(planner, ws)
    found: dict[str, None] = {}
    todo = [path]
    while todo:
        target = todo.pop()
        word = os.path.basename(target).encode()
        name, folder = own_package(target)
        for p, text in texts.items():
            if p in found or p == target or text is None or word not in text:
                continue
            if folder is not None and not _below(p, str(folder)) and (not name or name.encode() not in text):
                continue  # names a file of that name in another package
            found[p] = None
            todo.append(p)
    return {os.path.realpath(p) for p in found}


def _head(path: str) -> bytes | None:
    """The launch file's bytes for the name search (None: not readable here, so it is kept)."""
    from urdfcheck.core import door

    try:
        data = door.read_bytes(path, limit=GREP_BYTES)
    except OSError:
        return None
    return None if len(data) > GREP_BYTES else data


def _read_by(t) -> set[str]:
    if t._contracts is None:  # consumers found beside the model once it is built: its package (above)
        return set()
    consumers = t.contracts
    files = getattr(consumers, "files", None) or {}
    return {os.path.realpath(p) for paths in files.values() for p in paths}


def _below(path: str, base: str) -> bool:
    return path == base or path.startswith(base.rstrip(os.sep) + os.sep)
