"""The run's result: every finding, by target, with the finish applied (one finding per problem, the baseline,
one X013 per package): what every front end renders."""
from __future__ import annotations

from urdfcheck.core.findings import Finding, Severity
from urdfcheck.core.paths import shown
from urdfcheck.core.records import TYPE_CHECKING, Record
from urdfcheck.finish.packages import merge_x013

if TYPE_CHECKING:
    from urdfcheck.plan.plan import Target


class Result(Record):
    # models: (entry, variant) -> Model (None when it failed to load)
    # by_target: the findings of each target (index as in `targets`), before merging across targets; an
    #   unused suppression in a YAML file belongs to the first target that read the file
    # fail_on: the level at which the run fails (flags, else the config, else warning)
    # root: reports show paths relative to this folder ("" = the working directory)
    _fields = ('findings', 'targets', 'models', 'by_target', 'fail_on', 'root')
    infos: tuple = ()  # the planner's info lines (a package of xacro libraries only): not findings
    _finished: tuple = ((), {})  # (each target's findings the baseline kept, the run's X013 per package)
    libraries: int = 0  # xacro libraries the plan saw (not linted alone)
    read: set = frozenset()  # the files the expansions read
    baselined: int = 0  # findings the baseline file hid (said in the text report)
    changes = None  # `lint --diff-base REV`: what the change does to the findings (diff.findings.FindingsDiff)

    def __init__(self, findings: list[Finding], targets: list[Target], models: dict | None = None,
                 by_target: list | None = None, fail_on: Severity = Severity.WARNING, root: str = ""):
        self.findings = findings
        self.targets = targets
        self.models = {} if models is None else models
        self.by_target = [[] for _ in targets] if by_target is None else by_target
        self.fail_on = fail_on
        self.root = root

    @property
    def shares(self) -> list[list[Finding]]:
        """Each target's findings after the finish (baseline, one X013 per package, one finding per problem):
        what the pytest plugin's item of that target shows. Computed on first use, once."""
        if "_shares" not in self.__dict__:
            kept, merged = self._finished
            self._shares = [dedupe(merge_x013(fs, merged)) for fs in kept]
        return self._shares

    def raw(self) -> list[Finding]:
        """Every finding before duplicates were collapsed: what a baseline counts, so that a new call of a
        macro with a known problem is new."""
        return [f for fs in self.by_target for f in fs]

    def unchecked(self) -> list[Target]:
        """The targets whose model did not load: not checked, whatever the selection hid (issue 19). A probe
        that may be a fragment of another file (its evidence is a guess, core.evidence) is no robot left
        unchecked: its load findings say why at info, and a package lint never fails on a fragment alone."""
        return [t for t in self.targets if (str(t.path), t.variant) in self.models
                and self.models[(str(t.path), t.variant)] is None and not t.library and not fragment(t)]

    def not_passed(self) -> str | None:
        """Why a run without findings still is no pass (a report says it instead of "All checks passed"):
        models that did not load, or no robot at all."""
        bad = self.unchecked()
        if bad:
            n = len({str(t.path) for t in bad})
            return f"{n} model{'s' if n != 1 else ''} not checked (did not load): {self._why_unchecked(bad)}"
        if not [t for t in self.targets if not t.library]:
            n = self.libraries
            return "no robot found" + (f": {n} xacro librar{'y' if n == 1 else 'ies'}" if n else "")
        return None

    def _why_unchecked(self, bad: list[Target], most: int = 3) -> str:
        """Why the models did not load and how to make them checkable (from the first load finding of each),
        grouped by reason: an unchecked robot never passes, so the line says what to do about it."""
        index = {id(t): i for i, t in enumerate(self.targets)}
        groups: dict[str, list[str]] = {}
        named: set[str] = set()
        for t in bad:
            if str(t.path) in named:  # another variant of a model already named: its first reason is enough
                continue
            named.add(str(t.path))
            i = index.get(id(t))
            found = self.by_target[i] if i is not None and i < len(self.by_target) else []
            why = next((_how_to_load(f) for f in found if f.code.startswith("X")), "see its findings")
            groups.setdefault(why, []).append(shown(str(t.path)))
        parts = []
        for why, names in groups.items():
            more = f", {len(names) - most} more" if len(names) > most else ""
            parts.append(f"{', '.join(names[:most])}{more} ({why})")
        return "; ".join(parts)

    def worst(self) -> Severity | None:
        return max((f.severity for f in self.findings), default=None)

    def failed(self, fail_on: Severity | None = None) -> bool:
        """Any finding the gate judges (`gate`); a model that did not load was not checked: never a pass."""
        if self.unchecked():
            return True
        return bool(self.gate(fail_on)[0])

    def gate(self, fail_on: Severity | None = None) -> tuple[list[Finding], list[Finding]]:
        """(the findings that fail the run, those at or above their level that do not gate). A finding fails at or
        above `fail_on`; by default the level of the config its model was planned under (a workspace run: each
        package's own `fail_on`; a flag sets them all). With `changes` (`lint --diff-base`) only the new findings
        gate: the unchanged ones at or above the level are the second list. Every report's headline says this."""
        if fail_on is not None:
            above = [f for f in self.findings if f.severity >= fail_on]
        else:
            levels: dict[tuple, Severity] = {}
            for t, found in zip(self.targets, self.by_target):
                level = t.settings.fail_on if t.settings is not None else self.fail_on
                for f in found:
                    key = (f.code, f.location)
                    levels[key] = min(levels.get(key, level), level)
            above = [f for f in self.findings if f.severity >= levels.get((f.code, f.location), self.fail_on)]
        if self.changes is None:
            return above, []
        new = {id(f) for f in self.changes.new}
        return [f for f in above if id(f) in new], [f for f in above if id(f) not in new]


def _how_to_load(f: Finding) -> str:
    """One load finding as the reason a model was not checked, with what makes it checkable."""
    import re

    m = re.search(r"package '([\w.-]+)' not found", f.message) if f.code == "X013" else None
    if m is not None:
        return (f"package '{m.group(1)}' is not in the checkout: pass --package {m.group(1)}=PATH, or lint the "
                "workspace that holds it")
    m = re.match(r"xacro argument '([^']+)' has no default", f.message) if f.code == "X010" else None
    if m is not None:
        return (f"xacro argument '{m.group(1)}' has no default: pass --arg {m.group(1)}:=..., or lint the launch "
                "file that runs it")
    return f"{f.code} at {f.location}"


def dedupe(findings: list[Finding]) -> list[Finding]:
    """The same problem seen in several variants or models is reported once, naming where (issue 15)."""
    if not findings:
        return []
    from urdfcheck.finish.collapse import collapse

    return collapse(findings)


def fragment(t: Target) -> bool:
    """A probe whose load failed only on symbols the files that include it provide (`_load_findings`)."""
    return bool(t.probe) and getattr(t, "fragment", False)
