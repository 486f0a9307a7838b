"""Rule pages from the catalogue: `urdfcheck rules [CODE]` and the generated docs/rules.md."""
from __future__ import annotations

import json

from urdfcheck.core import lazyre
from urdfcheck.rules import catalogue as rulebook

_CODE_SPAN = lazyre.compile(r"(`[^`\n]*`)")


def md(text: str) -> str:
    """Catalogue prose for Markdown: `<robot>` outside code spans would be eaten as an HTML tag."""
    return "".join(part if part.startswith("`") and part.endswith("`") and len(part) > 1
                   else part.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
                   for part in _CODE_SPAN.split(text))


def _example(ex: dict) -> str:
    if not ex:
        return ""
    files = rulebook.example_files(ex)
    out = []
    for name, content in files.items():
        lang = "yaml" if name.endswith((".yaml", ".yml")) else ("python" if name.endswith(".py") else "xml")
        out.append(f"`{name}`\n\n```{lang}\n{str(content).rstrip()}\n```\n")
    if ex.get("args"):
        out.append("xacro arguments: " + ", ".join(f"`{k}:={v}`" for k, v in ex["args"].items()) + "\n")
    if ex.get("flags"):
        out.append("linted with: `urdfcheck lint " + " ".join(str(f) for f in ex["flags"]) + "`\n")
    return "\n".join(out)


def _example_text(ex: dict) -> str:
    """An example for a terminal: file name, then the content indented (no Markdown fences)."""
    if not ex:
        return ""
    files = rulebook.example_files(ex)
    out = []
    for name, content in files.items():
        out.append(f"  {name}:")
        out += ["    " + ln if ln.strip() else "" for ln in str(content).rstrip().splitlines()]
    if ex.get("args"):
        out.append("  xacro arguments: " + " ".join(f"{k}:={v}" for k, v in ex["args"].items()))
    if ex.get("flags"):
        out.append("  linted with: urdfcheck lint " + " ".join(str(f) for f in ex["flags"]))
    return "\n".join(out) + "\n"


def help_markdown(r: rulebook.RuleInfo) -> str:
    """Why, the failing example, the fix and the passing example (SARIF `help.markdown`, rule pages)."""
    parts = [f"**Why it matters.** {md(r.rationale)}\n"]
    if r.examples.get("fail"):
        parts.append("**Example that fails:**\n\n" + _example(r.examples["fail"]))
    parts.append(f"**Use instead.** {md(r.fix)}\n")
    if r.examples.get("pass"):
        parts.append(_example(r.examples["pass"]))
    if r.option_specs:
        parts.append("**Options** (set under `rules: {" + r.code + ": {...}}` in urdfcheck.yaml):\n\n"
                     + "".join(f"- `{s.name}` ({s.type}, default `{s.default}`): {md(s.doc)}\n"
                               for s in r.option_specs.values()))
    for expect, case in ((e, c) for e, c in r.all_examples() if any(c is x for x in r.cases)):
        what = f" {md(str(case['title']))}" if case.get("title") else ""
        parts.append(f"**More: an example that {'fails' if expect == 'fail' else 'passes'}.**{what}\n\n"
                     + _example(case))
    if r.references:
        parts.append("**References** (the upstream sources this rule follows):\n\n"
                     + "".join(f"- <{ref['url']}>: {md(str(ref['what']).strip())}\n" for ref in r.references))
    return "\n".join(parts)


def help_text(r: rulebook.RuleInfo) -> str:
    """Plain-text help: the fix and the examples (SARIF `help.text`)."""
    lines = ["Fix:", r.fix]
    if r.examples.get("fail"):
        lines += ["", "Fails:", _example_text(r.examples["fail"])]
    if r.examples.get("pass"):
        lines += ["Passes:", _example_text(r.examples["pass"])]
    if r.option_specs:
        lines += ["Options:"] + [f"  {s.name} ({s.type}, default {s.default}): {s.doc}"
                                 for s in r.option_specs.values()]
    for expect, case in r.all_examples():
        if any(case is c for c in r.cases):
            lines += [("Also fails:" if expect == "fail" else "Also passes:")
                      + (f" {case['title']}" if case.get("title") else ""), _example_text(case)]
    if r.references:
        lines += ["References:"] + [f"  {ref['url']}  {' '.join(str(ref['what']).split())}" for ref in r.references]
    return "\n".join(lines).rstrip() + "\n"


def page_markdown(r: rulebook.RuleInfo) -> str:
    parts = [f"## {r.code} {r.name}\n", f"Default severity: **{r.severity}**. Family: {r.family}.\n",
             f"**What it checks.** {md(r.summary)}\n", help_markdown(r)]
    return "\n".join(parts)


def page_text(r: rulebook.RuleInfo) -> str:
    lines = [f"{r.code}  {r.name}  ({r.severity}, {r.family})", "", r.summary, "", "Why it matters:",
             r.rationale, "", help_text(r)]
    return "\n".join(lines).rstrip() + "\n"


FORMATS = ("text", "json", "markdown")  # what `page` and `listing` render: `urdfcheck rules --format` offers these


def _known(fmt: str) -> None:
    if fmt not in FORMATS:
        raise ValueError(f"unknown format {fmt!r} (choose from {', '.join(FORMATS)})")


def page(code: str, fmt: str = "text") -> str | None:
    _known(fmt)
    r = rulebook.catalogue().get(code)
    if r is None:
        return None
    if fmt == "json":
        return json.dumps(_as_dict(r), indent=2, sort_keys=True) + "\n"
    return page_markdown(r) if fmt == "markdown" else page_text(r)


def _as_dict(r: rulebook.RuleInfo) -> dict:
    return {"code": r.code, "name": r.name, "severity": str(r.severity), "family": r.family,
            "summary": r.summary, "rationale": r.rationale, "fix": r.fix, "options": r.options,
            "option_types": {n: {"type": s.type, "doc": s.doc} for n, s in r.option_specs.items()}}


def listing(fmt: str = "text") -> str:
    _known(fmt)
    rules = sorted(rulebook.catalogue().values(), key=lambda r: r.code)
    if fmt == "json":
        return json.dumps([_as_dict(r) for r in rules], indent=2, sort_keys=True) + "\n"
    if fmt == "markdown":
        return rules_markdown()
    width = max((len(r.name) for r in rules), default=10)
    return "".join(f"{r.code}  {r.name:<{width}}  {str(r.severity):<7}  {r.summary}\n" for r in rules)


def _cell(text: str) -> str:
    return md(" ".join(text.split())).replace("|", "\\|")


def rules_markdown() -> str:
    """The whole docs/rules.md (generated; a test fails when the committed file is stale)."""
    rules = sorted(rulebook.catalogue().values(), key=lambda r: r.code)
    head = ["# urdfcheck rules", "", "Generated from `rules/*.yaml` by `urdfcheck rules --format markdown`; "
            "do not edit by hand.", "", "| code | name | default | summary |", "| --- | --- | --- | --- |"]
    head += [f"| [{r.code}](#{r.code.lower()}-{r.name}) | {r.name} | {r.severity} | {_cell(r.summary)} |"
             for r in rules]
    return "\n".join(head) + "\n\n" + "\n".join(page_markdown(r) for r in rules)


DESIGN_HEAD = "| code | name | default |"


def design_table() -> str:
    """The rule table of docs/design.md (generated; tests/rules/test_ruledocs.py keeps the committed one current)."""
    rules = sorted(rulebook.catalogue().values(), key=lambda r: r.code)
    return "\n".join([DESIGN_HEAD, "| --- | --- | --- |"]
                     + [f"| {r.code} | {r.name} | {r.severity} |" for r in rules]) + "\n"


def write_design_table(path) -> bool:
    """Replace the rule table in docs/design.md; True when it changed."""
    from pathlib import Path

    p = Path(path)
    text = p.read_text(encoding="utf-8")
    lines = text.splitlines(keepends=True)
    start = next(i for i, ln in enumerate(lines) if ln.startswith(DESIGN_HEAD))
    end = start
    while end < len(lines) and lines[end].startswith("|"):
        end += 1
    new = "".join(lines[:start]) + design_table() + "".join(lines[end:])
    if new != text:
        p.write_text(new, encoding="utf-8")
    return new != text
