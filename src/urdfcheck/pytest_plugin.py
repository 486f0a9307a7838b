"""pytest plugin: every robot model of a description package becomes a test item.

Registered through the `pytest11` entry point, so installing urdfcheck is enough. It is active when

* pytest runs with `--urdfcheck`, or
* the pytest rootdir holds a urdfcheck config (`urdfcheck.yaml`, `.urdfcheck.yaml`, or `pyproject.toml`
  with `[tool.urdfcheck]`).

The models are what the config declares (each variant is its own item) and the entry models found below the
rootdir that it does not declare (a config found in the checkout adds, never hides: issue 36); what the config
asked and was refused (X018) is the item `urdfcheck-config`. An item fails when the model has findings at or
above the fail level (`--urdfcheck-fail-on`, else the config's `fail_on` when it may set it, else `warning`);
the failure text lists the located
findings. The plugin makes the request `urdfcheck lint` run in the rootdir makes and runs the same pipeline
(plan/plan.py, run.py) once, on the first item: every item shows its model's share, and an unused
suppression in a YAML file fails the item of the first model that read the file, as R002 fails the CLI.
Items are marked `urdfcheck`: `pytest -m urdfcheck` runs only them, `-m "not urdfcheck"` skips
them, `-p no:urdfcheck` turns the plugin off.
"""
from __future__ import annotations

import os
from pathlib import Path
from types import SimpleNamespace

import pytest

_STATE = "_urdfcheck_state"


def pytest_addoption(parser):
    group = parser.getgroup("urdfcheck", "robot description lint (urdfcheck)")
    group.addoption("--urdfcheck", action="store_true", default=False,
                    help="lint the package's URDF/xacro models as test items (automatic when the rootdir "
                         "has a urdfcheck.yaml)")
    from urdfcheck.cli.options import choices, for_command

    for o in for_command("pytest"):  # lint's options, prefixed (cli/options.py): --urdfcheck-fail-on, ...
        group.addoption("--urdfcheck-" + o.flags[0][2:], dest="urdfcheck_" + o.dest, default=None,
                        metavar=o.metavar, help=f"lint's {o.flags[0]}: {o.help}",
                        choices=choices("severities") if o.type == "severity" else None)


def pytest_configure(config):
    config.addinivalue_line("markers", "urdfcheck: a urdfcheck lint item (one per robot model and variant)")


def _find_config(rootdir: Path) -> str | None:
    from urdfcheck.request.config import find_config

    return find_config(rootdir)


def _setup(config) -> SimpleNamespace | None:
    """What to lint and how; None when the plugin is not active for this run."""
    if hasattr(config, _STATE):
        return getattr(config, _STATE)
    state = None
    rootdir = Path(str(config.rootpath)).resolve()
    explicit = config.getoption("urdfcheck")
    found = _find_config(rootdir)
    at_root = found is not None and Path(found).resolve().parent == rootdir
    if explicit or at_root:
        state = SimpleNamespace(rootdir=rootdir, config_path=found, error=None, targets=[], result=None,
                                fail_on=None)
        try:
            _prepare(state, config)
        except Exception as e:  # never break the package's own test session: report it as a failing item
            from urdfcheck.request.request import UsageError

            state.error = str(e) if isinstance(e, UsageError) else f"{type(e).__name__}: {e}"
    setattr(config, _STATE, state)
    return state


def _prepare(state, config) -> None:
    """The request `urdfcheck lint` makes when run in the rootdir, planned once; the items lint their targets
    together on first use."""
    from urdfcheck.plan.plan import plan
    from urdfcheck.request.request import make_request

    state.request = make_request([], **request_fields(config), root=str(state.rootdir))
    from urdfcheck.core import door
    from urdfcheck.core.paths import showing

    with showing(state.request.root), door.guarding(_typed(state.request)):
        state.targets = plan(state.request, here=str(state.rootdir))
        state.roots = door.roots()  # the packages the plan resolved: readable when the items run (core.door)
    state.fail_on = state.request.fail_on  # None: each item's config decides


def request_fields(config) -> dict:
    """The request fields of the `--urdfcheck-*` options, as lint's flags fill them (cli/options.py)."""
    from urdfcheck.cli.options import for_command

    out = {}
    for o in for_command("pytest"):
        value = config.getoption("urdfcheck_" + o.dest)
        if value is not None and o.dest == "baseline":
            value = os.path.abspath(value)
        out[o.field] = value
    return out


def _typed(request) -> tuple:
    """What the runner typed, as `run.run` guards it."""
    return (*request.paths, request.config, request.baseline, *request.bags)


def _result(state):
    """The whole run, once, as `urdfcheck lint` runs it (suppression bookkeeping, one X013 per package, the
    baseline); each item shows its target's share (`Result.shares`)."""
    if state.result is None:
        from urdfcheck.core import door
        from urdfcheck.run import run

        with door.guarding(_typed(state.request)):
            for root in getattr(state, "roots", ()):
                door.add_root(root)
            state.result = run(state.request, targets=state.targets)
    return state.result


def pytest_report_header(config):
    state = _setup(config)
    if state is None:
        return None
    where = state.config_path or "no config, discovered below the rootdir"
    return f"urdfcheck: {len(state.targets)} model item(s) ({where})"


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(session, config, items):
    state = _setup(config)
    if state is None:
        return
    parents: dict = {}
    children: dict = {}

    def parent_for(path: Path):
        path = Path(os.path.abspath(path))
        if path not in parents:
            rel = os.path.relpath(path, state.rootdir).replace(os.sep, "/")
            parents[path] = UrdfcheckFile.from_parent(session, path=path, nodeid=rel)
            children[path] = []
        return parents[path], children[path]

    if state.error is not None:
        parent, kids = parent_for(Path(state.config_path or state.rootdir))
        kids.append(UrdfcheckItem.from_parent(parent, name="urdfcheck-config", target=None, state=state))
    else:
        for i, t in enumerate(state.targets):
            parent, kids = parent_for(t.path)
            name = f"urdfcheck[{t.variant}]" if t.variant else "urdfcheck"
            kids.append(UrdfcheckItem.from_parent(parent, name=name, target=t, state=state, index=i))
        if getattr(state.targets, "findings", None):  # about the plan itself (a refused config key, X018; X019)
            parent, kids = parent_for(Path(state.config_path or state.rootdir))
            kids.append(UrdfcheckItem.from_parent(parent, name="urdfcheck-config", target=None, state=state))
    new = []
    for path, parent in parents.items():
        # report the collection like pytest does for files it collects (counts, --co, junitxml)
        config.hook.pytest_collectreport(report=pytest.CollectReport(parent.nodeid, "passed", None, children[path]))
        new.extend(children[path])
    items[:0] = new


class UrdfcheckFile(pytest.File):
    """The model file the items belong to (items are created by the plugin, not by collecting it)."""

    def collect(self):
        return []


class UrdfcheckFailure(Exception):
    def __init__(self, text: str):
        super().__init__(text)
        self.text = text


class UrdfcheckItem(pytest.Item):
    def __init__(self, *, target, state, index=0, **kwargs):
        super().__init__(**kwargs)
        self.target = target
        self.index = index
        self.state = state
        self.add_marker("urdfcheck")

    def runtest(self):
        if self.state.error is not None:
            raise UrdfcheckFailure(f"invalid urdfcheck config: {self.state.error}")
        result = _result(self.state)
        if self.target is None:  # the plan's own findings: what the config asked and was refused (issue 36)
            from urdfcheck.core.findings import Severity

            findings, fail_on = list(self.state.targets.findings), self.state.fail_on or Severity.WARNING
            failing = [f for f in findings if f.severity >= fail_on]
            if failing:
                raise UrdfcheckFailure("\n".join([f"{len(failing)} urdfcheck finding(s) about the plan (config, "
                                                  "file walk)"] + [_line(f) for f in failing]))
            return
        findings = result.shares[self.index]
        fail_on = self.state.fail_on or self.target.settings.fail_on
        failing = [f for f in findings if f.severity >= fail_on]
        below = [f for f in findings if f.severity < fail_on]
        if below:
            self.add_report_section("call", "urdfcheck (below the fail level)", "\n".join(_line(f) for f in below))
        if failing:
            n = len(failing)
            from urdfcheck.core.findings import clean_text
            from urdfcheck.core.paths import shown

            head = (f"{n} urdfcheck finding{'s' if n != 1 else ''} at or above {fail_on} "
                    f"in {clean_text(shown(self.target.path, self.state.rootdir), 4096)}"
                    + (f" [{clean_text(self.target.variant)}]" if self.target.variant else ""))
            raise UrdfcheckFailure("\n".join([head] + [_line(f) for f in failing]))

    def repr_failure(self, excinfo, style=None):
        if isinstance(excinfo.value, UrdfcheckFailure):
            return excinfo.value.text
        return super().repr_failure(excinfo, style=style)

    def reportinfo(self):
        return self.path, None, self.name


def _line(f) -> str:
    from urdfcheck.core.findings import clean_text

    out = f"{clean_text(str(f.location), 4096)}: {f.code} [{f.severity}] {clean_text(f.message)}"
    for v in f.location.via:
        out += f"\n    via macro call at {clean_text(str(v), 4096)}"
    for r in f.related:
        out += f"\n    see also {clean_text(str(r), 4096)}"
    return out
