"""The `lint` command: config + flags -> targets -> findings -> reports -> exit code."""
from __future__ import annotations

import os
import sys

from urdfcheck.rules import engine
from urdfcheck.core.findings import Severity
from urdfcheck.pipeline.run import Target, lint_targets, missing_paths, targets_for


# parsed documents a one-shot process keeps until it exits (lint.lint_targets: `retain`)
_UNTIL_EXIT: list = []


def _selection(ns, cfg) -> engine.Selection:
    select = [c for group in ns.select for c in group] or list(getattr(cfg, "select", None) or ["ALL"])
    ignore = list(getattr(cfg, "ignore", None) or []) + [c for group in ns.ignore for c in group]
    severity = {}
    for code, level in (getattr(cfg, "severity", None) or {}).items():
        severity[code] = level if isinstance(level, Severity) else Severity.parse(level)
    options = dict(getattr(cfg, "rules", None) or {})
    return engine.Selection(tuple(select), tuple(ignore), severity, options)


def _config(ns, usage_error):
    if ns.no_config:
        return None
    try:
        from urdfcheck.pipeline import config as cfgmod
    except ImportError:
        return None
    path = ns.config
    if path is None:
        start = ns.paths[0] if ns.paths else os.getcwd()
        start = start if os.path.isdir(start) else os.path.dirname(os.path.abspath(start))
        path = cfgmod.find_config(start)
        if path is None:
            return None
    elif not os.path.isfile(path):
        raise usage_error(f"no such config file: {path}")
    try:
        return cfgmod.load_config(path)
    except cfgmod.ConfigError as e:
        where = getattr(e, "location", None)
        raise usage_error(f"invalid config {where or path}: {e}") from None


def _targets(ns, cfg) -> list[Target]:
    args = dict(ns.args)
    packages = dict(ns.packages)
    trusted = getattr(ns, "trusted", False) or bool(getattr(cfg, "trusted", False))
    if cfg is not None and hasattr(cfg, "targets"):
        return cfg.targets(paths=ns.paths or None, args=args, packages=packages, trusted=trusted)
    return targets_for(ns.paths or ["."], args, packages, trusted=trusted)


def run(ns, usage_error) -> int:
    missing = missing_paths(ns.paths)
    if missing:
        raise usage_error(f"no such file or folder: {', '.join(missing)}")
    cfg = _config(ns, usage_error)
    selection = _selection(ns, cfg)
    targets = _targets(ns, cfg)
    if not targets:
        raise usage_error(f"no URDF or xacro model found in {', '.join(ns.paths or ['.'])}")
    trusted = ns.trusted or bool(getattr(cfg, "trusted", False))
    allow_env = tuple(ns.allow_env) + tuple(getattr(cfg, "allow_env", ()) or ())
    result = lint_targets(targets, selection, trusted=trusted, allow_env=allow_env, timeout=ns.timeout,
                          config=cfg, max_elements=ns.max_elements or getattr(cfg, "max_elements", None),
                          retain=_UNTIL_EXIT if getattr(ns, "one_shot", False) else None)
    fail_on = ns.fail_on or _cfg_fail_on(cfg) or Severity.WARNING

    if ns.write_baseline or ns.baseline:
        from urdfcheck.report import baseline

        if ns.write_baseline:
            baseline.write(ns.write_baseline, result.findings)
            print(f"wrote {len(result.findings)} findings to {ns.write_baseline}", file=sys.stderr)
            return 0
        try:
            result.findings = baseline.filter_new(ns.baseline, result.findings)
        except (OSError, ValueError) as e:
            raise usage_error(f"cannot read baseline {ns.baseline}: {e}") from None

    from urdfcheck.report import render

    colour = ns.color == "always" or (ns.color == "auto" and ns.output is None and sys.stdout.isatty()
                                      and not os.environ.get("NO_COLOR"))
    text = render(ns.format, result, colour=colour, fail_on=fail_on)
    if ns.output:
        _write(ns.output, text, usage_error)
    else:
        sys.stdout.write(text)
    for fmt, path in ns.report:
        try:
            extra = render(fmt, result, colour=False, fail_on=fail_on)
        except ValueError as e:
            raise usage_error(str(e)) from None
        _write(path, extra, usage_error)
    return 1 if result.failed(fail_on) else 0


def _cfg_fail_on(cfg):
    level = getattr(cfg, "fail_on", None)
    if level is None:
        return None
    return level if isinstance(level, Severity) else Severity.parse(level)


def _write(path: str, text: str, usage_error) -> None:
    try:
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
    except OSError as e:
        raise usage_error(f"cannot write {path}: {e.strerror}") from None
