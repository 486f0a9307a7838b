"""urdfcheck: a model-contract linter and verification suite for ROS robot descriptions.

Public API (the CLI uses exactly this):

    urdfcheck.load(path, args=None, **options) -> Model          # raises LoadError with findings
    urdfcheck.expand(path, args=None, **options) -> Expanded     # expanded XML + source map + findings
    urdfcheck.lint(paths=(), **options) -> Result                  # like `urdfcheck lint`, config included
    urdfcheck.UsageError                                           # an unusable request (the CLI's exit 2)

`load` and `expand` read the config files `lint` reads (its packages and limits). Their options and `lint`'s
are the `LintRequest` fields (request/request.py): args, packages, select, ignore, severity, rules, fail_on,
trusted, allow_env, timeout, max_elements, config, no_config, root, baseline.
"""
from __future__ import annotations

__version__ = "0.1.0"
__all__ = ["load", "expand", "lint", "Finding", "Location", "Severity", "LoadError", "UsageError", "__version__"]

import urdfcheck.core.pathimport  # noqa: E402, F401  (pathlib without urllib.parse, before anything imports it)
import urdfcheck.load as _load_package  # noqa: E402  (empty __init__: cheap)


def _load(path, args=None, **options):
    """The model at `path` as `urdfcheck lint` loads it: the config found upward (its packages and limits),
    `options` over it (the `lint` options). Raises LoadError with the findings when it does not load."""
    from urdfcheck.core.findings import Severity

    loaded = _loaded(path, args, options)
    findings = loaded.expanded.findings
    errors = [f for f in findings if f.severity >= Severity.ERROR]
    if loaded.model is None or errors:
        from urdfcheck.load.loader import LoadError

        raise LoadError(errors or findings)
    return loaded.model


class _CallablePackage(type(_load_package)):
    """`urdfcheck.load` is both the sub-package `load/` and the API function: a package attribute named like a
    sub-package is replaced by the sub-package whenever one of its modules is imported first, so the package
    itself is callable (`urdfcheck.load(path)`), and `import urdfcheck.load.packages` keeps working."""

    def __call__(self, path, args=None, **options):
        return _load(path, args, **options)


_load_package.__class__ = _CallablePackage
load = _load_package


def expand(path, args=None, **options):
    """The expanded document (source map, load findings) the rules of `urdfcheck lint` see."""
    return _loaded(path, args, options, build=False).expanded


def _loaded(path, args, options, build=True):
    from urdfcheck.request.request import make_request
    from urdfcheck.run import load as load_one

    return load_one(make_request([path], args=args, **options), path, build=build)


def lint(paths=(), args=None, **options):
    """Lint like `urdfcheck lint PATHS...` from the working directory: the same config files (found upward
    from each path, one per package in a workspace), the same findings. Callable any number of times.
    Returns a `run.Result` (`.findings`, `.failed()`); raises UsageError where the CLI exits 2."""
    from urdfcheck.request.request import make_request
    from urdfcheck.run import run

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
        from urdfcheck.request.request import UsageError

        return UsageError
    raise AttributeError(name)
