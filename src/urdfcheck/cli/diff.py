"""`urdfcheck diff OLD NEW` and `urdfcheck diff --git REV [PATH...]`: flags -> `diff.compare` -> report.

Exit 0 (whatever changed) unless `--fail-on-change`: then 1 when anything changed. A side that does not load
is reported and exits 1 (nothing was compared); an unusable invocation exits 2.
"""
from __future__ import annotations

import os
import sys

from urdfcheck.cli.common import EXIT_CLEAN, EXIT_FINDINGS, UsageError
from urdfcheck.cli.parsing import add_options


def add_parser(sub) -> None:
    from urdfcheck.report.diff import FORMATS

    p = sub.add_parser(
        "diff", help="what a change does to the robot (frames moved, joints, limits, inertia, contracts)",
        description="Compare the robots two trees describe (every model, deployment and variant that `lint` "
        "plans), or the working tree with a git revision (--git REV: the old files are read with git, "
        "nothing is checked out). Comments and formatting are no change.")
    p.add_argument("paths", nargs="*", metavar="PATH",
                   help="OLD NEW (two files or folders); with --git: the paths to compare (default .)")
    p.add_argument("--git", metavar="REV", help="compare the working tree with this revision (e.g. HEAD, origin/main)")
    p.add_argument("--format", choices=FORMATS, default="text")
    p.add_argument("--output", "-o", metavar="FILE", help="write the report to FILE instead of stdout")
    p.add_argument("--fail-on-change", action="store_true", help="exit 1 when anything changed (frozen descriptions)")
    p.add_argument("--findings", action="store_true",
                   help="with --git: also lint both sides and tell the findings the change adds and fixes (as "
                   "`lint --diff-base REV`; informational: the exit code stays diff's)")
    p.add_argument("--seeds", type=int, default=5, metavar="N",
                   help="random joint configurations besides zero at which frame poses are compared (default 5)")
    add_options(p, "diff")
    p.set_defaults(func=cmd_diff)


def _options(ns) -> dict:
    from urdfcheck.cli.options import request_fields

    return request_fields(ns, "diff")


def cmd_diff(ns) -> int:
    from urdfcheck.diff import compare as stage

    if ns.seeds < 0 or ns.seeds > 100:
        raise UsageError("--seeds must be between 0 and 100")
    for p in ns.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or folder: {p}")
    if ns.git is None:
        if len(ns.paths) != 2:
            raise UsageError("give OLD and NEW (two files or folders), or --git REV")
        old, new = ns.paths
        result = stage.diff([old], [new], _root(old), _root(new), seeds=ns.seeds, old_label=_label(old),
                            new_label=_label(new), **_options(ns))
    else:
        from urdfcheck.core import git

        paths = ns.paths or ["."]
        with revision(ns.git, paths[0], "--git") as (repo, tree):
            rel = [os.path.relpath(os.path.realpath(p), repo.work_tree) for p in paths]
            if any(r == ".." or r.startswith(".." + os.sep) for r in rel):
                raise UsageError("--git: every path must be inside the repository")
            old = [o for o in (os.path.join(tree.root, r) for r in rel) if os.path.exists(o)]  # else: all added
            try:
                result = stage.diff(old, [os.path.realpath(p) for p in paths], tree.root, repo.work_tree,
                                    seeds=ns.seeds, old_label=git.shown_name(ns.git.encode()),
                                    new_label="working tree", **_options(ns))
            except git.GitError as e:
                raise UsageError(f"--git: {e}") from None
            result.notes[:0] = tree.notes
        if ns.findings:
            result.findings = _findings(ns, paths)
    from urdfcheck.report.diff import render

    text = render(ns.format, result)
    if ns.output:
        try:
            with open(ns.output, "w", encoding="utf-8") as f:
                f.write(text)
        except OSError as e:
            raise UsageError(f"cannot write {ns.output}: {e.strerror}") from None
    else:
        sys.stdout.write(text)
    if any(p.status == "unloadable" for p in result.pairs):
        return EXIT_FINDINGS
    return EXIT_FINDINGS if ns.fail_on_change and result.changed else EXIT_CLEAN


def _findings(ns, paths):
    """What the change does to lint's findings: the revision and the working tree linted with diff's options."""
    from urdfcheck import run as pipeline
    from urdfcheck.core.git import GitError
    from urdfcheck.diff import findings as changes
    from urdfcheck.request.request import make_request

    def options(in_tree=None):
        opts = _options(ns)
        if opts.get("config"):
            opts["config"] = (in_tree and in_tree(opts["config"])) or os.path.abspath(opts["config"])
        return opts

    def make(base_paths, map_root, in_tree):
        return make_request(base_paths, **options(in_tree))

    try:
        root, base, _ = changes.base_findings(ns.git, paths, make)
    except GitError as e:
        raise UsageError(f"--git: {e}") from None
    result = pipeline.run(make_request(paths, **options()))
    # its notes: already the diff's
    return changes.classify(ns.git, base, result.findings, root, (), changes.unloaded(result, root))


def _label(path: str) -> str:
    """A side as the report names it: the path as typed, relative when it lies below the working directory."""
    from urdfcheck.core import git

    p = os.path.abspath(path)
    rel = os.path.relpath(p)
    return git.shown_name(os.fsencode(rel if not rel.startswith("..") else os.path.basename(p) or p))


class revision:
    """`with revision(REV, PATH, flag) as (repo, tree)`: the repository around PATH (found by urdfcheck, never
    by git) and REV's files in a private temporary folder, removed on leaving. UsageError when either fails."""

    def __init__(self, rev: str, path: str, flag: str):
        self.rev, self.path, self.flag = rev, path, flag
        self.tree = None

    def __enter__(self):
        from urdfcheck.core import git

        start = os.path.abspath(self.path)
        repo = git.find(start)
        if repo is None:
            raise UsageError(f"{self.flag}: no git repository (a .git folder) around {_label(self.path)}")
        try:
            self.tree = git.export(repo, self.rev)
        except git.GitError as e:
            raise UsageError(f"{self.flag}: {e}") from None
        from urdfcheck.core import door

        door.add_root(self.tree.root)  # in a guarded run, the revision's files are readable like the checkout's
        return repo, self.tree

    def __exit__(self, *exc) -> None:
        if self.tree is not None:
            self.tree.cleanup()


def _root(path: str) -> str:
    return os.path.abspath(path) if os.path.isdir(path) else os.path.dirname(os.path.abspath(path))
