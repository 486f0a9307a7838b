"""urdfcheck: a model-contract linter and verification suite for ROS robot descriptions.

Public API (the CLI uses exactly this):

    urdfcheck.load(path, args=None, **options) -> Model          # raises LoadError with findings
    urdfcheck.expand(path, args=None, **options) -> Expanded     # expanded XML + source map + findings
    urdfcheck.lint(paths=(), **options) -> Result                  # like `urdfcheck lint`, config included
    urdfcheck.UsageError                                           # an unusable request (the CLI's exit 2)

`lint` options are the `LintRequest` fields (pipeline/request.py): args, packages, select, ignore, severity,
rules, fail_on, trusted, allow_env, timeout, max_elements, config, no_config, root, baseline.
"""
from __future__ import annotations

__version__ = "0.1.0"
__all__ = ["load", "expand", "lint", "Finding", "Location", "Severity", "LoadError", "UsageError", "__version__"]



def load(path, args=None, **options):
    from urdfcheck.load.loader import load_model

    return load_model(path, args, **options)


def expand(path, args=None, **options):
    from urdfcheck.load.loader import expand as _expand

    return _expand(path, args, **options)


def lint(paths=(), args=None, **options):
    """Lint like `urdfcheck lint PATHS...` from the working directory: the same config files (found upward
    from each path, one per package in a workspace), the same findings. Callable any number of times.
    Returns a `pipeline.run.Result` (`.findings`, `.failed()`); raises UsageError where the CLI exits 2."""
    from urdfcheck.pipeline.request import make_request
    from urdfcheck.pipeline.run import run

    return run(make_request(paths, args=args, **options))


def __getattr__(name):
    # on first use: a cached lint run (cli/cache.py) answers without importing them (enum, re: 15 ms)
    if name in ("Finding", "Location", "Severity"):
        from urdfcheck.core import findings

        return getattr(findings, name)
    if name == "LoadError":
        from urdfcheck.load.loader import LoadError

        return LoadError
    if name == "UsageError":
        from urdfcheck.pipeline.request import UsageError

        return UsageError
    raise AttributeError(name)
