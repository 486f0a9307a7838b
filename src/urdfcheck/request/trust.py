"""Who may lower the guard: the person running the tool, never the files it checks (issue 19).

In CI on a pull request every file of the checkout is the attacker's, its configuration included. So what
lowers the guard -- `trusted` (stock xacro runs the model's Python), `allow_env` (environment values into the
report), limits raised above the defaults, paths outside the checkout -- counts only when it comes from the
command line, the environment, the Python API, or a config the command line names explicitly with
`--config FILE --trust-config`. A config found on disk (urdfcheck.yaml, .urdfcheck.yaml, [tool.urdfcheck],
a nested sub/urdfcheck.yaml) that asks for one gets an X018 finding at the key, and the key is ignored.

    screen(data, path, key_loc, trusted) -> [Finding]   # drops what an untrusted config may not say
    confine(full, root, trusted) -> str | None          # why a config path leaves the checkout, or None
    repo_root(folder) -> str                            # the repository a config belongs to
"""
from __future__ import annotations

import os

from urdfcheck.core.findings import Finding, Location, Severity

DEFAULT_MAX_ELEMENTS = 2_000_000  # load.loader.MAX_ELEMENTS (not imported: start-up)
GUARD_KEYS = ("trusted", "allow_env")


def _finding(message: str, loc: Location) -> Finding:
    return Finding("X018", Severity.WARNING, message, loc, name="untrusted-config")


def screen(data: dict, path: str, key_loc, trusted: bool) -> list[Finding]:
    """Remove from `data` (a parsed config) what only the person running the tool may set; one finding per key.
    Lower limits stay: tightening the guard is anyone's right."""
    if trusted:
        return []
    out = []
    how = "pass it on the command line, or name this config with --config FILE --trust-config"
    if data.get("trusted"):
        out.append(_finding("'trusted' in a config found in the checkout is ignored (it would run the model's "
                            f"Python with stock xacro); {how}", key_loc("trusted")))
    data.pop("trusted", None)
    if data.get("allow_env"):
        names = ", ".join(str(n) for n in data["allow_env"])[:200]
        out.append(_finding(f"'allow_env' ({names}) in a config found in the checkout is ignored (it would put "
                            f"environment values into the report); {how}", key_loc("allow_env")))
    data.pop("allow_env", None)
    out.extend(_keep_load_findings(data, key_loc))
    limit = data.get("max_elements")
    if isinstance(limit, int) and limit > DEFAULT_MAX_ELEMENTS:
        out.append(_finding(f"'max_elements: {limit}' above the default ({DEFAULT_MAX_ELEMENTS}) in a config found "
                            f"in the checkout is ignored; {how}", key_loc("max_elements")))
        data.pop("max_elements")
    return out


LOAD_PREFIX = "X0"  # load and sandbox findings: X001-X029


def _hides_load(pattern) -> bool:
    p = str(pattern).upper()
    return p == "ALL" or LOAD_PREFIX.startswith(p) or p.startswith(LOAD_PREFIX)


def _keep_load_findings(data: dict, key_loc) -> list[Finding]:
    """A config found in the checkout cannot deselect or soften load and sandbox findings (X0xx): a refused
    expansion must not become "All checks passed"."""
    out = []
    hidden = [p for p in data.get("ignore") or () if _hides_load(p)]
    if hidden:
        data["ignore"] = [p for p in data["ignore"] if not _hides_load(p)]
        out.append(_finding(f"'ignore: {', '.join(map(str, hidden))[:200]}' in a config found in the checkout does "
                            "not hide load and sandbox findings (X0xx); ignore them on the command line",
                            key_loc("ignore")))
    select = data.get("select")
    if select and not any(str(p).upper() in ("ALL", "X", LOAD_PREFIX) for p in select):  # X017 alone is not all
        data["select"] = [*select, LOAD_PREFIX]  # selected anyway: silently, as `select` lists what to add
    softened = [k for k in data.get("severity") or {} if _hides_load(k)]
    if softened:
        for k in softened:
            del data["severity"][k]
        out.append(_finding(f"'severity: {', '.join(map(str, softened))[:200]}' in a config found in the checkout "
                            "does not change load and sandbox findings (X0xx)", key_loc("severity")))
    return out


_ROOTS: dict[str, str] = {}


def repo_root(folder: str) -> str:
    """The nearest folder at or above `folder` holding `.git` (a repository or a worktree), else `folder`."""
    folder = os.path.realpath(folder)
    if folder not in _ROOTS:
        root = folder
        for d in (folder, *_parents(folder)):
            if os.path.exists(os.path.join(d, ".git")):
                root = d
                break
        _ROOTS[folder] = root
    return _ROOTS[folder]


def _parents(p: str):
    while True:
        up = os.path.dirname(p)
        if up == p:
            return
        yield up
        p = up


def _below(path: str, base: str) -> bool:
    return path == base or path.startswith(base.rstrip(os.sep) + os.sep)


def confine(full: str, root: str, trusted: bool) -> str | None:
    """Why `full` (a path a config names, already joined to its folder) may not be read, or None: its real
    path must stay in the config's repository or the working directory, as the loader keeps symlinks."""
    if trusted:
        return None
    real = os.path.realpath(full)
    bases = (repo_root(root), os.path.realpath(os.getcwd()))
    if any(_below(real, b) for b in bases):
        return None
    return ("leaves the checkout (a config found in the checkout may only name files inside its repository "
            "or the working directory; name it with --config FILE --trust-config to allow this)")
