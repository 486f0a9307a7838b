"""Suppressions and selection applied to a target's findings (inline in the model, in the YAML files the contract
checks read, in the MoveIt SRDF), and the unused ones (R002)."""
from __future__ import annotations

import os

from urdfcheck.core.findings import Finding, Location, Severity
from urdfcheck.core.suppress import is_srdf, is_yaml, srdf_suppressions, yaml_suppressions
from urdfcheck.rules import catalogue as rulebook
from urdfcheck.rules.engine import Selection


def finish_target(findings: list[Finding], selection: Selection, suppressions=(), model: str = "",
           variant: str = "", yaml_used: set | None = None) -> list[Finding]:
    """Apply selection and severity to load findings too, fill names, drop suppressed, report unused.

    `yaml_used` collects (file, index) of the YAML suppressions that hid a finding: a YAML file serves every
    model of a package, so only the caller, after the last model, can tell one unused (`unused_yaml`)."""
    cat = rulebook.catalogue()
    kept = []
    used = set()
    for f in findings:
        if not selection.enabled(f.code):
            continue
        info = cat.get(f.code)
        sev = selection.severity_of(f.code, f.severity if f.name or not info else info.severity)
        hit = _suppressed(f, suppressions)
        if hit is not None:
            used.add(hit)
            continue
        if is_yaml(f.location.file):
            hit = _suppressed(f, yaml_suppressions(f.location.file))
            if hit is not None:  # `# urdfcheck: ignore[...]` in the YAML file the finding points into
                if yaml_used is not None:  # absolute, like the consumer files `unused_yaml` is given
                    yaml_used.add((os.path.abspath(f.location.file), hit))
                continue
        elif is_srdf(f.location.file) and _suppressed(f, srdf_suppressions(f.location.file)) is not None:
            continue  # `<!-- urdfcheck: ignore[...] -->` in the MoveIt SRDF the finding points into
        kept.append(Finding(f.code, sev, f.message, _shown(f.location),
                            f.name or (info.name if info else ""),
                            tuple(_shown(r) for r in f.related), model or f.model, variant or f.variant,
                            profile=f.profile, evidence=f.evidence, profiles=f.profiles))
    if selection.enabled("R002"):
        for i, s in enumerate(suppressions):
            if i in used:
                continue
            live = [c for c in s.codes if selection.enabled(c)]
            if not live:
                continue
            info = cat.get("R002")
            kept.append(Finding("R002", selection.severity_of("R002", info.severity if info else Severity.WARNING),
                                f"unused suppression of {', '.join(live)}", Location(s.file, s.comment_line),
                                "unused-suppression", (), model, variant))
    return kept


def unused_yaml(files, used: set, selection: Selection) -> list[Finding]:
    """R002 for each suppression in the YAML `files` (read by the contract checks) that hid nothing."""
    if not selection.enabled("R002"):
        return []
    info = rulebook.catalogue().get("R002")
    out = []
    for file in sorted(set(files)):
        for i, s in enumerate(yaml_suppressions(file)):
            live = [c for c in s.codes if selection.enabled(c)]
            if (file, i) in used or not live:
                continue
            out.append(Finding("R002", selection.severity_of("R002", info.severity if info else Severity.WARNING),
                               f"unused suppression of {', '.join(live)}", _shown(Location(file, s.comment_line)),
                               "unused-suppression"))
    return out


def _shown(loc: Location) -> Location:
    """Every location the way reports show files (readers of YAML and launch files record absolute paths)."""
    if not os.path.isabs(loc.file) and not loc.via:
        return loc
    return loc.shown()


def _suppressed(f: Finding, suppressions) -> int | None:
    locs = (f.location,) + f.location.via
    for i, s in enumerate(suppressions):
        if f.code not in s.codes and "ALL" not in s.codes:
            continue
        for loc in locs:
            if loc.file == s.file and (s.first == 0 or (loc.line is not None and s.first <= loc.line <= s.last)):
                return i
    return None


class YamlUse:
    """The YAML files the contract checks read (with the selection they were read under, and the first
    target that read each), and which of their suppressions hid a finding."""

    def __init__(self):
        self.files: dict[str, tuple[Selection, int]] = {}
        self.used: set[tuple[str, int]] = set()
        self.index = 0  # the target being checked

    def read(self, consumers, selection) -> None:
        from urdfcheck.core.suppress import is_yaml

        for paths in (getattr(consumers, "files", None) or {}).values():
            for p in paths:
                if is_yaml(str(p)):
                    self.files.setdefault(os.path.abspath(p), (selection, self.index))

    def unused(self) -> list[tuple[int, Finding]]:
        """(first target that read the file, R002 finding) for each suppression that hid nothing."""
        out = []
        for file in sorted(self.files):
            selection, first = self.files[file]
            out.extend((first, f) for f in unused_yaml([file], self.used, selection))
        return out
