"""How a consumer file was paired with a model (issue 37): by reference first, then as the only model of its
package, then by the joint names it shares with the model; never by "same package" alone.

In a package of several models (a robot and its older variant, a fiducial grid, a dock), a parameter file that
one model names (a Gazebo plugin's `<parameters>` in the model's files; a launch file that mentions that model
and loads the file) belongs to that model: it is checked against it as evidence, and never against the package's
other models. A file no model names is checked against a model whose joints it names, as a guess (the engine
says its findings at info, `core.evidence`).

    references(entry, package_root, models, find) -> (mine, others)   # realpaths named for entry / for others
    step(path, how, model) -> core.evidence.Step
"""
from __future__ import annotations

import os
import re

from urdfcheck.core import lazyre

_COMMENT = lazyre.compile(r"<!--.*?(?:-->|\Z)", re.S)
_PLUGIN = lazyre.compile(r"<plugin\b[^>]*>(.*?)</plugin>", re.S)
_PARAMS = lazyre.compile(r"<parameters>\s*([^<]+?)\s*</parameters>")
_FIND = lazyre.compile(r"^\$\(\s*find(?:-pkg-share)?\s+([A-Za-z0-9_]+)\s*\)(/[^$]*)$")
MAX_LAUNCH_BYTES = 2 * 1024 * 1024

CONFIRM = ("name it under models: in urdfcheck.yaml (controllers:, drivers: or localization: of this model), or "
           "load it from a launch file that runs this model")


def step(path: str, how: str, model: str = ""):
    from urdfcheck.core.evidence import Step
    from urdfcheck.core.paths import shown

    subject = shown(path) + (f" for {shown(model)}" if model else "")
    params = path.endswith((".yaml", ".yml"))
    confirm = CONFIRM if params else "name it under models: in urdfcheck.yaml (launch: of this model)"
    return Step("parameters" if params else "launch", subject, how,
                "" if how in ("referenced", "launched", "config", "only") else confirm)


def plugin_files(entry: str, find) -> set[str]:
    """Realpaths of the files a model's Gazebo plugins name in `<parameters>` (`$(find pkg)/x.yaml`), read as
    text through the model's literal includes."""
    from urdfcheck.load.packages import literal_includes

    out = set()
    for _path, text in literal_includes([entry], find):
        for block in _PLUGIN.finditer(_COMMENT.sub("", text)):
            for m in _PARAMS.finditer(block.group(1)):
                hit = _FIND.match(m.group(1).strip())
                root = find(hit.group(1)) if hit else None
                if root:
                    out.add(os.path.realpath(root + hit.group(2)))
    return out


def named_in(text: bytes, name: str) -> bool:
    return re.search(rb"(?<![\w.-])" + re.escape(name.encode()) + rb"(?![\w.-])", text) is not None


def _name_of(path: str, paths) -> str:
    """How a launch file names `path`: its file name, or with its folder when another file shares the name."""
    base = os.path.basename(path)
    if sum(os.path.basename(p) == base for p in paths) > 1:
        return "/".join(path.replace("\\", "/").split("/")[-2:])
    return base


def launch_files_named(launches, models, params) -> dict[str, set[str]]:
    """model realpath -> the parameter files (realpaths) a launch file that mentions that model (by file name)
    loads (names by file name): a launch file naming two models pairs its files with both."""
    from urdfcheck.core import door
    from urdfcheck.load.packages import leaves_cwd

    out: dict[str, set[str]] = {}
    for lf in launches:
        if leaves_cwd(lf):
            continue
        try:
            text = door.read_bytes(lf, limit=MAX_LAUNCH_BYTES)
        except OSError:
            continue
        named = [m for m in models if named_in(text, os.path.basename(m))]
        if not named:
            continue
        files = {os.path.realpath(p) for p in params if named_in(text, _name_of(p, params))}
        for m in named:
            out.setdefault(os.path.realpath(m), set()).update(files)
    return out


def references(entry: str, root: str, models, params, launches, find) -> tuple[set[str], set[str]]:
    """(files named for `entry`, files named for the package's other models and not for `entry`)."""
    me = os.path.realpath(entry)
    by_model = {os.path.realpath(m): plugin_files(m, find) for m in {*models, entry}}
    for m, files in launch_files_named(launches, {*models, entry}, params).items():
        by_model.setdefault(m, set()).update(files)
    mine = by_model.get(me, set())
    others = set().union(*(f for m, f in by_model.items() if m != me)) - mine if by_model else set()
    return mine, others


def finder(root: str, packages=None):
    """A package finder for `$(find pkg)`: the explicit packages, else the enclosing package by its name."""
    from pathlib import Path

    from urdfcheck.load.packages import package_name

    own = package_name(Path(root) / "package.xml")
    pk = dict(packages or {})

    def find(name: str):
        if name in pk:
            return str(pk[name])
        return root if name == own else None
    return find


def others_files(skipped) -> list:
    """Parameter files left to the package's other models: what they supply (a localization node, a drive) may
    also run beside this one, so an absence claimed here is not failed (consumers.openworld)."""
    if not skipped:
        return []
    from urdfcheck.core.findings import Location
    from urdfcheck.core.paths import shown

    return [(f"{', '.join(shown(p) for p in skipped[:3])} (named for another model of the package, not read "
             "for this one)", Location(skipped[0]))]


def drop_unloaded(c, files, model) -> None:
    """Controller files read because the model's Gazebo ros2_control plugin names them (as text, through every
    branch): when the expanded model has no plugin naming one, these xacro arguments do not load it (the plugin
    sits in a branch they do not take). Its controllers are dropped, and what they would supply is not known."""
    from urdfcheck.core.findings import Location
    from urdfcheck.core.paths import shown

    named = [p.text.strip() for pl in getattr(model, "plugins", ()) for p in pl.params if p.tag == "parameters"]
    gone = [f for f in files if not any(n.endswith("/" + os.path.basename(f)) or n == os.path.basename(f)
                                        for n in named)]
    if not gone:
        return
    real = {os.path.realpath(f) for f in gone}
    ctrls = c.controllers.controllers
    for key in [k for k, ctl in ctrls.items() if os.path.realpath(getattr(ctl, "file", "") or "") in real]:
        del ctrls[key]
    for key in ("controllers",):
        if key in c.files:
            c.files[key] = [f for f in c.files[key] if os.path.realpath(f) not in real]
    c.pairing = {k: v for k, v in c.pairing.items() if k not in real}
    c.unknown = list(c.unknown or ()) + [(f"{shown(gone[0])} (the model's Gazebo ros2_control plugin loads it "
                                          "under other xacro arguments)", Location(gone[0]))]
