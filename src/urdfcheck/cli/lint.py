"""`urdfcheck lint` (and both pre-commit hooks): parsed flags -> `LintRequest` -> `run` -> reports -> exit code.

The flags become request fields here and nowhere else; a flag not given is None, so the config decides.
"""
from __future__ import annotations

import os
import sys

from urdfcheck.request.request import LintRequest, UsageError, make_request

# parsed documents and the result (its models) a one-shot process keeps until it exits (run.lint_targets: `retain`)
_UNTIL_EXIT: list = []


def request_from_flags(ns) -> LintRequest:
    from urdfcheck.cli.options import request_fields

    fields = request_fields(ns, "lint")
    if getattr(ns, "write_baseline", None):  # the baseline being written is not read
        fields["baseline"] = None
    return make_request(ns.paths, **fields)


def run(ns, usage_error=UsageError) -> int:
    """`usage_error`: raised (with the message) for an unusable invocation; UsageError by default."""
    from urdfcheck.core import door

    # every read of the run goes through the door, confined to the checkout, the packages and what is typed
    with door.guarding((*ns.paths, ns.config, ns.baseline, *(getattr(ns, "bags", None) or ()))):
        return _with_config_from(ns, usage_error)


def _with_config_from(ns, usage_error) -> int:
    rev = getattr(ns, "config_from", None)
    if not rev:
        return _run(ns, usage_error)
    from urdfcheck.core.findings import clean_text

    if ns.config or ns.no_config:  # both typed by the runner (an Action's default and a workflow's own flag)
        what = "--config FILE" if ns.config else "--no-config"
        print(f"urdfcheck: info: --config-from {clean_text(rev)} is not used: {what} is given", file=sys.stderr)
        return _run(ns, usage_error)
    from urdfcheck.core.git import GitError
    from urdfcheck.diff import basecfg

    try:
        base = basecfg.load(rev, ns.paths[0] if ns.paths else ".")
    except GitError as e:
        raise usage_error(f"--config-from: {e}") from None
    with base:
        print(f"urdfcheck: info: {clean_text(base.info, 4096)}", file=sys.stderr)
        if base.path is None:
            ns.no_config = True
        else:
            ns.config, ns.trust_config = base.path, True
            ns.config_from_tree = base.for_tree
        ns.scrub = lambda text: base.scrub(text, getattr(ns, "root", None))
        try:
            return _run(ns, usage_error)
        except UsageError as e:
            raise usage_error(base.scrub(str(e))) from None


def _run(ns, usage_error) -> int:
    from urdfcheck import run as pipeline

    try:
        request = request_from_flags(ns)
        if getattr(ns, "list", False):
            return _list(request)
        from urdfcheck.core import progress

        progress.to_terminal(None if getattr(ns, "quiet", False) else sys.stderr)
        try:
            against = _diff_base(ns, usage_error) if getattr(ns, "diff_base", None) and not ns.write_baseline \
                else None
            retain = _UNTIL_EXIT if getattr(ns, "one_shot", False) else None
            result = pipeline.run(request, retain=retain)
            if retain is not None:  # its models too: freeing 10,000 links' objects one by one costs ~45 ms
                retain.append(result)
            if against is not None:
                from urdfcheck.diff import findings as changes

                root, base, notes = against
                result.changes = changes.classify(ns.diff_base, base, result.findings, root, notes,
                                                  changes.unloaded(result, root))
        finally:
            progress.close()
    except UsageError as e:
        if usage_error is UsageError:
            raise
        raise usage_error(str(e)) from None

    if ns.write_baseline:
        from urdfcheck.finish import baseline

        baseline.write(ns.write_baseline, result.raw())
        print(f"wrote {len(result.raw())} findings to {ns.write_baseline}", file=sys.stderr)
        return 0

    from urdfcheck.core.findings import clean_text, escape_bidi
    from urdfcheck.report import render

    for line in getattr(result, "infos", ()):  # on stderr: the report formats stay as they are
        print(f"urdfcheck: info: {escape_bidi(clean_text(line, 4096))}", file=sys.stderr)

    colour = ns.color == "always" or (ns.color == "auto" and ns.output is None and sys.stdout.isatty()
                                      and not os.environ.get("NO_COLOR"))
    scrub = getattr(ns, "scrub", None) or (lambda t: t)  # --config-from: its temporary file is REV:path
    text = scrub(_with_changes(ns.format, render(ns.format, result, colour=colour, fail_on=result.fail_on), result))
    if ns.output:
        _write(ns.output, text, usage_error)
    else:
        sys.stdout.write(text)
    for fmt, path in ns.report:
        try:
            extra = scrub(_with_changes(fmt, render(fmt, result, colour=False, fail_on=result.fail_on), result))
        except ValueError as e:
            raise usage_error(str(e)) from None
        _write(path, extra, usage_error)
    return 1 if result.failed() else 0  # with --diff-base: the new findings only (Result.gate)


def _diff_base(ns, usage_error):
    """(repository root, the base revision's findings, notes): `--diff-base REV` linted with the same flags."""
    import argparse

    from urdfcheck.core.git import GitError
    from urdfcheck.diff import findings as changes

    def make(paths, map_root, in_tree):
        base = argparse.Namespace(**vars(ns))
        base.paths, base.root = paths, map_root(getattr(ns, "root", None))
        if getattr(ns, "config_from_tree", None) is not None:  # --config-from: its paths in the base tree
            base.config = ns.config_from_tree(in_tree)
        elif ns.config:  # a config of the repository: the base's own copy of it; else the runner's file
            base.config = in_tree(ns.config) or os.path.abspath(ns.config)
        base.baseline = base.write_baseline = None
        base.bags = [os.path.abspath(b) for b in getattr(ns, "bags", None) or ()]
        return request_from_flags(base)

    try:
        return changes.base_findings(ns.diff_base, ns.paths, make)
    except GitError as e:
        raise usage_error(f"--diff-base: {e}") from None


def _with_changes(fmt: str, text: str, result) -> str:
    """The report with what the change does to the findings (--diff-base): a section in text and Markdown, a
    `diff_base` member in JSON; the other formats are left as they are."""
    changes = getattr(result, "changes", None)
    if changes is None:
        return text
    if fmt == "text":
        return text + "\n".join(changes.text_lines()) + "\n"
    if fmt == "markdown":
        return text.rstrip("\n") + "\n\n" + "\n".join(changes.markdown_lines()) + "\n"
    if fmt == "json":
        import json

        from urdfcheck.report import gate

        data = json.loads(text)
        data["diff_base"] = changes.as_dict()
        gating, quiet = gate(result)  # what the exit code judged (each model's config level), as the headlines say
        data["diff_base"]["gate"] = {"fail_on": str(result.fail_on), "gating": len(gating), "not_gating": len(quiet)}
        return json.dumps(data, indent=2, sort_keys=True) + "\n"
    return text


def _list(request: LintRequest) -> int:
    """`--list`: the plan, one line per target, then the deployments. Paths below the working directory
    (or --root) are relative, arguments' values included. A target from a launch file shows the xacro
    arguments that tell it apart, files aside (the deployment below lists them; arguments equal to a launch
    argument's default are only counted)."""
    from urdfcheck.core.paths import showing

    with showing(request.root):
        return _list_plan(request)


def _list_plan(request: LintRequest) -> int:
    from urdfcheck.core.findings import clean_text, escape_bidi
    from urdfcheck.core.paths import shown
    from urdfcheck.plan.deployments import describe, show_args
    from urdfcheck.plan.plan import plan

    targets = plan(request)
    if not targets and not targets.infos:
        raise UsageError(f"no URDF or xacro model found in {', '.join(request.paths or ['.'])}")

    def out(text: str) -> None:
        print(escape_bidi(clean_text(text, 4096)))

    for line in targets.infos:
        out(f"info: {line}")
    for t in targets:
        d = t.deployment
        if d is not None:  # the launch file's choices (files: in the deployment below), what the request adds
            args = show_args({**d.chosen_args(), **dict(request.args)}, shown,
                             len({**d.args, **dict(request.args)}), files=False)
        else:
            args = show_args(t.args, shown)
        cfg = getattr(t.settings.config, "path", None) if t.settings is not None else None
        out(shown(t.path) + (f" [{t.variant}]" if t.variant else "") + args
            + (f"  (config {shown(cfg)})" if cfg else ""))
    from urdfcheck.rules.checks.values import describe_target

    assumed = (describe_target(str(t.path), t.settings.target if t.settings is not None else None) for t in targets)
    for name, why in dict.fromkeys(assumed):
        out(f"ROS distribution: {name} ({why})")
    deployments = list({id(t.deployment): t.deployment for t in targets if t.deployment is not None}.values())
    deployments += getattr(targets, "not_understood", [])
    if deployments:
        print()
        for line in describe(deployments, shown).splitlines():
            out(line)
    print(f"{len(targets)} target(s)")
    return 0


def _write(path: str, text: str, usage_error) -> None:
    try:
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
    except OSError as e:
        raise usage_error(f"cannot write {path}: {e.strerror}") from None
