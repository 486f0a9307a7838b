"""`urdfcheck diff` reports: text, JSON, Markdown (a Mermaid tree with the changed edges highlighted and a table
of moved frames, for a pull-request comment or a job summary)."""
from __future__ import annotations

import json

from urdfcheck.core import lazyre
from urdfcheck.core.findings import clean_text as _clean

# bidi controls reorder what a reviewer reads (a link name that displays as another); dropped from every format
_BIDI = lazyre.compile("[\u061c\u200e\u200f\u202a-\u202e\u2066-\u2069]")


def clean_text(text, limit: int = 500) -> str:
    return _BIDI.sub("", _clean(text, limit))

MAX_MERMAID_EDGES = 300  # GitHub renders larger diagrams poorly (and stops at its text limit)


FORMATS = ("text", "json", "markdown")  # what `render` renders: `urdfcheck diff --format` offers these


def render(fmt: str, result, shown=str) -> str:
    from urdfcheck.report import finish_text

    if fmt not in FORMATS:
        raise ValueError(f"unknown format {fmt!r} (choose from {', '.join(FORMATS)})")

    if fmt == "json":
        return finish_text(json.dumps(result.as_dict(), indent=2, sort_keys=False) + "\n", "json")
    if fmt == "markdown":
        return finish_text(markdown(result, shown), "markdown")
    return finish_text(text(result, shown), "text")


def _title(p) -> str:
    return clean_text(p.model) + (f" [{clean_text(p.variant)}]" if p.variant else "")


def _v(value) -> str:
    if value is None:
        return "(none)"
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, list):
        return "[" + ", ".join(_v(x) for x in value) + "]"
    return clean_text(str(value))


def _structure(p) -> list[str]:
    out = []
    for what in ("links", "joints"):
        d = getattr(p, what)
        for n in d["added"]:
            out.append(f"{what[:-1]} added: {n}")
        for n in d["removed"]:
            out.append(f"{what[:-1]} removed: {n}")
        for o, n in d["renamed"]:
            out.append(f"{what[:-1]} renamed: {o} -> {n}")
    return [clean_text(x) for x in out]


def _change_line(c) -> str:
    field = f".{c['field']}" if c["field"] else ""
    return clean_text(f"{c['kind']} {c['name']}{field}: {_v(c['old'])} -> {_v(c['new'])}")


def _moved_line(m) -> str:
    where = f"{m['zero_mm']:g} mm, {m['zero_deg']:g} deg at zero" if (m["zero_mm"] or m["zero_deg"]) else \
        "at zero: not moved"
    cause = f" (joint {m['because']})" if m["because"] else ""
    return clean_text(f"{m['frame']} moved {m['mm']:g} mm, {m['deg']:g} deg ({where}){cause}")


def _detail(p) -> list[str]:
    return [*_structure(p), *(_moved_line(m) for m in p.moved), *(_change_line(c) for c in p.changes)]


def _models(result) -> list[list]:
    """The pairs grouped by model, in order."""
    groups: dict[str, list] = {}
    for p in result.pairs:
        groups.setdefault(p.model, []).append(p)
    return list(groups.values())


def _in(n: int, m: int, variants: list[str]) -> str:
    """lint's way: nothing when a line holds in every variant, else "[in N of M variants: a, b]"."""
    if n >= m:
        return ""
    names = [clean_text(v) for v in variants[:3]] + (["..."] if len(variants) > 3 else [])
    return f" [in {n} of {m} variants: {', '.join(names)}]"


def _collapsed(pairs) -> list[tuple[str, int, list[str]]]:
    """(line, how many variants show it, which) for the changed pairs of one model: a change seen in every
    variant is one line, not one per variant."""
    seen: dict[str, list[str]] = {}
    for p in pairs:
        for line in dict.fromkeys(_detail(p)):
            seen.setdefault(line, []).append(p.variant)
    return [(line, len(vs), vs) for line, vs in seen.items()]


def text(result, shown=str) -> str:
    lines = [f"note: {clean_text(n, 4096)}" for n in result.notes]
    for group in _models(result):
        if len(group) > 1 and all(p.status == "unchanged" for p in group):
            lines.append(f"{clean_text(group[0].model)}: no change in {len(group)} variants")
            continue
        changed = [p for p in group if p.status == "changed"]
        for p in group:
            if p.status == "unchanged":
                lines.append(f"{_title(p)}: no change")
            elif p.status in ("added", "removed"):
                lines.append(f"{_title(p)}: model {p.status}")
            elif p.status == "unloadable":
                lines.append(f"{_title(p)}: not compared, a side does not load")
                for side, errs in p.errors.items():
                    lines.extend(f"  {side}: {clean_text(e, 4096)}" for e in errs[:10])
        if len(changed) == 1 and len(group) == 1:
            lines.append(f"{_title(changed[0])}: changed")
            lines.extend(f"  {x}" for x in _detail(changed[0]))
        elif changed:
            lines.append(f"{clean_text(group[0].model)}: changed in {len(changed)} of {len(group)} variants")
            lines.extend(f"  {line}{_in(n, len(changed), vs)}" for line, n, vs in _collapsed(changed))
    lines.extend(_findings_text(result))
    lines.append(_tally(result))
    return "\n".join(lines) + "\n"


def _findings_text(result) -> list[str]:
    fd = getattr(result, "findings", None)
    return [] if fd is None else fd.text_lines()


def _tally(result) -> str:
    n = len(result.pairs)
    changed = sum(p.status in ("changed", "added", "removed") for p in result.pairs)
    broken = sum(p.status == "unloadable" for p in result.pairs)
    out = f"{changed} of {n} model variants changed" if changed else \
        f"no change in {n - broken} model variant{'s' if n - broken != 1 else ''}"
    if broken:
        out += f"; {broken} not compared (a side does not load)"
    return out


def _cell(s) -> str:
    """Untrusted text in a table cell or list item: HTML, links, @mentions and bare URLs made inert."""
    from urdfcheck.report.markdown import md

    return md(str(s))


def _code(s) -> str:
    """Untrusted text inside a `code span`."""
    from urdfcheck.report.markdown import code

    return code(str(s))


def markdown(result, shown=str) -> str:
    out = ["## urdfcheck diff", ""]
    out += [_tally(result), ""]
    out += [f"- note: {_cell(n)}" for n in result.notes] + ([""] if result.notes else [])
    fd = getattr(result, "findings", None)
    if fd is not None:
        out += fd.markdown_lines() + [""]
    if not any(p.changed for p in result.pairs):
        return "\n".join(out) + "\n"
    for group in _models(result):
        changed = [p for p in group if p.status == "changed"]
        for p in group:
            if p.status in ("added", "removed", "unloadable"):
                out += [f"### `{_code(_title(p))}`: {p.status}", ""]
            if p.status == "unloadable":
                for side, errs in p.errors.items():
                    out.extend(f"- {side}: `{_code(e)}`" for e in errs[:10])
                out.append("")
        if not changed:
            continue
        if len(group) == 1:
            out += [f"### `{_code(_title(changed[0]))}`: changed", ""]
        else:
            out += [f"### `{_code(group[0].model)}`: changed in {len(changed)} of {len(group)} variants", ""]
        m = len(changed)
        tables = {_change_line(c) for p in changed for c in p.changes}
        out.extend(f"- {_cell(line)}{_cell(_in(n, m, vs))}" for line, n, vs in _collapsed(changed)
                   if line not in tables)
        rows: dict[tuple, list[str]] = {}
        for p in changed:
            for c in p.changes:
                row = (c["kind"], c["name"], c["field"], _v(c["old"]), _v(c["new"]))
                if p.variant not in rows.setdefault(row, []):
                    rows[row].append(p.variant)
        if rows:
            out += ["", "| what | field | before | after |" + (" variants |" if m > 1 else ""),
                    "| --- | --- | --- | --- |" + (" --- |" if m > 1 else "")]
            for (kind, name, field, old, new), vs in rows.items():
                where = f" {_cell(_in(len(vs), m, vs).strip(' []') or 'all')} |" if m > 1 else ""
                out.append(f"| {_cell(kind)} `{_code(name)}` | {_cell(field)} | {_cell(old)} | {_cell(new)} |{where}")
        first = changed[0]
        if first.moved:
            out += ["", "| frame | moved (mm) | rotated (deg) | at zero (mm, deg) | changed joint |",
                    "| --- | ---: | ---: | --- | --- |"]
            for m in first.moved:
                out.append(f"| `{_code(m['frame'])}` | {m['mm']:g} | {m['deg']:g} | {m['zero_mm']:g}, "
                           f"{m['zero_deg']:g} | {_cell(m['because'] or '')} |")
        diagram = mermaid(first)
        if diagram:
            out += ["", "```mermaid", diagram, "```"]
        out.append("")
    return "\n".join(out) + "\n"


def mermaid(p) -> str:
    """The new tree; the edges of changed, added or renamed joints (and of moved frames) in red, removed ones
    dashed grey."""
    if p.tree is None:
        return ""
    edges, roots, removed, _ = p.tree
    if len(edges) + len(removed) > MAX_MERMAID_EDGES:
        return ""
    hot = {c["name"] for c in p.changes if c["kind"] == "joint"}
    hot |= set(p.joints["added"]) | {n for _, n in p.joints["renamed"]}
    moved = {m["frame"] for m in p.moved if m["because"] is None or m["because"] in hot}
    ids: dict[str, str] = {}

    def node(name):
        if name not in ids:
            ids[name] = f"n{len(ids)}"
        return ids[name]

    def label(s):  # only [A-Za-z0-9_ ] literally: no HTML, quote or arrow from a name reaches the diagram
        from urdfcheck.report.markdown import mermaid as entities

        return entities(str(s))

    lines = ["graph TD"]
    for r in roots:
        lines.append(f'    {node(r)}["{label(r)}"]')
    red, grey = [], []
    k = 0
    for parent, joint, child in edges:
        if parent is None or child is None:
            continue
        lines.append(f'    {node(parent)} -->|"{label(joint)}"| {node(child)}["{label(child)}"]')
        if joint in hot or child in moved:
            red.append(k)
        k += 1
    for parent, joint, child in removed:
        if parent is None or child is None:
            continue
        src = ids[parent] if parent in ids else f'{node("old:" + parent)}["{label(parent)}"]'
        lines.append(f'    {src} -.->|"{label(joint)} (removed)"| {node("old:" + child)}["{label(child)}"]')
        grey.append(k)
        k += 1
    if red:
        lines.append(f"    linkStyle {','.join(map(str, red))} stroke:#d33,stroke-width:3px")
    if grey:
        lines.append(f"    linkStyle {','.join(map(str, grey))} stroke:#999,stroke-dasharray:4")
    return "\n".join(lines)
