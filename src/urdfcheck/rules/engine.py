"""Run the checks over a model: selection, severities, locations, the evidence rule.

A check only yields Problems pointing at model parts; this module turns them into Findings. A check
that raises becomes an R001 finding, never a traceback. Suppressions come after, in the finish stage
(`finish.suppressions`).
"""
from __future__ import annotations

import os

from urdfcheck.core import nogc
from urdfcheck.core.findings import Finding, Location, Problem, Severity, clean_text
from urdfcheck.core.records import Record
from urdfcheck.rules import catalogue as rulebook


class Selection(Record):
    # severity: code or prefix -> Severity
    # options: code -> {option: value}
    _fields = ('select', 'ignore', 'severity', 'options')

    def __init__(self, select: tuple[str, ...] = ("ALL",),
                 ignore: tuple[str, ...] = (),
                 severity: dict | None = None,
                 options: dict | None = None):
        self.select = select
        self.ignore = ignore
        self.severity = {} if severity is None else severity
        self.options = {} if options is None else options

    def enabled(self, code: str) -> bool:
        return rulebook.matches(code, self.select) and not rulebook.matches(code, self.ignore)

    def severity_of(self, code: str, default: Severity) -> Severity:
        best = None
        for key, sev in self.severity.items():
            if code.startswith(key) and (best is None or len(key) > len(best[0])):
                best = (key, sev)
        return best[1] if best else default


class Context(Record):
    """What a check may look at besides the model."""

    # expanded: load.Expanded (entry, files, resolver)
    # config: config.Config or None
    # contracts: the consumers read for this model (controllers, launch files...)
    # options: the running rule's options (catalogue defaults + config)
    # target: the ROS distribution the model is checked for (flag over config; None: the checks decide, U007)
    # profiles: the consumer profiles asked for (--profile / `profiles:`), e.g. ("mujoco", "gazebo")
    # evidence: the planning steps (core.evidence.Step) of the target: how the model and deployment were chosen
    _fields = ('selection', 'expanded', 'config', 'contracts', 'variant', 'options', 'target', 'profiles',
               'evidence')

    def __init__(self, selection: Selection | None = None,
                 expanded: object = None,
                 config: object = None,
                 contracts: object = None,
                 variant: str = "",
                 options: dict | None = None,
                 target: str | None = None,
                 profiles: tuple = (),
                 evidence: tuple = ()):
        self.profiles = tuple(profiles or ())
        self.evidence = tuple(evidence or ())
        self.selection = Selection() if selection is None else selection
        self.expanded = expanded
        self.config = config
        self.contracts = contracts
        self.variant = variant
        self.options = {} if options is None else options
        self.target = target

    @property
    def resolver(self):
        return getattr(self.expanded, "resolver", None)


def _loc(at, default: Location) -> Location:
    if at is None:
        return default
    if isinstance(at, Location):
        return at
    loc = getattr(at, "loc", None)
    return loc if isinstance(loc, Location) else default


def run_checks(model, ctx: Context) -> list[Finding]:
    # on a large model the rules build large indexes in turn (link graph, name maps, tensors)
    return nogc.call(_run_checks, model, ctx)


def _run_checks(model, ctx: Context) -> list[Finding]:
    from urdfcheck.consumers.reach import may_have_consumers

    cat = rulebook.catalogue()
    consumers = may_have_consumers(model, ctx)
    checks = rulebook.load_checks(consumers=consumers or bool(model.ros2_control))
    out: list[Finding] = []
    done = set()
    for code in sorted(checks):
        fn = checks[code]
        if fn in done:
            continue
        done.add(fn)
        codes = [c for c in fn.codes if ctx.selection.enabled(c)]
        if not codes:
            continue
        try:
            ctx.options = rulebook.options_for(fn.codes, ctx.selection.options, cat)
            if not _can_run(fn, model, consumers):
                continue
            for p in fn(model, ctx) or ():
                f = _finding(p, fn, model, ctx, cat)
                if f is not None:
                    out.append(f)
        except Exception as e:  # a broken rule must not hide the others
            if ctx.selection.enabled("R001"):
                out.append(Finding("R001", Severity.ERROR,
                                   clean_text(f"rule {'/'.join(fn.codes)} crashed: {type(e).__name__}: {e}"),
                                   model.loc, name="rule-crashed"))
    return out


def _can_run(fn, model, consumers: bool) -> bool:
    """What the check `needs` (`rules.catalogue.check`) is there: the model's consumers, or its <ros2_control>."""
    needs = getattr(fn, "needs", "model")
    if needs == "consumers":
        return consumers
    return needs != "ros2_control" or bool(model.ros2_control)


def _finding(p: Problem, fn, model, ctx: Context, cat) -> Finding | None:
    code = p.code or fn.codes[0]
    if not ctx.selection.enabled(code):
        return None
    info = cat.get(code)
    default = p.severity or (info.severity if info else Severity.ERROR)
    message, related = p.message, tuple(_loc(r, model.loc) for r in p.related)
    unknown = getattr(ctx.contracts, "unknown", None) if p.absent else None
    if unknown:  # an absence claimed about a world not wholly understood (issue 20): said, not failed
        default = Severity.INFO
        message += f"; not failed, since {_listing([w for w, _ in unknown])} may {p.absent}"
        related += tuple(loc for _, loc in unknown[:3] if loc is not None)
    at = _loc(p.at, model.loc)
    steps = ctx.evidence + p.rests_on + _paired(ctx.contracts, (at, *related), p.rests_on)
    if steps and default > Severity.INFO:  # the evidence rule (issue 37): a guess under it makes it an info
        from urdfcheck.core.evidence import demotion

        why = demotion(steps)
        if why is not None:
            default = Severity.INFO
            message += why
    return Finding(
        code=code,
        severity=ctx.selection.severity_of(code, default),
        message=clean_text(message),
        location=at,
        name=info.name if info else "",
        related=related,
        profile=p.data.get("profile") or _annotated(code, ctx),
        evidence=steps,
        profiles=tuple(p.data.get("profiles", ())) or _annotating(code, ctx),
    )


def _paired(contracts, locs, have) -> tuple:
    """How the consumer files a finding points at were paired with the model (`Consumers.pairing`, issue 37):
    a finding about a parameter file rests on that pairing."""
    pairing = getattr(contracts, "pairing", None)
    if not pairing:
        return ()
    out = []
    for loc in locs:
        f = getattr(loc, "file", None)
        s = pairing.get(os.path.realpath(f)) if f and not str(f).startswith("<") else None
        if s is not None and s not in out and s not in have:
            out.append(s)
    return tuple(out)


def _annotating(code: str, ctx: Context) -> tuple:
    if not ctx.profiles:
        return ()
    from urdfcheck.rules.checks.profiles.common import annotating

    return annotating(code, ctx.profiles)


def _annotated(code: str, ctx: Context) -> str:
    """The active profile that reads a general rule's finding as its own rejection (rules/checks/profiles)."""
    if not ctx.profiles:
        return ""
    from urdfcheck.rules.checks.profiles.common import annotates

    return annotates(code, ctx.profiles)


def _listing(items, shown: int = 3) -> str:
    """`a`, `a and b`, `a, b, c and 2 more`."""
    items = list(dict.fromkeys(items))
    head, more = items[:shown], len(items) - shown
    if more > 0:
        return ", ".join(head) + f" and {more} more"
    return head[0] if len(head) == 1 else ", ".join(head[:-1]) + " and " + head[-1]


def on_evidence(findings: list[Finding], steps: tuple) -> list[Finding]:
    """The evidence rule for the loader's findings (X0xx, said before any check runs): those of a target chosen
    by a guess (a probe that may be a fragment of another file) are said at info, as `_finding` does."""
    if not steps:
        return list(findings)
    from urdfcheck.core.evidence import demotion

    why = demotion(steps)
    cat = rulebook.catalogue()
    out = []
    for f in findings:
        info = cat.get(f.code)
        sev = f.severity if f.name or not info else info.severity
        if why is not None and sev > Severity.INFO:
            f = f._replace(severity=Severity.INFO, message=clean_text(f.message + why),
                           name=f.name or (info.name if info else ""))
        out.append(f._replace(evidence=tuple(steps) + tuple(f.evidence)))
    return out
