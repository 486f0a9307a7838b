"""Human text: grouped by file, `file:line:col  CODE  message`, colour on a terminal, one summary line."""
from __future__ import annotations

from urdfcheck.core.findings import Severity, clean_text

_COLOURS = {Severity.ERROR: "\x1b[31m", Severity.WARNING: "\x1b[33m", Severity.INFO: "\x1b[36m"}
_BOLD, _DIM, _RESET = "\x1b[1m", "\x1b[2m", "\x1b[0m"


def _short(loc) -> str:
    """`file:line` by the file's name (the full path is in the finding's own line or the JSON)."""
    name = clean_text(loc.file).rsplit("/", 1)[-1]
    return f"{name}:{loc.line}" if loc.line else name


def render(result, colour: bool = False, **_) -> str:
    def c(code, text):
        return f"{code}{text}{_RESET}" if colour else text

    if result.findings:  # (a clean run does not need the collapse helpers: start-up time)
        from urdfcheck.finish.collapse import chains, describe, variant_totals

        totals = variant_totals(result.targets, result.root)
    lines = []
    current = None
    for f in result.findings:
        loc = f.location
        if loc.file != current:
            if current is not None:
                lines.append("")
            lines.append(c(_BOLD, clean_text(loc.file)))
            current = loc.file
        where = clean_text(str(loc))
        tag = f"{f.code}"
        where_ = describe(f, totals)
        extra = f" [{clean_text(where_)}]" if where_ else ""
        # one line per problem: the macro call chains and related places go at its end, by file name (JSON and
        # SARIF carry the full paths); the calls of one model's instances are listed ("via a:55; a:56"), the
        # chains of other models and variants are not (too many to be useful on one line)
        tail = ""
        paths = chains(f)
        if paths:
            shown = [" < ".join(_short(v) for v in chain) for chain in paths[:3]]
            more = f"; {len(paths) - 3} more" if len(paths) > 3 else ""
            tail += "  (via " + "; ".join(shown) + more + ")"
        related = list(dict.fromkeys(_short(r) for r in f.related if (r.file, r.line) != (loc.file, loc.line)))
        if related:  # by file name and line: two uses through different macro calls are one place here
            tail += "  (see also " + ", ".join(related) + ")"
        lines.append(f"{where}  {c(_COLOURS[f.severity], tag)}  {c(_DIM, str(f.severity))}  "
                     f"{clean_text(f.message)}{extra}{c(_DIM, tail)}")
    counts = {s: sum(1 for f in result.findings if f.severity == s) for s in Severity}
    n_models = len(result.targets)
    # how many of them come from launch files (issue 13: zero config lints a deployed model through them)
    n_dep = len({id(d) for t in result.targets if (d := getattr(t, "deployment", None)) is not None})
    deployed = f" ({n_dep} from launch-file deployment{'s' if n_dep != 1 else ''})" if n_dep else ""
    why_not = getattr(result, "not_passed", lambda: None)()  # no robot, or a model that did not load
    if result.findings:
        lines.append("")
        parts = [f"{counts[s]} {s}{'s' if counts[s] != 1 else ''}" for s in (Severity.ERROR, Severity.WARNING,
                                                                           Severity.INFO) if counts[s]]
        lines.append(f"Found {len(result.findings)} finding{'s' if len(result.findings) != 1 else ''} "
                     f"({', '.join(parts)}) in {n_models} model{'s' if n_models != 1 else ''}{deployed}.")
        from urdfcheck.report import gate, gate_words

        level = getattr(result, "fail_on", Severity.WARNING)
        words = gate_words(result, level)
        if words is not None:  # --diff-base: the exit code judges the new findings only
            _, gating, rest = words
            lines.append(f"Gate: {gating}" + (f"; {rest}" if rest else "") + ".")
        if why_not:
            lines.append(f"Not a pass: {why_not}.")
        failing = gate(result, level)[0]
        if failing and all(f.code == "G001" for f in failing):
            # the model itself passed: only the mesh files it names are absent (a checkout without its meshes, Git
            # LFS not pulled, a package of meshes outside the checkout)
            lines.append("Only missing meshes fail this run (G001): fetch the mesh files (`git lfs pull`, "
                         "submodules) or lint where the package that ships them is (--package NAME=PATH).")
    elif why_not:
        lines.append(f"Nothing checked: {why_not}, no findings.")
    elif getattr(result, "baselined", 0):  # the baseline is a file too: what it hides is said (issue 36)
        hidden = result.baselined
        lines.append(f"No new findings: {n_models} model{'s' if n_models != 1 else ''}{deployed}; {hidden} "
                     f"finding{'s' if hidden != 1 else ''} hidden by the baseline (--baseline).")
    else:
        lines.append(f"All checks passed: {n_models} model{'s' if n_models != 1 else ''}{deployed}, no findings.")
    if result.findings and getattr(result, "baselined", 0):
        lines.append(f"{result.baselined} more hidden by the baseline (--baseline).")
    return "\n".join(lines) + "\n"
