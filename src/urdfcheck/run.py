"""Running: load -> build -> check -> finish, for the targets `plan.plan` made from a request.

    run(request) -> Result           # `lint`: what every front end calls (CLI, urdfcheck.lint, pytest plugin)
    load(request, path) -> Loaded    # one model with the settings lint gives it (expand, tree, tf, publish,
                                     # verify, urdfcheck.load / urdfcheck.expand)

What happens after the checks is the finish stage (`finish/`): suppressions, one finding per problem, the
baseline, one X013 per package, and the `Result` every front end renders.
"""
from __future__ import annotations

import contextlib
import os
from pathlib import Path

from urdfcheck.core import progress
from urdfcheck.core.findings import Finding, Location, Severity
from urdfcheck.core.paths import shown
from urdfcheck.core.records import TYPE_CHECKING, Record
from urdfcheck.finish.result import Result, dedupe, fragment  # noqa: F401  (Result: imported from here too)
from urdfcheck.finish.stage import finish_run, not_understood
from urdfcheck.finish.suppressions import YamlUse, finish_target
from urdfcheck.load import loader
from urdfcheck.plan.plan import Later, Target, plan  # noqa: F401  (Later, Target: imported from here too)
from urdfcheck.request.request import LintRequest, UsageError

if TYPE_CHECKING:  # the rules are imported after the first expansions are sent (`_lint_targets`), not with this module
    from urdfcheck.rules import engine


def run(request: LintRequest, *, retain: list | None = None, targets: list[Target] | None = None) -> Result:
    """Plan (unless given the plan of this request: the pytest plugin makes its items from it), lint, finish.
    Paths are shown relative to the request's root from the start (`core.paths.showing`): nothing is
    rewritten afterwards. The run's budget (load.budget) covers the planning too: launch files are read there.
    Raises UsageError when there is nothing to lint or an input is unusable."""
    from urdfcheck.core import door
    from urdfcheck.core.findings import reset_hints
    from urdfcheck.core.paths import showing
    from urdfcheck.load.budget import run_budget
    from urdfcheck.load.discover import remembering

    reset_hints()
    typed = (*request.paths, request.config, request.baseline, *request.bags)
    # the runner lowered the guard (`--trusted`, or `--config FILE --trust-config`: its paths are the runner's)
    trusted = bool(request.trusted) or bool(request.config and request.trust_config)
    with door.guarding(typed), (door.unconfined() if trusted else contextlib.nullcontext()), \
            showing(request.root), run_budget(request.budget), remembering():
        try:
            return _run(request, retain, targets)
        except MemoryError:
            raise UsageError("the run's memory budget was used up while planning (a launch or config file "
                             "that grows without bound?); nothing was checked") from None


def _run(request: LintRequest, retain, targets) -> Result:
    targets = plan(request) if targets is None else targets
    infos = list(getattr(targets, "infos", ()))
    noted = [f._replace(location=f.location.shown())
             for f in getattr(targets, "findings", ())]  # about the plan: a config's ignored keys, a walk cut short
    if not targets:
        # xacro libraries only, or deployments whose model is no URDF (an SDFormat model): nothing to lint
        # alone, not an unusable invocation; a deployment not understood is still said (C021)
        unread = list(getattr(targets, "not_understood", ()))
        if infos or noted or unread:
            result = Result(noted, [], fail_on=request.fail_on or Severity.WARNING, root=request.root)
            result.infos, result.libraries = infos, getattr(targets, "libraries", 0)
            not_understood(result, unread, request)
            return result
        raise UsageError(f"no URDF or xacro model found in {', '.join(request.paths or ['.'])}")
    if request.bags:
        _attach_bags(targets, request.bags, request.joint_states)
    result = lint_targets(targets, retain=retain, budget=request.budget, **request.settings(None).load_options())
    result = _unread_libraries(result, getattr(targets, "included", ()), retain, request,
                               getattr(targets, "library_files", ()))
    _drop_libraries(result)
    result.infos, result.libraries = infos, getattr(targets, "libraries", 0)
    result.root = request.root
    return finish_run(result, request, targets, noted)


def _attach_bags(targets: list[Target], bags: tuple, topic: str | None) -> None:
    """A recording shows one configuration of the robot: it is checked against one target per entry model,
    the defaults (or the deployment, or the first variant), not against every variant."""
    chosen: dict[str, Target] = {}
    for t in targets:
        best = chosen.get(str(t.path))
        if best is None or (best.variant not in ("", "defaults") and t.variant in ("", "defaults")):
            chosen[str(t.path)] = t
    for t in chosen.values():
        t.bags = tuple(t.bags) + tuple(b for b in bags if b not in t.bags)
        t.runner_bags = tuple(bags)  # typed on the command line (core.door: runner=True)
        t.joint_states = topic


def _attachable(t: Target, model) -> tuple:
    """A discovered model with no root link of its own, every link a child of a joint and some parent link
    defined nowhere in it (intera's controller_box.urdf: parts attached to Sawyer's `base` at run time), is a
    fragment for another robot, not a robot: what it says rests on that guess (issue 37). A robot with a
    misspelt parent still has its root link, and one named or launched is a robot by evidence."""
    if any(s.how in ("named", "config", "launched") for s in t.evidence) or getattr(t, "deployment", None):
        return ()
    if not model.links or model.roots:
        return ()
    if not any(j.parent is not None and j.parent not in model.links for j in model.joint_list):
        return ()
    from urdfcheck.core.evidence import Step

    return (Step("model", shown(str(t.path)), "probe", "name it under models: in urdfcheck.yaml if it is a whole "
                 "robot"),)


def _combinations(targets: list[Target], by_target: list[list[Finding]]) -> None:
    """The evidence rule for automatic variants (issue 37): a problem that only a combination of several options
    shows (a variant of a discovered model that no launch file or config was seen to use) is an info saying how
    to confirm it; one that the defaults or an option alone show too keeps its severity in every variant."""
    if not any(getattr(t, "combination", False) for t in targets):
        return
    from urdfcheck.core.evidence import Step
    from urdfcheck.finish.collapse import _shape
    from urdfcheck.rules import engine

    def key(t, f):
        loc = f.location
        return (os.path.realpath(str(t.path)), f.code, loc.file, loc.line, loc.column, _shape(f.message))

    plain = {key(t, f) for t, found in zip(targets, by_target) if not getattr(t, "combination", False)
             for f in found}
    step = Step("variant", "with several options", "combination", "name the combination under the model's "
                "variants: in urdfcheck.yaml, or pass it with --arg, if a deployment uses it")
    for i, t in enumerate(targets):
        if getattr(t, "combination", False):
            by_target[i] = [f if f.severity <= Severity.INFO or key(t, f) in plain
                            else engine.on_evidence([f], (step,))[0] for f in by_target[i]]


_NO_DEFAULT = None


def _required_args(t: Target, found: list[Finding]) -> list[Finding]:
    """The evidence rule for a required xacro argument (no default) that nothing sets, on a model found by
    discovery (no launch file runs it, no one named it): the argument is an input of the model (UR's `name`), the
    deployment that gives it is what is missing, so an info naming it. A launch file that runs the model without
    it, or a model the runner named, keeps the error."""
    global _NO_DEFAULT
    d = getattr(t, "deployment", None)
    if d is not None:
        if getattr(d, "dropped_args", None):
            found = _given_at_launch(t, found)
        if getattr(d, "variant", "") and not d.variant.startswith("model="):
            found = _choice(t, found)
        return found
    if any(s.how in ("named", "config", "launched") for s in t.evidence) or d is not None:
        return found
    import re

    from urdfcheck.core.evidence import Step
    from urdfcheck.rules import engine

    _NO_DEFAULT = _NO_DEFAULT or re.compile(r"^xacro argument '([^']+)' has no default and nothing sets it")
    out = []
    flipped = t.variant not in ("", "defaults")
    for f in found:
        m = _NO_DEFAULT.match(f.message) if f.code == "X010" else None
        # an option flipped on its own whose branch includes a file named by another argument left empty
        # (vrx's yaml_component_generation and component_xacro_file): that argument is the deployment's too
        empty = f.code == "X010" and flipped and f.message.startswith("not a regular file (a folder)")
        if m is not None or empty:
            step = Step("deployment", f"a launch file running {shown(str(t.path))}", "undeployed",
                        "lint the launch file that runs it")
            f = engine.on_evidence([f], (step,))[0]
        out.append(f)
    return out


def _given_at_launch(t: Target, found: list[Finding]) -> list[Finding]:
    """A launch file that passes a xacro argument from a launch argument decided at launch time (denso's
    `model:=<model>`, a launch argument without default): that the model then lacks it is no defect of the
    launch file, whose users give it; an info (issue 37). An argument the launch file does not pass at all keeps
    the error."""
    import re

    from urdfcheck.core.evidence import Step
    from urdfcheck.rules import engine

    given = set(t.deployment.dropped_args or ())
    out = []
    for f in found:
        m = re.match(r"^xacro argument '([^']+)' has no default", f.message) if f.code == "X010" else None
        if m is not None and m.group(1) in given:
            step = Step("deployment", shown(t.deployment.launch.file), "required",
                        f"lint with --arg {m.group(1)}:=... or name the deployment's arguments in urdfcheck.yaml")
            f = engine.on_evidence([f], (step,))[0]
        out.append(f)
    return out


def _choice(t: Target, found: list[Finding]) -> list[Finding]:
    """A deployment of a launch-argument value other than the default (panther's wheel_type:=custom, which its
    description says needs the user's own wheel_config_path) whose model reads a file that does not exist: the
    value needs arguments the launch file's users give, so an info (issue 37). The defaults keep the error."""
    from urdfcheck.core.evidence import Step
    from urdfcheck.rules import engine

    out = []
    for f in found:
        if f.code == "X010" and f.severity > Severity.INFO and (
                "No such file or directory" in f.message or f.message.startswith("not a regular file")):
            step = Step("deployment", f"{shown(t.deployment.launch.file)} [{t.deployment.variant}]", "choice",
                        "name the arguments that value needs under models: in urdfcheck.yaml")
            f = engine.on_evidence([f], (step,))[0]
        out.append(f)
    return out


def _load_findings(t: Target, exp) -> list[Finding]:
    """The loader's findings of `t`, through the evidence rule (rules.engine.on_evidence): a probe that another
    file may include and that fails only on a symbol (macro, property, argument) that file provides is a
    fragment of it: those findings are infos, and the probe is no model left unchecked. Any other finding of it
    keeps its severity (a decoy include never hides a broken robot)."""
    from urdfcheck.rules import engine

    found = _required_args(t, engine.on_evidence(exp.findings, t.evidence))
    if not (t.probe and t.includers and exp.findings):
        return found
    from urdfcheck.core.evidence import Step
    from urdfcheck.plan.robots import includer_texts, includers_of, provided

    failing = [f for f in exp.findings if f.code == "X010"]
    if not failing:
        return found
    includers = [i for i in t.includers if i != "?"] or includers_of(str(t.path))
    texts = includer_texts(includers, lambda n: t.packages.get(n))
    if not texts or not all(provided(f.message, texts) for f in failing):
        return found
    t.fragment = True
    step = Step("model", shown(str(t.path)), "probe", f"lint {shown(includers[0])}, which includes it, or name this "
                "file under models: in urdfcheck.yaml if it is a whole robot")
    return [engine.on_evidence([f], (step,) if f.code == "X010" else t.evidence)[0] for f in exp.findings]


def _unread_libraries(result: Result, included, retain, request: LintRequest, libraries=()) -> Result:
    """Files taken for included libraries that no model of the run read (the include was commented out,
    conditional, or in a file that is no robot): expanded now as probes, so that a robot is never hidden by
    another file claiming to include it."""
    from urdfcheck.plan.robots import missed

    # macro libraries no model read too: a robot may include them only under a non-default argument
    result = _reaching(result, missed([*included, *libraries], result.read), retain, request)
    unread = missed(included, result.read)
    if not unread:
        return result
    by_path = {os.path.realpath(t.path): t for t in result.targets}
    extra = []
    for path in unread:
        like = next(iter(by_path.values()), None)
        t = Target(Path(path), {}, "", None, dict(like.packages) if like is not None else {},
                   like.settings if like is not None else None)
        t.probe = True
        t.includers = ("?",)  # found when it fails (plan.robots.includers_of)
        extra.append(t)
    with progress.after(len(result.targets)):
        more = lint_targets(extra, retain=retain, budget=request.budget, **request.settings(None).load_options())
    merged = Result(dedupe(result.raw() + more.raw()), result.targets + more.targets,
                    {**result.models, **more.models}, result.by_target + more.by_target)
    merged.read = set(result.read) | set(more.read)
    return merged


def _reaching(result: Result, unread: list[str], retain, request: LintRequest) -> Result:
    """Included files that no model read because their robot includes them only under a non-default xacro argument
    (a boolean, or a literal comparison: plan.plan.reaching_targets): each linted through the variant of the robots
    of its package that includes it, before any is probed alone (a probe of a macro file is no check of it)."""
    from urdfcheck.load.packages import enclosing_package
    from urdfcheck.plan.plan import reaching_targets

    if not unread:
        return result
    robots = [t for t in result.targets if not t.probe and not t.library]
    extra: list[Target] = []
    infos: list[str] = []
    for path in unread:
        pkg = enclosing_package(Path(os.path.abspath(path)).parent)
        if pkg is None:
            continue
        near = [t for t in robots if enclosing_package(Path(os.path.abspath(t.path)).parent) == pkg]
        extra.extend(v for v in reaching_targets(path, near, infos) if not any(
            os.path.realpath(v.path) == os.path.realpath(x.path) and v.args == x.args for x in extra))
    if not extra:
        return result
    with progress.after(len(result.targets)):
        more = lint_targets(extra, retain=retain, budget=request.budget, **request.settings(None).load_options())
    merged = Result(dedupe(result.raw() + more.raw()), result.targets + more.targets,
                    {**result.models, **more.models}, result.by_target + more.by_target)
    merged.read = set(result.read) | set(more.read)
    return merged


def _drop_libraries(result: Result) -> None:
    """Probes whose expansion had no link and said nothing are libraries: not models of the report."""
    keep = [i for i, t in enumerate(result.targets) if not (t.library and not result.by_target[i])]
    if len(keep) == len(result.targets):
        return
    gone = [t for t in result.targets if t.library]
    result.targets = [result.targets[i] for i in keep]
    result.by_target = [result.by_target[i] for i in keep]
    for t in gone:
        if t not in result.targets:
            result.models.pop((str(t.path), t.variant), None)


def lint_target(t: Target, selection: engine.Selection, *, trusted=False, allow_env=(), timeout=loader.XACRO_TIMEOUT,
                config=None, max_elements=None) -> tuple[list[Finding], object]:
    """One target on its own (tests). A run lints all its targets with `lint_targets`."""
    pending = _begin(t, dict(trusted=trusted, allow_env=allow_env, timeout=timeout, max_elements=max_elements))
    return _check(t, pending.result(), selection, config)


def _bag_findings(model, t: Target, selection: engine.Selection, contracts=None) -> list[Finding]:
    """The recordings of this target against its model (urdfcheck.bag), with the B rules' options."""
    from urdfcheck.bag import CODES, BagOptions, check_recording

    if not any(selection.enabled(c) for c in CODES):
        return []

    from urdfcheck.rules.catalogue import options_for

    def tolerance(code: str) -> float:  # declared once, in rules/CODE.yaml; the config may set it
        return options_for((code,), selection.options)["tolerance"]

    options = BagOptions(joint_topic=t.joint_states, tolerance=tolerance("B005"),
                         replay_tolerance=tolerance("B013"), static_tolerance=tolerance("B011"),
                         frame_prefix=getattr(contracts, "rsp_prefix", "") or "")  # the config's or deployment's
    out = []
    runner = getattr(t, "runner_bags", ())
    for bag in t.bags:
        out.extend(check_recording(model, bag, options, progress=_bag_progress(bag), runner=bag in runner))
    return out


def _bag_progress(bag: str):
    """Messages read so far, on a terminal's stderr (a long recording takes minutes); None elsewhere."""
    import sys

    if not sys.stderr.isatty():
        return None
    name = os.path.basename(bag.rstrip(os.sep))

    def show(n: int) -> None:
        sys.stderr.write(f"\rurdfcheck: {name}: {n:,} messages read\x1b[K")
        sys.stderr.flush()

    return show


def _begin(t: Target, kw: dict, batch: loader.Batch | None = None) -> loader.Pending:
    opts = t.settings.load_options() if t.settings is not None else kw
    # a probe's tree is looked at before any model is built (plan.robots: a library or a robot?)
    return loader.begin(t.path, t.args, packages=t.packages, batch=batch, stream=not t.probe, **opts)


def _check(t: Target, exp, selection: engine.Selection, config, yaml: YamlUse | None = None
           ) -> tuple[list[Finding], object]:
    from urdfcheck.rules import engine

    model = loader.build_model(exp)  # first: a document read as it is built may add its load findings
    findings = _load_findings(t, exp)
    if model is not None:
        contracts = t.consumers(model, exp, config)  # planned, or found beside the model: once per target
        ctx = engine.Context(selection=selection, expanded=exp, config=config, contracts=contracts,
                             variant=t.variant, target=t.settings.target if t.settings is not None else None,
                             profiles=t.settings.profiles if t.settings is not None else (),
                             evidence=t.evidence + _attachable(t, model))
        findings.extend(engine.run_checks(model, ctx))
        if t.bags:
            findings.extend(_bag_findings(model, t, selection, contracts))
        if yaml is not None:
            yaml.read(contracts, selection)
    return finish_target(findings, selection, exp.suppressions, model=exp.entry, variant=t.variant,
                         yaml_used=yaml.used if yaml is not None else None), model


def lint_targets(targets: list[Target], selection: engine.Selection | None = None, *, config=None,
                 retain: list | None = None, budget: float | None = None, **kw) -> Result:
    """`_lint_targets` within one time and memory budget for all models and variants (load.budget; `budget`
    seconds, default 300): what the budget leaves unlinted is an X017 finding at its model."""
    from urdfcheck.load.budget import run_budget

    with run_budget(budget):
        return _lint_targets(targets, selection, config=config, retain=retain, **kw)


def _lint_targets(targets: list[Target], selection: engine.Selection | None = None, *, config=None,
                  retain: list | None = None, **kw) -> Result:
    """Lint every target. Xacro expansions run ahead in their workers (a few at a time), so this process
    imports the rules and builds the previous model while the next ones expand.

    Each target is linted under its own settings (its config file); targets without settings (made by
    hand) under `selection`, `config` and the load options `kw`.

    `retain`: a list that keeps each parsed document alive. A process that exits right after (the console
    command) passes one: freeing a large libxml2 tree costs time, and the allocator's clean-up of its
    million small blocks on the next large request costs more (~0.1 s for 10,000 links)."""
    by_target: list[list[Finding]] = [[] for _ in targets]
    models = {}
    ahead = max(1, min(4, os.cpu_count() or 1))
    pending: dict[int, loader.Pending] = {}
    yaml = YamlUse()
    read: set = set()  # every file an expansion read (display paths): plan.robots.missed
    from urdfcheck.consumers.params import parsed_ahead
    from urdfcheck.plan.robots import has_links

    with parsed_ahead() as parsed:
        try:
            first = loader.Batch()  # the first xacro models go to the console's spare together
            for i in range(min(ahead, len(targets))):
                pending[i] = _begin(targets[i], kw, first)
            if first.items:
                first.also = _params_ahead(targets[:len(first.items)])
            first.send()
            from urdfcheck.rules import engine

            selection = selection or engine.Selection()
            _warm_up(targets, config)
            for i, t in enumerate(targets):
                if i + ahead < len(targets):
                    pending[i + ahead] = _begin(targets[i + ahead], kw)
                where = shown(str(t.path))  # as the report will name it
                progress.step(i, len(targets), where if not t.variant else f"{where} [{t.variant}]")
                exp = pending.pop(i).result()
                if i == 0:
                    _take_params(first, parsed)
                yaml.index = i
                if exp.readable:  # read *and* expanded: an includer that failed checked nothing it read
                    read.update(exp.files or ())
                if t.probe and exp.root is not None and not has_links(exp.root):  # a library (plan.robots)
                    t.library = True
                    sel = t.settings.selection if t.settings is not None else selection
                    models[(str(t.path), t.variant)] = None
                    by_target[i].extend(finish_target(_load_findings(t, exp), sel, exp.suppressions,
                                                      model=exp.entry))
                    continue
                try:
                    if t.settings is not None:
                        found, model = _check(t, exp, t.settings.selection, t.settings.config, yaml)
                    else:
                        found, model = _check(t, exp, selection, config, yaml)
                except MemoryError:  # the run's memory limit (load.budget): this model is not checked
                    found, model = [_over_memory(exp)], None
                if retain is not None:
                    retain.append(exp)
                models[(str(t.path), t.variant)] = model
                by_target[i].extend(found)
        finally:
            for p in pending.values():
                p.cancel()
    for i, f in yaml.unused():
        by_target[i].append(f)
    _combinations(targets, by_target)
    result = Result(dedupe([f for fs in by_target for f in fs]), targets, models, by_target)
    result.read = read
    return result


def _params_ahead(targets: list[Target]) -> tuple[str, tuple] | None:
    """The parameter files of the packages around the run's first models (what zero-config consumer discovery
    reads), for the xacro worker to parse while it expands (`consumers.params.parse_ahead`): PyYAML is imported
    there already. Only a few small files: the first results wait for the parse, and in a package of several
    models discovery parses only the files that name one of the model's joints (consumers.prefilter), which
    the worker cannot tell before the model exists. None when there is nothing to send."""
    from urdfcheck.load.discover import discover
    from urdfcheck.load.packages import enclosing_package

    paths: list[str] = []
    for t in targets:
        if t._contracts is not None:  # planned consumers (a config, a deployment): read from their own files
            continue
        pkg = enclosing_package(Path(os.path.abspath(t.path)).parent)
        if pkg is not None:
            paths.extend(p for p in discover(pkg).params if p not in paths)
    if not paths or len(paths) > PARAMS_AHEAD_FILES:
        return None
    try:
        # lstat: a link is not followed here (the worker's reader refuses one that leads out of the checkout)
        if sum(os.lstat(p).st_size for p in paths) > PARAMS_AHEAD_BYTES:
            return None
    except OSError:
        return None
    return ("urdfcheck.consumers.params:parse_ahead", (paths,))


PARAMS_AHEAD_FILES = 16
PARAMS_AHEAD_BYTES = 128 * 1024


def _take_params(batch: loader.Batch, store: dict) -> None:
    """The worker's parse of the parameter files, for `read_params` to answer from; with the lint cache on, only
    together with what the worker read (core.observe), so that an edited parameter file is a cache miss."""
    got = batch.also_result() if batch.also is not None else None
    if not isinstance(got, dict) or not isinstance(got.get("parsed"), dict):
        return
    from urdfcheck.core import observe

    if observe.active():
        if got.get("observed") is None:
            return  # the console reads them itself, and sees what it reads
        observe.add(got["observed"])
    store.update(got["parsed"])


def _over_memory(exp) -> Finding:
    return Finding("X017", Severity.ERROR, "not checked: the run's memory budget was used up while checking this "
                   "model", Location(exp.entry), name="lint-budget")


def _warm_up(targets: list[Target], config) -> None:
    """What the run needs after loading (model builders, rule modules, the catalogue, the contract readers
    when there can be consumers), done while the first expansions run in their workers, not after them."""
    from urdfcheck.consumers.reach import in_package
    from urdfcheck.model import build  # noqa: F401
    from urdfcheck.rules import catalogue as rulebook

    if not targets:
        return
    consumers = config is not None or any(t.settings is not None and t.settings.config is not None for t in targets) \
        or any(t._contracts is not None for t in targets) or in_package(targets[0].path)
    rulebook.load_checks(consumers=consumers)  # the consumer rules' modules import their readers
    rulebook.catalogue()


# --- for tests and scripts ---------------------------------------------------------------------------------
class Loaded(Record):
    """One model as `lint` loads it: the expansion (findings, source map), the model (None when it failed to
    load, or was not asked for) and the settings it was loaded under."""

    _fields = ('expanded', 'model', 'settings')

    def __init__(self, expanded, model, settings):
        self.expanded, self.model, self.settings = expanded, model, settings


def load(request: LintRequest, path, *, build: bool = True) -> Loaded:
    """The model at `path` with the settings `lint` gives it: the nearest config file (its `packages:`,
    limits, target; a declared model's xacro arguments), the request's flags over it."""
    from urdfcheck.core.paths import showing
    from urdfcheck.plan.plan import Planner

    path = os.fsdecode(path)
    if not os.path.isfile(path):
        raise UsageError(f"no such file: {path}")
    with showing(request.root):
        planner = Planner(request)
        cfg = planner.nearest(path)
        settings = planner.settings(cfg)
        declared = planner.declared(cfg, [path]) if cfg is not None and cfg.model_for(path) is not None else []
        t = declared[0] if declared else planner.target(Path(path), {}, "", None, settings)
        exp = loader.begin(t.path, t.args, packages=t.packages, **settings.load_options()).result()
        model = loader.build_model(exp) if build and exp.root is not None else None
        return Loaded(exp, model, settings)
