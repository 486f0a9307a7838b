"""GitHub Actions workflow commands: one annotation per finding.

    ::error file=urdf/robot.urdf,line=12,col=5,title=S001 multiple-roots::The model has 2 root links ...

error -> `::error`, warning -> `::warning`, info -> `::notice`. Escaping follows the runner's rules
(`%` -> `%25`, CR -> `%0D`, LF -> `%0A`; in properties also `:` -> `%3A` and `,` -> `%2C`), and all text
from the model went through `clean_text` first, so nothing from a model can start a workflow command:
every line this module prints starts with `::<level> ` or is a fixed summary. Only here does every `::` of the
message get a zero-width space between its colons (the other formats leave `gz::sim::systems` as it is).
"""
from __future__ import annotations

from urdfcheck.core.findings import Severity, clean_text

COMMANDS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}


def escape_data(text: str) -> str:
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def defuse(text: str) -> str:
    return text.replace("::", ":\u200b:")


def escape_property(text: str) -> str:
    return escape_data(text).replace(":", "%3A").replace(",", "%2C")


def command(f, totals: dict | None = None) -> str:
    from urdfcheck.finish.collapse import describe

    props = []
    if f.location.file:
        props.append("file=" + escape_property(clean_text(f.location.file, 4096)))
    if f.location.line:
        props.append(f"line={int(f.location.line)}")
        if f.location.column:
            props.append(f"col={int(f.location.column)}")
    title = f"{f.code} {clean_text(f.name)}".strip()
    props.append("title=" + escape_property(title))
    lines = [clean_text(f.message) or f.code]
    where = describe(f, totals)
    if where:
        lines[0] += f" [{clean_text(where)}]"
    lines += [f"via macro call at {clean_text(str(v), 4096)}" for v in f.location.via]
    lines += [f"see also {clean_text(str(r), 4096)}" for r in f.related]
    lines += [f"also at {clean_text(str(a.location), 4096)}" for a in f.also]
    return f"::{COMMANDS[f.severity]} {','.join(props)}::{escape_data(defuse(chr(10).join(lines)))}"


def render(result, **_) -> str:
    from urdfcheck.finish.collapse import variant_totals
    from urdfcheck.report import gate_words

    totals = variant_totals(result.targets, result.root)
    out = [command(f, totals) for f in result.findings]
    n = len(result.findings)
    m = len(result.targets)
    words = gate_words(result, getattr(result, "fail_on", Severity.WARNING))
    gated = f"; {words[1]}" + (f", {words[2]}" if words[2] else "") if words is not None else ""  # --diff-base
    out.append(f"urdfcheck: {n} finding{'s' if n != 1 else ''} in {m} model{'s' if m != 1 else ''}{defuse(gated)}")
    return "\n".join(out) + "\n"
