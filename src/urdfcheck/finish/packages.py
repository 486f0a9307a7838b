"""One X013 per package the run cannot resolve (naming every place that references it), and the evidence rule for
a package the checkout references but does not hold."""
from __future__ import annotations

import os
from pathlib import Path

from urdfcheck.core.findings import Finding, Location
from urdfcheck.core.paths import shown

_MISSING = None


def missing_packages_once(result) -> dict[str, Finding]:  # result: finish.result.Result
    """One X013 per package the run cannot resolve, naming every place that references it (the first is the
    finding's location, the others its related locations), instead of one per model and variant. An
    expansion stops at its first unknown package; the models that hit one are read as text through their
    literal includes (`load.packages.missing_packages`), so every missing package is listed in one run."""
    import re

    global _MISSING
    _MISSING = _MISSING or re.compile(r"package '([A-Za-z0-9_]+)' not found")
    if not any(f.code == "X013" for f in result.findings):
        return {}
    from urdfcheck.load.packages import Resolver, missing_packages

    template: dict[str, Finding] = {}
    owners: dict[str, list] = {}  # package -> the targets that stopped at it
    places: dict[str, list[tuple[str, int]]] = {}
    variants: dict[str, list] = {}  # package -> the (model, variant) places the loader stopped at it
    for t, found in zip(result.targets, result.by_target):
        hits = [f for f in found if f.code == "X013"]
        if not hits:
            continue
        names = {m.group(1) for f in hits if (m := _MISSING.search(f.message))}
        if not names:
            continue
        for n in names:
            owners.setdefault(n, []).append(t)
        find = Resolver(dict(t.packages), near=Path(os.path.abspath(t.path))).find
        missing = missing_packages([str(t.path)], find)
        for f in hits:
            m = _MISSING.search(f.message)
            if m:
                template.setdefault(m.group(1), f)
                seen_in = variants.setdefault(m.group(1), [])
                seen_in.extend(p for p in f.places() if p not in seen_in)
                missing.setdefault(m.group(1), []).insert(0, (f.location.file, f.location.line or 0))
        for name, where in missing.items():
            have = places.setdefault(name, [])
            known = {(os.path.abspath(f), ln) for f, ln in have}
            for f, ln in where:
                if (os.path.abspath(f), ln) not in known:
                    known.add((os.path.abspath(f), ln))
                    have.append((shown(f), ln))  # as the loader's findings show paths
            if name not in template and hits:
                template[name] = hits[0]
    if not places:
        return {}
    merged = {}
    for name, where in places.items():
        base = template[name]
        first = Location(where[0][0], where[0][1] or None)
        rest = tuple(Location(f, ln or None) for f, ln in where[1:])
        n = len(where)
        msg = (f"package {name!r} not found (pass --package {name}=PATH)"
               + (f"; referenced in {n} places" if n > 1 else ""))
        seen_in = variants.get(name, [])
        merged[name] = _outside(base._replace(message=msg, location=first, related=rest,
                                              where=tuple(seen_in) if len(seen_in) > 1 else ()),
                                name, owners.get(name, ()))
    result.findings = sorted([f for f in result.findings if f.code != "X013"] + list(merged.values()),
                             key=Finding.sort_key)
    return merged


def _outside(f: Finding, name: str, targets) -> Finding:
    """The evidence rule for a package not found (issue 37): one the checkout references but does not hold is a
    dependency the workspace provides (colcon builds the repository beside its dependencies): linted alone, its
    absence is no defect of the repository, so an info saying how to confirm. It stays an error when the runner
    named the package (--package, the config's packages:) or when a package of the checkout has a name it
    nearly matches (a misspelt name: that package never provides it)."""
    import difflib

    from urdfcheck.core.evidence import Step
    from urdfcheck.rules import engine

    have: set[str] = set()
    for t in targets:
        settings = getattr(t, "settings", None)
        if settings is not None and name in dict(settings.packages):
            return f
        have.update(t.packages)
    if difflib.get_close_matches(name, sorted(have), n=1, cutoff=0.85):
        return f
    step = Step("package", name, "outside", f"pass --package {name}=PATH, or lint from a workspace that holds it")
    return engine.on_evidence([f], (step,))[0]


def merge_x013(found: list[Finding], merged: dict) -> list[Finding]:
    """A target's findings with its X013 replaced by the run's one X013 per package."""
    if not merged:
        return found
    out, seen = [], set()
    for f in found:
        m = _MISSING.search(f.message) if f.code == "X013" else None
        if m is not None and m.group(1) in merged:
            if m.group(1) not in seen:
                seen.add(m.group(1))
                out.append(merged[m.group(1)])
        else:
            out.append(f)
    return out
