"""JUnit XML for GitLab (`artifacts:reports:junit`), Jenkins (`junit` step) and other CI test views.

    <testsuites>                 one <testsuite> per linted model (and xacro variant)
      <testsuite>                one <testcase> per rule family from the catalogue
        <testcase>               fails (<failure>) when the family has findings at or above --fail-on;
                                 findings below it are listed in <system-out> and the case passes

Counts (`tests`, `failures`, `errors`, `skipped`) are computed from the cases written.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET

from urdfcheck.core import lazyre, paths
from urdfcheck.core.findings import Severity, clean_text

# XML 1.0 cannot carry these at all, even escaped (clean_text already removed C0/C1 controls)
_NOT_XML = lazyre.compile("[^\u0009\u000a\u000d\u0020-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")
OTHER_FAMILY = "other"


def x(text: object, limit: int = 4096) -> str:
    return _NOT_XML.sub("\ufffd", clean_text(text, limit))


def families() -> list[str]:
    from urdfcheck.rules import catalogue as rulebook

    return sorted({r.family for r in rulebook.catalogue().values()})


def family_of(code: str) -> str:
    from urdfcheck.rules import catalogue as rulebook

    info = rulebook.catalogue().get(code)
    return info.family if info else OTHER_FAMILY


def by_target(result, once: bool = False) -> list[tuple[str, str, list]]:
    """[(model display path, variant, findings)] in target order; findings of no target come last.
    A finding that applies to several models/variants (`Finding.where`) counts in each of them, or with
    `once` only in the first (a report that prints it once, naming the others)."""
    groups = []
    claimed = set()
    for t in result.targets:
        shown = paths.shown(t.path, result.root)
        mine = []
        for i, f in enumerate(result.findings):
            if once and i in claimed:
                continue
            if any(p.model == shown and p.variant == t.variant for p in f.places()):
                mine.append(f)
                claimed.add(i)
        groups.append((shown, t.variant, mine))
    rest: dict = {}
    for i, f in enumerate(result.findings):
        if i not in claimed:
            rest.setdefault((f.model or f.location.file, f.variant), []).append(f)
    groups += [(m, v, fs) for (m, v), fs in rest.items()]
    return groups


def finding_line(f, totals: dict | None = None) -> str:
    from urdfcheck.finish.collapse import describe

    where = describe(f, totals, every=True)  # shown in one suite only: name the others
    out = f"{x(str(f.location))}: {f.code} [{f.severity}] {x(f.message)}" + (f" [{x(where)}]" if where else "")
    for v in f.location.via:
        out += f"\n    via macro call at {x(str(v))}"
    for r in f.related:
        out += f"\n    see also {x(str(r))}"
    for a in f.also:
        out += f"\n    also at {x(str(a.location))}: {x(a.message)}"
    return out


def _summary(findings) -> str:
    counts = {s: sum(1 for f in findings if f.severity == s) for s in Severity}
    parts = [f"{counts[s]} {s}" for s in (Severity.ERROR, Severity.WARNING, Severity.INFO) if counts[s]]
    n = len(findings)
    return f"{n} finding{'s' if n != 1 else ''} ({', '.join(parts)})"


def as_tree(result, fail_on: Severity = Severity.WARNING) -> ET.Element:
    fams = families()
    root = ET.Element("testsuites", name="urdfcheck")
    totals = {"tests": 0, "failures": 0}
    from urdfcheck.finish.collapse import variant_totals

    vtotals = variant_totals(result.targets, result.root)
    for model, variant, findings in by_target(result, once=True):  # a collapsed finding: one line, in its first suite
        suite_name = model + (f" [{variant}]" if variant else "")
        classname = model.replace(".", "_").replace("/", ".").replace("\\", ".") + (f"[{variant}]" if variant else "")
        groups: dict[str, list] = {fam: [] for fam in fams}
        for f in findings:
            groups.setdefault(family_of(f.code), []).append(f)
        suite = ET.SubElement(root, "testsuite", name=x(suite_name), tests="0", failures="0", errors="0",
                              skipped="0", time="0")
        n_fail = 0
        for fam, fs in groups.items():
            case = ET.SubElement(suite, "testcase", name=x(fam), classname=x(classname), file=x(model), time="0")
            failing = [f for f in fs if f.severity >= fail_on]
            if failing:
                n_fail += 1
                worst = max(f.severity for f in failing)
                fail = ET.SubElement(case, "failure", message=_summary(failing), type=str(worst))
                fail.text = "\n".join(finding_line(f, vtotals) for f in failing) + "\n"
            below = [f for f in fs if f.severity < fail_on]
            if below:
                out = ET.SubElement(case, "system-out")
                lines = "\n".join(finding_line(f, vtotals) for f in below)
                out.text = ("below --fail-on:\n" if failing else "") + lines + "\n"
        suite.set("tests", str(len(groups)))
        suite.set("failures", str(n_fail))
        totals["tests"] += len(groups)
        totals["failures"] += n_fail
    root.set("tests", str(totals["tests"]))
    root.set("failures", str(totals["failures"]))
    root.set("errors", "0")
    root.set("skipped", "0")
    root.set("time", "0")
    return root


def render(result, fail_on: Severity | None = None, **_) -> str:
    root = as_tree(result, fail_on or Severity.WARNING)
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"
