"""Markdown for a pull-request comment (GitHub/GitLab flavoured).

Summary table (severity counts per model and variant), findings table, and the TF tree of every linted
model as a Mermaid flowchart (parent -> child per joint, labelled with the joint name and type).

Everything from the model is untrusted: it goes through `clean_text`, then Markdown/HTML escaping for
tables (so a link name cannot close a table, open HTML, ping `@someone` or end a code fence) or
Mermaid entity codes inside diagrams (only `[A-Za-z0-9_ ]` is written literally). The comment stays
under GitHub's 65 536 character limit: diagrams are dropped first, then findings rows.
"""
from __future__ import annotations

from urdfcheck.core import lazyre, paths
from urdfcheck.core.findings import Severity, clean_text
from urdfcheck.report.junit import by_target

MAX_CHARS = 60_000
MAX_ROWS = 200
MAX_TREE_JOINTS = 300
_ICON = {Severity.ERROR: "🔴 error", Severity.WARNING: "🟠 warning", Severity.INFO: "🔵 info"}
_MD_SPECIAL = lazyre.compile(r"([\\`*_\[\]|~#!$])")


# what GitHub and GitLab turn into a link by itself (an "autolink"): a scheme, or www.
_BARE_URL = lazyre.compile(r"(?i)\b(?:[a-z][a-z0-9+.-]{1,20}://|www\.)[^\s`|]*")


def md(text: object, limit: int = 500) -> str:
    """Untrusted text as inert Markdown inline text (also safe inside a table cell): HTML as entities, Markdown
    syntax (links, emphasis, code) backslash-escaped, no @mention (a zero-width space after the @), a bare URL in a
    code span (shown, not a link)."""
    s = clean_text(text, limit)
    out, at = [], 0
    for m in _BARE_URL.finditer(s):
        out += [_inline(s[at:m.start()]), f"`{m.group(0)}`"]
        at = m.end()
    return "".join(out) + _inline(s[at:])


def _inline(s: str) -> str:
    s = s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")
    s = _MD_SPECIAL.sub(r"\\\1", s)
    return s.replace("@", "@\u200b")  # no @mentions from a model


def code(text: object, limit: int = 500) -> str:
    """Untrusted text as the inside of a `code span` in a table cell: no backtick to end it, `|` escaped (a GFM
    table splits cells before it parses code spans)."""
    return clean_text(text, limit).replace("`", "'").replace("|", "\\|")


_MERMAID_SAFE = lazyre.compile(r"[A-Za-z0-9_ ]")


def mermaid(text: object, limit: int = 200) -> str:
    """Untrusted text for a quoted Mermaid label: everything but [A-Za-z0-9_ ] as `#NNN;` entity codes."""
    s = clean_text(text, limit)
    return "".join(ch if _MERMAID_SAFE.fullmatch(ch) else f"#{ord(ch)};" for ch in s)


def tf_tree(model) -> list[str]:
    """Mermaid flowchart lines for a Model: one node per link, one edge per joint (parent -> child)."""
    ids: dict[str, str] = {}

    def node(name) -> str:
        if name not in ids:
            ids[name] = f"n{len(ids)}"
        return ids[name]

    lines = ["flowchart TD"]
    for name in model.links:
        lines.append(f'  {node(name)}["{mermaid(name)}"]')
    for j in model.joint_list:
        if j.parent is None or j.child is None:
            continue
        missing = [n for n in (j.parent, j.child) if n not in ids]
        for n in missing:
            lines.append(f'  {node(n)}["{mermaid(n)} #40;missing#41;"]')
        label = mermaid(f"{j.name} ({j.type})")
        lines.append(f'  {node(j.parent)} -->|"{label}"| {node(j.child)}')
    return lines


def _counts(findings) -> dict:
    return {s: sum(1 for f in findings if f.severity == s) for s in Severity}


def _where(f) -> str:
    out = md(str(f.location), 4096)
    if f.location.via:
        out += " via " + ", ".join(md(str(v), 4096) for v in f.location.via)
    return out


def _summary(result, fail_on: Severity, max_rows: int = MAX_ROWS) -> list[str]:
    from urdfcheck.report import gate, gate_words

    total = _counts(result.findings)
    failing = len(gate(result, fail_on)[0])  # what the exit code judges (with --diff-base: the new ones)
    n_models = len(result.targets)
    models = f"{n_models} model{'s' if n_models != 1 else ''}"
    why_not = getattr(result, "not_passed", lambda: None)()  # no robot, or a model that did not load
    words = gate_words(result, fail_on)
    if words is not None:
        failing = words[0]  # the exit code's own count
    if words is not None and (failing or not why_not):
        _, gating, rest = words
        mark = "❌" if failing else "✅"
        head = (f"{mark} **{md(gating)}** in {models} ({md(rest) + '; ' if rest else ''}"
                f"{total[Severity.ERROR]} errors, {total[Severity.WARNING]} warnings, {total[Severity.INFO]} info "
                "in all)")
    elif failing:
        head = (f"❌ **{failing} finding{'s' if failing != 1 else ''} at or above {fail_on}** in {models} "
                f"({total[Severity.ERROR]} errors, {total[Severity.WARNING]} warnings, "
                f"{total[Severity.INFO]} info)")
    elif result.findings and not why_not:
        head = f"✅ nothing at or above {fail_on} in {models} ({len(result.findings)} below it)"
    elif why_not:
        head = f"⚠️ nothing checked: {why_not}"
    else:
        head = f"✅ all checks passed: {models}, no findings"
    lines = ["## urdfcheck", "", head, "", "| model | variant | errors | warnings | info |",
             "| --- | --- | ---: | ---: | ---: |"]
    groups = by_target(result)
    for model, variant, findings in groups[:max_rows]:
        c = _counts(findings)
        lines.append(f"| {md(model, 4096)} | {md(variant) if variant else '–'} | {c[Severity.ERROR]} | "
                     f"{c[Severity.WARNING]} | {c[Severity.INFO]} |")
    if len(groups) > max_rows:
        lines += ["", f"… and {len(groups) - max_rows} more models."]
    return lines


def _findings(result, max_rows: int) -> list[str]:
    if not result.findings:
        return []
    lines = ["", "### Findings", "", "| severity | rule | location | message |", "| --- | --- | --- | --- |"]
    from urdfcheck.finish.collapse import describe, variant_totals

    totals = variant_totals(result.targets, result.root)
    ordered = sorted(result.findings, key=lambda f: (-int(f.severity), f.sort_key()))
    for f in ordered[:max_rows]:
        msg = md(f.message)
        where = describe(f, totals)
        if where:
            msg += f" \\[{md(where)}\\]"
        lines.append(f"| {_ICON[f.severity]} | **{f.code}** {md(f.name)} | {_where(f)} | {msg} |")
    if len(ordered) > max_rows:
        lines += ["", f"… and {len(ordered) - max_rows} more (see the full report in the job output)."]
    return lines


def _trees(result) -> list[str]:
    models = getattr(result, "models", None) or {}
    out = []
    for t in result.targets:
        model = models.get((str(t.path), t.variant))
        shown = paths.shown(t.path, result.root)  # relative, like the findings
        title = md(shown, 4096) + (f" \\[{md(t.variant)}\\]" if t.variant else "")
        if model is None:
            out += [f"- {title}: not loaded (see the findings)"]
            continue
        if len(model.joint_list) > MAX_TREE_JOINTS:
            out += [f"- {title}: {len(model.joint_list)} joints, too large to draw here"]
            continue
        out += ["", f"<details><summary>TF tree of {title} ({len(model.links)} links, "
                    f"{len(model.joint_list)} joints)</summary>", "", "```mermaid", *tf_tree(model), "```", "",
                "</details>"]
    return ["", "### TF trees", *out] if out else []


def render(result, fail_on: Severity | None = None, **_) -> str:
    fail_on = fail_on or Severity.WARNING
    rows = MAX_ROWS
    trees = _trees(result)
    dropped = not trees
    while True:
        text = "\n".join(_summary(result, fail_on, rows) + _findings(result, rows) + trees) + "\n"
        if len(text) <= MAX_CHARS:
            return text
        if not dropped:
            trees = ["", "### TF trees", "", "_Diagrams left out: the comment would be too long._"]
            dropped = True
            continue
        if rows <= 1:
            cut = text[:MAX_CHARS - 80].rsplit("\n", 1)[0]
            return cut + "\n\n… truncated (see the full report in the job output).\n"
        rows //= 2
