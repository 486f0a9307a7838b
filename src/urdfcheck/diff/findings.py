"""What a change does to lint's findings: new, fixed and unchanged against a git revision (`lint --diff-base REV`).

The base revision's files are written by the git door (core.git) into a private temporary folder outside the
user's tree, linted there with the same flags as the working tree (from the matching folder, so every path and
message reads as it does in the working tree), and removed. A finding is matched by its code, its file relative
to the repository, its message with line numbers taken out and the text of the line it points at; then, for
what is left, without that text (the element's line was edited, the finding was not). So a finding that only
moved lines is unchanged; a third identical finding where the base had two is new.

A base finding that is gone because every model it was found in no longer loads is not fixed: it was not looked
for. It is counted apart (`not_checked`), and the load failure is among the new findings.
"""
from __future__ import annotations

import os

from urdfcheck.core import lazyre
from urdfcheck.core.findings import Finding, clean_text
from urdfcheck.core.records import Record


class FindingsDiff(Record):
    """rev: the base revision as typed. new: findings of the working tree the base did not have (Finding).
    fixed: findings of the base the working tree no longer has (dicts: code, severity, file, line, message).
    unchanged: how many are in both. notes: files of the revision that were not read, and why.
    not_checked: findings of the base (dicts, as `fixed`) whose models all fail to load in the working tree."""

    _fields = ('rev', 'new', 'fixed', 'unchanged', 'notes', 'not_checked')

    def __init__(self, rev: str, new: list, fixed: list, unchanged: int, notes=(), not_checked=()):
        self.rev, self.new, self.fixed, self.unchanged, self.notes = rev, new, fixed, unchanged, list(notes)
        self.not_checked = list(not_checked)

    def as_dict(self) -> dict:
        return {"base": clean_text(self.rev), "new": [_summary(f) for f in self.new], "fixed": list(self.fixed),
                "unchanged": self.unchanged, "not_checked": list(self.not_checked),
                "notes": [clean_text(n, 4096) for n in self.notes]}

    def tally(self) -> str:
        gone = f", {len(self.not_checked)} not checked (the model no longer loads)" if self.not_checked else ""
        return (f"against {clean_text(self.rev)}: {len(self.new)} new, {len(self.fixed)} fixed, "
                f"{self.unchanged} unchanged{gone}")

    def text_lines(self) -> list[str]:
        out = ["", self.tally()]
        out += [f"  note: {clean_text(n, 4096)}" for n in self.notes]
        out += [f"  NEW   {_line(_summary(f))}" for f in self.new]
        out += [f"  fixed {_line(x)}" for x in self.fixed]
        out += [f"  not checked {_line(x)}" for x in self.not_checked]
        return out

    def markdown_lines(self) -> list[str]:
        out = [f"### Findings {_md(self.tally())}", ""]
        if self.new:
            out += ["**New in this change:**", ""]
            out += [f"- :new: `{_code(x['code'])}` {_md(x['severity'])} at `{_code(_where(x))}`: {_md(x['message'])}"
                    for x in map(_summary, self.new)]
            out.append("")
        if self.fixed:
            out += ["**Fixed by this change:**", ""]
            out += [f"- `{_code(x['code'])}` at `{_code(_where(x))}`: {_md(x['message'])}" for x in self.fixed]
            out.append("")
        if self.not_checked:
            out += ["**Not checked in this change** (the model no longer loads; not fixed):", ""]
            out += [f"- `{_code(x['code'])}` at `{_code(_where(x))}`: {_md(x['message'])}" for x in self.not_checked]
            out.append("")
        out += [f"- note: {_md(n)}" for n in self.notes]
        return out


def _summary(f: Finding) -> dict:
    loc = f.location
    return {"code": f.code, "severity": str(f.severity), "file": clean_text(str(loc.file), 4096),
            "line": loc.line, "message": clean_text(f.message)}


def _where(x: dict) -> str:
    return x["file"] + (f":{x['line']}" if x.get("line") else "")


def _line(x: dict) -> str:
    return _clean(f"{_where(x)}: {x['severity']} {x['code']} {x['message']}", 4096)


_BIDI = lazyre.compile("[\u061c\u200e\u200f\u202a-\u202e\u2066-\u2069]")
_MD_SPECIAL = lazyre.compile(r"([\\`*_\[\]|~#!$])")


def _clean(s, limit: int = 500) -> str:
    return _BIDI.sub("", clean_text(s, limit))


def _code(s) -> str:
    """Text for inside a code span (where nothing is interpreted but the closing backtick)."""
    return _clean(str(s), 4096).replace("`", "'")


def _md(s) -> str:
    """Text from the checkout as inert Markdown (no HTML, links, emphasis or @mentions), as report.markdown does."""
    s = _clean(str(s), 4096)
    s = s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")
    return _MD_SPECIAL.sub(r"\\\1", s).replace("@", "@\u200b")


def key(f: Finding, root: str) -> tuple[str, str, str, str]:
    """(code, file relative to `root`, message without line numbers, hash of the line's text). Called while the
    finding's files can still be read (the base's temporary folder exists, the working directory is the one the
    run had)."""
    from urdfcheck.finish import baseline

    message = _mesh_named(f.message) if f.code == "G001" else f.message
    return (f.code, baseline.portable_path(str(f.location.file), root), baseline.normalise_message(message),
            baseline.context(f))


_MESH = lazyre.compile(r"^mesh '([^']+)'")


def _mesh_named(message: str) -> str:
    """G001 quotes the mesh as the model writes it, an absolute `file://` path shown relative to the working
    directory: one missing mesh written `package://ur_description/m.dae` in the base and
    `file://$(find ur_description)/m.dae` in the change is the same finding. Named as diff compares meshes."""
    m = _MESH.match(message)
    if m is None:
        return message
    uri = m.group(1)
    if "://" in uri and not uri.startswith("file://"):
        return message
    from urdfcheck.diff.compare import mesh_name

    path = uri[len("file://"):] if uri.startswith("file://") else uri
    return f"mesh {mesh_name(os.path.abspath(path), None)!r}" + message[m.end():]


def also_keys(f: Finding, root: str) -> tuple:
    """The loose keys (code, file, message) of the other lines a finding stands for (its `also`: the same problem
    written again in the same file, one line in the reports). A change that adds such a line adds a problem even
    though the finding's first line is unchanged."""
    return tuple(sorted({key(f._replace(location=a.location, message=a.message, also=()), root)[:3]
                         for a in f.also}))


def places(f: Finding, root: str) -> tuple[tuple[str, str], ...]:
    """The (model relative to `root`, variant) pairs a finding was found in."""
    from urdfcheck.finish import baseline

    return tuple((baseline.portable_path(p.model, root), p.variant) for p in f.places() if p.model)


def unloaded(result, root: str) -> set[tuple[str, str]]:
    """(model relative to `root`, variant) of each target of a run (run.Result) whose model did not load."""
    from urdfcheck.finish import baseline

    return {(baseline.portable_path(str(t.path), root), t.variant) for t in result.unchecked()}


def classify(rev: str, base: list[tuple[tuple, dict]], findings: list[Finding], root: str, notes=(),
             unchecked=frozenset()) -> FindingsDiff:
    """`base`: (key, summary) of each base finding, the summary's "_places" its `places`; `findings`: the working
    tree's, keyed against `root`; `unchecked`: `unloaded` of the working tree's run."""
    from urdfcheck.finish import baseline

    baseline._LINES_CACHE.clear()
    keys = [key(f, root) for f in findings]
    exact: dict[tuple, list[int]] = {}
    loose: dict[tuple, list[int]] = {}
    for j, (k, _) in enumerate(base):
        exact.setdefault(k, []).append(j)
        loose.setdefault(k[:3], []).append(j)
    taken = [False] * len(base)
    matched = [False] * len(findings)
    grew = [False] * len(findings)

    def take(i: int, j: int) -> None:
        taken[j] = matched[i] = True
        before = {tuple(x) for x in base[j][1].get("_also") or ()} | {base[j][0][:3]}
        grew[i] = any(a not in before for a in also_keys(findings[i], root))

    for i, k in enumerate(keys):  # the same text at the same place
        free = [j for j in exact.get(k, ()) if not taken[j]]
        if free:
            take(i, free[0])
    for i, k in enumerate(keys):  # the line it points at was edited, the finding was not
        if matched[i]:
            continue
        free = [j for j in loose.get(k[:3], ()) if not taken[j]]
        if free:
            take(i, free[0])
    matched = [m and not g for m, g in zip(matched, grew)]  # one more line of the same problem: new
    fixed, gone = [], []
    for (_, summary), t in zip(base, taken):
        where = summary.get("_places") or ()
        summary = {k: v for k, v in summary.items() if k not in ("_places", "_also")}
        if not t:
            (gone if where and all(tuple(w) in unchecked for w in where) else fixed).append(summary)
    new = [f for f, m in zip(findings, matched) if not m]
    return FindingsDiff(rev, new, fixed, sum(matched), notes, gone)


def base_findings(rev: str, paths: list[str], make_request, *, start: str | None = None):
    """Lint `rev`'s version of `paths`: (root of the repository, [(key, summary)], notes).

    `make_request(paths, map_root, in_tree) -> LintRequest`: the working tree's flags with these paths (and
    --root, through `map_root`) in the revision's tree; `in_tree(path)`: the revision's copy of a working-tree
    file (absolute; None when it has none or the path lies outside the repository). Raises core.git.GitError
    when there is no repository or no such revision."""
    from urdfcheck import run as pipeline
    from urdfcheck.core import git
    from urdfcheck.request.request import UsageError

    start = start or (paths[0] if paths else ".")
    repo = git.find(os.path.abspath(start))
    if repo is None:
        raise git.GitError("no git repository (a .git folder) around " + git.shown_name(os.fsencode(start)))
    wt = repo.work_tree

    def inside(p: str) -> str | None:
        real = os.path.realpath(os.path.abspath(p))
        rel = os.path.relpath(real, wt)
        return None if rel == ".." or rel.startswith(".." + os.sep) else rel

    from urdfcheck.core import door

    with git.export(repo, rev) as tree:
        door.add_root(tree.root)  # a run guarded already (the command line's): the base's files are readable too
        here = os.getcwd()
        rel_here = inside(here)
        base_here = os.path.join(tree.root, rel_here) if rel_here is not None else tree.root
        os.makedirs(base_here, exist_ok=True)
        mapped = []
        for p in paths or ["."]:
            rel = inside(p)
            if rel is None:
                mapped.append(os.path.abspath(p))  # outside the repository: the runner's file, the same one
            elif os.path.exists(os.path.join(tree.root, rel)):  # absolute: a worker forked earlier has another cwd
                mapped.append(os.path.join(tree.root, rel))
        if not mapped:  # the paths are new in this change: every finding is new
            return wt, [], tree.notes
        os.chdir(base_here)  # paths and messages read as in the working tree
        try:
            try:
                result = pipeline.run(make_request(mapped, lambda r: _map_root(r, inside, tree.root, base_here),
                                                   lambda p: _in_tree(p, inside, tree.root)))
            except UsageError as e:
                if "no URDF or xacro model found" in str(e):
                    return wt, [], tree.notes
                raise
            from urdfcheck.finish import baseline

            baseline._LINES_CACHE.clear()
            shown_wt = os.path.relpath(wt, here)
            out = [(key(f, tree.root), {**_scrubbed(_summary(f), tree.root, shown_wt),
                                        "_places": places(f, tree.root), "_also": also_keys(f, tree.root)})
                   for f in result.findings]
        finally:
            os.chdir(here)
        return wt, out, tree.notes


def _scrubbed(summary: dict, tree_root: str, shown_wt: str) -> dict:
    """A base finding as the working tree would name it: never the temporary folder."""
    for field in ("file", "message"):
        text = summary[field]
        for r in dict.fromkeys((os.path.realpath(tree_root), tree_root)):
            text = text.replace(r, shown_wt)
        summary[field] = os.path.normpath(text) if field == "file" and text else text
    return summary


def _in_tree(p: str, inside, tree_root: str) -> str | None:
    rel = inside(p)
    if rel is None:
        return None
    full = os.path.join(tree_root, rel)
    return full if os.path.exists(full) else None


def _map_root(root, inside, tree_root: str, base_here: str):
    if not root:
        return root
    rel = inside(root)
    return os.path.relpath(os.path.join(tree_root, rel), base_here) if rel is not None else os.path.abspath(root)
