"""One finding per problem: the same problem seen in several variants or models is reported once.

A problem written in a shared xacro macro shows up once per model and variant that expands it, and once
per call of the macro, each time naming that expansion's links ('fer_link8', 'fp3_link8'). Findings with the
same code, severity and source position (file, line, column) whose messages agree once quoted names are set
aside are one problem: the first is kept and `Finding.where` lists every model/variant it applies to (with
the message there when it reads differently). The reports print one line for it; JSON keeps the list.

Instances inside one model (a wheel macro called for the left and the right wheel, an arm macro expanded
for two arms) are one problem as well: one edit at that line fixes them all, so they are one line, naming
the other instances ("also 'right_wheel_link'").

The same problem written again at other lines of the same file, in exactly the same models and variants
(twelve joints named like their links, six joints with effort limit 0, an unknown element repeated in every
joint) is one line too: the first place, then "also 'LF_HFE', … at lines 687, 763, …"; `Finding.also` keeps
each place (JSON `also`, SARIF related locations).
"""
from __future__ import annotations

from urdfcheck.core import lazyre
from urdfcheck.core.findings import Also, Finding, Place

# a quoted name: no blank inside, so that "('link 'x' is not unique')" (urdfdom's words quoted) pairs up right
_QUOTED = lazyre.compile(r"'[^'\s]*'|\"[^\"\s]*\"")
_HINT = lazyre.compile(r" \(did you mean [^)]*\)")


# names as urdfdom's messages quote them: "parent link [fer_link8] of joint [fer_hand_joint] not found"
_BRACKETED = lazyre.compile(r"\[[^\]\s]*\]")
# a file path written without quotes ("file not found (pkg/meshes/a.dae)", "No such file or directory: x/y.yaml")
_PATH = lazyre.compile(r"[^\s'\"()\[\]]*/[^\s'\"()\[\]]*\.\w+")


def _shape(message: str) -> str:
    """The message with quoted names (and name suggestions) set aside: what stays equal across macro
    expansions."""
    return _PATH.sub("…", _BRACKETED.sub("[…]", _QUOTED.sub("'…'", _HINT.sub("", message))))


def collapse(findings: list[Finding]) -> list[Finding]:
    """Merge findings that are the same problem (see the module doc); sorted like `Finding.sort_key`."""
    groups: dict[tuple, list[Finding]] = {}
    exact: set[tuple] = set()
    for f in findings:
        loc = f.location
        if loc.line is None:
            # a finding with no line is about a whole file: only identical messages are the same problem
            key = (f.code, f.severity, loc.file, None, None, f.message)
        else:
            key = (f.code, f.severity, loc.file, loc.line, loc.column, _shape(f.message))
        place = f.places()[0][:2]
        if (key, place, f.message, loc.via) in exact:
            continue  # the very same finding again (same macro call chain)
        exact.add((key, place, f.message, loc.via))
        groups.setdefault(key, []).append(f)
    out = []
    for members in groups.values():
        out.append(members[0] if len(members) == 1 and not members[0].where else _merge(members))
    return _across_lines(out)


def _across_lines(findings: list[Finding]) -> list[Finding]:
    """Merge the same problem at several lines of one file (see the module doc); the first line leads. Returns
    them sorted like `Finding.sort_key` (groups keep the order of their first member)."""
    groups: dict[tuple, list[Finding]] = {}
    for f in sorted(findings, key=Finding.sort_key):
        loc = f.location
        if loc.line is None:
            groups[(id(f),)] = [f]
            continue
        places = frozenset((p.model, p.variant) for p in f.places())
        groups.setdefault((f.code, f.severity, loc.file, _shape(f.message), places), []).append(f)
    out = []
    for first, *rest in groups.values():
        out.append(first._replace(also=tuple(Also(g.location, g.message) for g in rest)) if rest else first)
    return out


def _merge(members: list[Finding]) -> Finding:
    first = members[0]
    places: dict[tuple[str, str, str], tuple] = {}  # ordered: place -> its call chain
    for f in members:
        for p in f.places():
            msg = p.message or f.message
            places.setdefault((p.model, p.variant, "" if msg == first.message else msg), p.via or f.location.via)
    where = tuple(Place(m, v, msg, via) for (m, v, msg), via in places.items())
    if len(where) == 1:
        return first._replace(where=())
    return first._replace(model=where[0].model, variant=where[0].variant, where=where)


def chains(f: Finding) -> list[tuple]:
    """The distinct macro call chains of a problem's instances in the model/variant it is shown under (a wheel
    macro called for each wheel: one chain per call), the finding's own first."""
    first = f.places()[0]
    out = [f.location.via] if f.location.via else []
    for p in f.places()[1:]:
        if (p.model, p.variant) == (first.model, first.variant) and p.via and p.via not in out:
            out.append(p.via)
    return out


def _short_names(paths: list[str]) -> list[str]:
    """Each path by its file name, with as many parent folders as it takes to tell two apart
    (moveit_resources has two panda.urdf.xacro)."""
    out = []
    for p in paths:
        parts = p.split("/")
        n = 1
        while n < len(parts) and any(q != p and q.split("/")[-n:] == parts[-n:] for q in paths):
            n += 1
        out.append("/".join(parts[-n:]))
    return out


def _short(label: str) -> str:
    """A variant label for one line: a launch file path (a deployment's label) by its file name."""
    head, sep, rest = label.partition(" ")
    return head.rsplit("/", 1)[-1] + sep + rest if "/" in head else label


def _first_name(message: str) -> str | None:
    m = _QUOTED.search(message)
    return m.group(0) if m else None


def _other_names(own_message: str, messages) -> list[str]:
    """The first quoted name of each message, once each, other than the one `own_message` names."""
    own = _first_name(own_message)
    names: list[str] = []
    for message in messages:
        name = _first_name(message)
        if name and name != own and name not in names:
            names.append(name)
    return names


def _listed(names: list[str], limit: int) -> str:
    return ", ".join(names[:limit]) + (f" and {len(names) - limit} more" if len(names) > limit else "")


def instances(f: Finding, limit: int = 3) -> str:
    """The other instances of a problem in the model/variant the finding is shown under: "also 'right_wheel'"."""
    first, *others = f.places()
    names = _other_names(f.message, (p.message for p in others
                                     if (p.model, p.variant) == (first.model, first.variant) and p.message))
    return "also " + _listed(names, limit) if names else ""


def elsewhere(f: Finding, limit: int = 3) -> str:
    """The other lines of the file with the same problem: "also 'LF_HFE', 'LF_KFE' and 9 more at lines 687,
    763, …" (names as the messages quote them, when they do)."""
    if not f.also:
        return ""
    names = _other_names(f.message, (a.message for a in f.also))
    lines = [str(a.location.line) for a in f.also]
    shown_lines = ", ".join(lines[:limit]) + (", …" if len(lines) > limit else "")
    head = "also " + (_listed(names, limit) + " " if names else "")
    return f"{head}at line{'s' if len(lines) > 1 else ''} {shown_lines}"


def describe(f: Finding, totals: dict[str, int] | None = None, limit: int = 3, every: bool = False) -> str:
    """Where a finding applies, for one line of a report: "" (one place), "variant: a=true",
    "in 12 of 16 variants: a=true, b=false, …", "in 3 models: x.urdf, y.urdf, …"; nothing when it applies to
    every variant of its model, unless `every` ("in all 16 variants"). `totals`: model -> number of variants linted."""
    places = f.places()
    parts = [s for s in (instances(f, limit), elsewhere(f, limit)) if s]
    models = list(dict.fromkeys(p.model for p in places))
    if len(models) > 1:
        names = _short_names(models)
        shown = ", ".join(names[:limit]) + (", …" if len(names) > limit else "")
        parts.append(f"in {len(models)} models: {shown}")
        # and in which of their variants, unless in all of them
        per_model = {m: {p.variant for p in places if p.model == m} for m in models}
        if any(v != {""} and len(v) < (totals or {}).get(m, len(v) + 1) for m, v in per_model.items()):
            variants = list(dict.fromkeys(_short(p.variant) for p in places if p.variant))
            shown = ", ".join(variants[:limit]) + (", …" if len(variants) > limit else "")
            parts.append(f"variant{'s' if len(variants) > 1 else ''} {shown}")
    else:
        variants = list(dict.fromkeys(_short(p.variant) for p in places if p.variant))
        total = (totals or {}).get(models[0] if models else "", 0)
        if len(variants) == 1 and total != 1:
            parts.append(f"variant {variants[0]}")
        elif len(variants) > 1 and not (total and len(variants) >= total):
            shown = ", ".join(variants[:limit]) + (", …" if len(variants) > limit else "")
            of = f" of {total}" if total else ""
            parts.append(f"in {len(variants)}{of} variants: {shown}")
        elif len(variants) > 1 and every:  # a report that shows it once, under one variant, says so
            parts.append(f"in all {len(variants)} variants")
        else:  # shown in every variant: a deployment's launch file is still named (issue 13), short
            launch = [v for v in variants if _LAUNCH.search(v)]
            if launch:
                shown = ", ".join(launch[:limit]) + (", …" if len(launch) > limit else "")
                parts.append(f"from {shown}" if len(launch) == 1 else f"from {len(launch)} launch files: {shown}")
    return "; ".join(parts)


_LAUNCH = lazyre.compile(r"(\.launch(\.py|\.xml|\.ya?ml)?|_launch\.py)( \[|$)")


def variant_totals(targets, root: str = "") -> dict[str, int]:
    """model display path -> how many variants of it were linted (for "in 3 of 4 variants")."""
    from urdfcheck.core.paths import shown

    out: dict[str, int] = {}
    for t in targets:
        where = shown(t.path, root)
        out[where] = out.get(where, 0) + 1
    return out
