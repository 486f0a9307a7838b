"""`lint --config-from REV`: the config of a git revision (the pull request's base), trusted, for the working tree.

On a pull request the checkout's config is the author's: it could hide the very findings the pull request adds
(issue 36). The runner names a revision whose config was reviewed; its file (`urdfcheck.yaml`, `.urdfcheck.yaml`,
or `pyproject.toml` with `[tool.urdfcheck]`, the nearest above the first path, as `find_config` looks in the
working tree) is read through the git door into a private temporary folder and handed to the run as
`--config FILE --trust-config`. Its relative paths (models, controllers, launch files, drivers, bags, packages)
are made absolute against the folder the config has in the repository, so they name the working tree's files.
Whether the checkout's own config differs from it is one info line.
"""
from __future__ import annotations

import os
import re
import shutil
import tempfile

from urdfcheck.core import git

MAX_CONFIG = 1024 * 1024


class BaseConfig:
    """`path`: the temporary config to use (None: REV has no config, run with none); `shown`: REV:relative path;
    `info`: what to tell the runner. Remove with `cleanup` (or as a context manager)."""

    def __init__(self, folder: str | None, path: str | None, shown: str, info: str, data: bytes = b"",
                 found: str = ""):
        self.folder, self.path, self.shown, self.info = folder, path, shown, info
        self.data, self.found = data, found
        self.said: dict[str, str] = {}  # a path made absolute -> as the config wrote it (for `scrub`)
        self.tree_dirs: list[str] = []  # the config's folder in the base revision's temporary tree (`for_tree`)

    def for_tree(self, in_tree) -> str | None:
        """The same config with its paths in another tree (`lint --diff-base`: the base revision's files);
        `in_tree(path)` maps a working-tree path there."""
        if self.path is None:
            return None
        sub = tempfile.mkdtemp(prefix="base-", dir=self.folder)
        tree_dir = _tree_dir(self.config_dir, in_tree)
        self.tree_dirs.append(os.path.normpath(tree_dir))
        return _rewrite(self.data, os.path.basename(self.found), sub, tree_dir, self.said)

    def cleanup(self) -> None:
        if self.folder:
            shutil.rmtree(self.folder, ignore_errors=True)

    def scrub(self, text: str, root: str | None = None) -> str:
        """`text` with the temporary config's path (absolute, or relative to here or to --root) replaced by
        REV:path."""
        if not self.path:
            return text
        # a path the rewrite made absolute, as the config wrote it: one that leaves the config's folder (`../x`)
        # would otherwise show the runner's tree or the base revision's temporary folder
        for full in sorted(self.said, key=len, reverse=True):
            text = text.replace(full, self.said[full])
        # whatever form a report gives it (absolute, relative to here, to --root or to the checkout's top)
        name = re.escape(os.path.basename(self.folder))
        text = re.sub(r"[^\s'\"(]*" + name + r"/(?:base-[^/\s]+/)?urdfcheck\.yaml", self.shown, text)
        config_dir = getattr(self, "config_dir", None)
        if config_dir:  # its paths were made absolute in the working tree: shown relative again
            rel = os.path.relpath(config_dir, root or os.getcwd())
            # and in the base revision's temporary tree (`lint --diff-base REV --config-from REV`): a model the
            # base revision lacks (a link git keeps but the copy leaves out) named that temporary folder
            for d in sorted([*self.tree_dirs, config_dir], key=len, reverse=True):
                text = text.replace(d.rstrip(os.sep) + os.sep, "" if rel == "." else rel + os.sep)
        return text

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.cleanup()


def _names_in(entries) -> set[str]:
    return {n.decode("utf-8", "surrogateescape") for n, mode, _ in entries if mode in ("100644", "100755")}


def find_in(names: set[str], rel_dir: str, read) -> str | None:
    """The config of the revision that applies to the folder `rel_dir` (relative to the repository): nearest
    first, as `request.config.find_config` looks on disk."""
    from urdfcheck.request.config import CONFIG_NAMES, PYPROJECT

    d = rel_dir.strip("/")
    while True:
        for name in (*CONFIG_NAMES, PYPROJECT):
            p = f"{d}/{name}" if d and d != "." else name
            if p not in names:
                continue
            if name != PYPROJECT:
                return p
            text = (read(p) or b"").decode("utf-8", "replace")
            if re.search(r"^\s*\[\[?\s*tool\.urdfcheck(\s*\]|\.)", text, re.M):
                return p
        if not d or d == ".":
            return None
        d = os.path.dirname(d)


def _only_below(names: set[str], rel_dir: str, read, rev: str) -> str | None:
    """No config above the path: the one config below it, when there is exactly one (a repository of one
    package, linted from its root)."""
    from urdfcheck.request.config import CONFIG_NAMES, PYPROJECT

    prefix = "" if rel_dir in ("", ".") else rel_dir.replace(os.sep, "/").rstrip("/") + "/"
    below = sorted(n for n in names if n.startswith(prefix) and os.path.basename(n) in CONFIG_NAMES)
    below += sorted(n for n in names if n.startswith(prefix) and os.path.basename(n) == PYPROJECT
                    and find_in({n}, os.path.dirname(n), read) == n)
    folders = {os.path.dirname(n) for n in below}
    if len(folders) > 1:
        raise git.GitError(f"{git.shown_name(rev.encode())} holds {len(folders)} configs below this path; name the "
                           "package to lint (urdfcheck lint --config-from REV PATH)")
    return below[0] if below else None


def load(rev: str, start: str) -> BaseConfig:
    """The config `rev` has for `start` (a path the runner named, or the working directory)."""
    repo = git.find(os.path.abspath(start))
    if repo is None:
        raise git.GitError("no git repository (a .git folder) around " + git.shown_name(os.fsencode(start)))
    commit = repo.commit(rev)
    real = os.path.realpath(os.path.abspath(start))
    rel_dir = os.path.relpath(real if os.path.isdir(real) else os.path.dirname(real), repo.work_tree)
    if rel_dir == ".." or rel_dir.startswith(".." + os.sep):
        raise git.GitError("the path lies outside the repository")
    names = _names_in(repo.tree(commit))

    def read(p):
        return repo.read(commit, p, MAX_CONFIG)

    from urdfcheck.request.config import find_config

    mine = find_config(start)
    found = find_in(names, rel_dir.replace(os.sep, "/"), read) or _only_below(names, rel_dir, read, rev)
    rev_shown = git.shown_name(rev.encode())
    if found is None:
        info = f"--config-from {rev_shown}: the revision has no config for this path; running with none"
        if mine:
            info += f" (the checkout's {_rel(mine)} is not used)"
        return BaseConfig(None, None, rev_shown, info)
    data = read(found)
    if data is None or len(data) > MAX_CONFIG:
        raise git.GitError(f"{rev_shown}:{found}: not a readable config")
    folder = tempfile.mkdtemp(prefix="urdfcheck-cfg-")
    try:
        config_dir = os.path.join(repo.work_tree, os.path.dirname(found))
        said: dict[str, str] = {}
        path = _rewrite(data, os.path.basename(found), folder, config_dir, said)
    except BaseException:
        shutil.rmtree(folder, ignore_errors=True)
        raise
    same_place = os.path.join(repo.work_tree, found)
    if os.path.isfile(same_place):
        mine = same_place
    shown = f"{rev_shown}:{found}"
    info = f"--config-from {rev_shown}: using {shown} (trusted)"
    if mine is None:
        info += "; the checkout has no config of its own"
    else:
        from urdfcheck.core import door

        try:
            same = door.read_bytes(mine, limit=MAX_CONFIG) == data
        except OSError:
            same = False
        where = _rel(mine)
        info += (f"; the checkout's {where} is the same" if same else
                 f"; the checkout's {where} differs from it (not used: what this change does to the config "
                 "is not applied)")
    from urdfcheck.core import door

    door.add_root(folder)  # in a guarded run, the config is readable (the runner named the revision)
    out = BaseConfig(folder, path, shown, info, data, found)
    out.config_dir = config_dir
    out.said = said
    return out


def _tree_dir(config_dir: str, in_tree) -> str:
    """The folder in another tree that matches `config_dir` of the working tree (the nearest existing one)."""
    d = config_dir
    while True:
        mapped = in_tree(d)
        if mapped is not None:
            return os.path.join(mapped, os.path.relpath(config_dir, d))
        up = os.path.dirname(d)
        if up == d:
            return config_dir
        d = up


def _rel(p: str) -> str:
    r = os.path.relpath(p)
    return r if not r.startswith("..") else os.path.basename(p)


# keys whose values are paths relative to the config's folder (request/config.py `resolve`)
_MODEL_LISTS = ("controllers", "launch", "localization", "bags")


def _rewrite(data: bytes, name: str, folder: str, config_dir: str, said: dict | None = None) -> str:
    """Write the config into `folder` as YAML, its relative paths made absolute against `config_dir`; `said`
    gets each absolute path -> the text the config wrote."""
    from urdfcheck.request.config import PYPROJECT, ConfigError, _read_pyproject, _read_yaml
    from urdfcheck.request.request import UsageError

    raw = os.path.join(folder, name)
    with open(raw, "wb") as f:  # our own private file
        f.write(data)
    try:
        table = (_read_pyproject if name == PYPROJECT else _read_yaml)(raw)[0]
    except ConfigError as e:
        raise UsageError(f"--config-from: {e.args[0] if e.args else 'invalid config'}") from None
    os.unlink(raw)
    table = _plain(table)
    if not isinstance(table, dict):
        raise UsageError("--config-from: the config must be a mapping of keys")

    def absolute(p):
        if not isinstance(p, str):
            return p
        full = os.path.normpath(os.path.join(config_dir, p))
        rel = os.path.relpath(full, config_dir)
        if said is not None and (rel == ".." or rel.startswith(".." + os.sep)) and full != p and len(full) > 1:
            said[full] = p  # a path below config_dir is shown relative by `scrub` already
        return full

    for m in table.get("models") or []:
        if not isinstance(m, dict):
            continue
        if "path" in m:
            m["path"] = absolute(m["path"])
        for key in _MODEL_LISTS:
            if isinstance(m.get(key), list):
                m[key] = [absolute(p) for p in m[key]]
        for d in m.get("drivers") or []:
            if isinstance(d, dict) and "file" in d:
                d["file"] = absolute(d["file"])
    if isinstance(table.get("packages"), dict):
        table["packages"] = {k: absolute(v) for k, v in table["packages"].items()}
    from urdfcheck.core.yamlimport import yaml

    out = os.path.join(folder, "urdfcheck.yaml")
    with open(out, "w", encoding="utf-8") as f:
        yaml.safe_dump(table, f, sort_keys=False, allow_unicode=True)
    return out


def _plain(v):
    if isinstance(v, dict):
        return {str(k): _plain(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    if isinstance(v, (str, int, float, bool)) or v is None:
        return v
    return str(v)
