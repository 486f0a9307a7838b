"""urdfcheck: a model-contract linter and verification suite for ROS robot descriptions.

Public API (the CLI uses exactly this):

    urdfcheck.load(path, args=None, **options) -> Model          # raises LoadError with findings
    urdfcheck.expand(path, args=None, **options) -> Expanded     # expanded XML + source map + findings
    urdfcheck.lint(paths, args=None, select=..., ignore=..., **options) -> Result
"""
from __future__ import annotations

__version__ = "0.1.0"
__all__ = ["load", "expand", "lint", "Finding", "Location", "Severity", "LoadError", "__version__"]

from urdfcheck.core.findings import Finding, Location, Severity  # noqa: E402  (tiny, no heavy imports)


def load(path, args=None, **options):
    from urdfcheck.load.loader import load_model

    return load_model(path, args, **options)


def expand(path, args=None, **options):
    from urdfcheck.load.loader import expand as _expand

    return _expand(path, args, **options)


def lint(paths, args=None, *, select=("ALL",), ignore=(), packages=None, **options):
    from urdfcheck.rules import engine
    from urdfcheck.pipeline.run import lint_targets, targets_for

    if isinstance(paths, (str, bytes)) or hasattr(paths, "__fspath__"):
        paths = [paths]
    targets = targets_for([str(p) for p in paths], args, packages, trusted=bool(options.get("trusted")))
    return lint_targets(targets, engine.Selection(tuple(select), tuple(ignore)), **options)


def __getattr__(name):
    if name == "LoadError":
        from urdfcheck.load.loader import LoadError

        return LoadError
    raise AttributeError(name)
