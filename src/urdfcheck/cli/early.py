"""What the console decides before it imports anything else (cli/cache.py `fork_early`, cli/main.py): whether a
lint could expand xacro (then it forks the xacro worker early) and whether it reads a YAML config (then PyYAML is
imported once, before that fork). Plain functions over the file system: no import of the rest of the tool."""
from __future__ import annotations

import os


def reads_yaml_config(config: str | None, paths: list[str]) -> bool:
    """Will this lint read a YAML config (`--config FILE.yaml`, or an urdfcheck.yaml at or above a path)? Then this
    process imports PyYAML anyway, which the worker always imports (xacro does): imported once, before the fork,
    instead of on both sides (~6 ms of CPU; issue 38's goal is the CPU of xacro then check_urdf per variant). A
    run without one keeps PyYAML out of this process (its parameter files are parsed in the worker)."""
    if config is not None:
        return config.lower().endswith((".yaml", ".yml"))
    names = ("urdfcheck.yaml", ".urdfcheck.yaml")  # request.config.CONFIG_NAMES (not imported: start-up)
    for p in paths:
        d = os.path.abspath(p)
        d = d if os.path.isdir(d) else os.path.dirname(d)
        while True:
            if any(os.path.isfile(os.path.join(d, n)) for n in names):
                return True
            up = os.path.dirname(d)
            if up == d:
                break
            d = up
    return False


def may_hold_xacro(paths: list[str], config: str | None = None, max_dirs: int = 2000,
                   yaml_config: bool | None = None) -> bool:
    """Could this lint expand xacro? A .xacro path, a folder holding one (looked for until the first, in at most
    `max_dirs` folders: past that, assume so), or a config (it may declare a model elsewhere). A package of plain
    URDFs then starts no xacro worker, whose imports are a sixth of its lint; a xacro reached only through a
    launch file elsewhere is expanded in a worker started then (load.loader), as without a spare."""
    if config is not None and config != "":
        return True
    if config is None and (reads_yaml_config(None, paths) if yaml_config is None else yaml_config):
        return True
    budget = [max_dirs]
    return any(p.endswith(".xacro") or (os.path.isdir(p) and _xacro_below(p, budget)) for p in paths)


def _xacro_below(top: str, budget: list) -> bool:
    stack = [top]
    while stack:
        if budget[0] <= 0:
            return True
        budget[0] -= 1
        try:
            with os.scandir(stack.pop()) as it:
                for e in it:
                    if e.name.endswith(".xacro"):
                        return True
                    if not e.name.startswith(".") and e.is_dir(follow_symlinks=False):
                        stack.append(e.path)
        except OSError:
            continue
    return False
