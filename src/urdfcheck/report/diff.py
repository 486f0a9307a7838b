"""`urdfcheck diff` reports: text, JSON, Markdown (a Mermaid tree with the changed edges highlighted and a table
of moved frames, for a pull-request comment or a job summary)."""
from __future__ import annotations

import json

from urdfcheck.core.findings import clean_text

MAX_MERMAID_EDGES = 300  # GitHub renders larger diagrams poorly (and stops at its text limit)


def render(fmt: str, result, shown=str) -> str:
    from urdfcheck.report import finish_text

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


def text(result, shown=str) -> str:
    lines = []
    for p in result.pairs:
        if p.status == "unchanged":
            lines.append(f"{_title(p)}: no change")
            continue
        if p.status in ("added", "removed"):
            lines.append(f"{_title(p)}: model {p.status}")
            continue
        if p.status == "unloadable":
            lines.append(f"{_title(p)}: not compared, a side does not load")
            for side, errs in p.errors.items():
                lines.extend(f"  {side}: {clean_text(e, 4096)}" for e in errs[:10])
            continue
        lines.append(f"{_title(p)}: changed")
        lines.extend(f"  {x}" for x in _structure(p))
        lines.extend(f"  {_moved_line(m)}" for m in p.moved)
        lines.extend(f"  {_change_line(c)}" for c in p.changes)
    lines.append(_tally(result))
    return "\n".join(lines) + "\n"


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
    if not any(p.changed for p in result.pairs):
        return "\n".join(out) + "\n"
    for p in result.pairs:
        out.append(f"### `{_code(_title(p))}`: {'no change' if not p.changed else p.status}")
        out.append("")
        if p.status == "unloadable":
            for side, errs in p.errors.items():
                out.extend(f"- {side}: `{_code(e)}`" for e in errs[:10])
            out.append("")
        if p.status != "changed":
            continue
        out.extend(f"- {_cell(x)}" for x in _structure(p))
        if p.moved:
            out += ["", "| frame | moved (mm) | rotated (deg) | at zero (mm, deg) | changed joint |",
                    "| --- | ---: | ---: | --- | --- |"]
            for m in p.moved:
                out.append(f"| `{_code(m['frame'])}` | {m['mm']:g} | {m['deg']:g} | {m['zero_mm']:g}, "
                           f"{m['zero_deg']:g} | {_cell(m['because'] or '')} |")
        if p.changes:
            out += ["", "| what | field | before | after |", "| --- | --- | --- | --- |"]
            for c in p.changes:
                out.append(f"| {_cell(c['kind'])} `{_code(c['name'])}` | {_cell(c['field'])} | {_cell(_v(c['old']))} "
                           f"| {_cell(_v(c['new']))} |")
        diagram = mermaid(p)
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
