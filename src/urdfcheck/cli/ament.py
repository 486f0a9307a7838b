"""`ament_urdfcheck`: urdfcheck with the command line of the ament_lint linters (ament_xmllint, ament_flake8), for
`colcon test` through `ament_cmake_urdfcheck` (an ament_lint_auto extension) or a test of your own.

    ament_urdfcheck [PATH...] [--exclude NAME...] [--xunit-file FILE] [--fail-on LEVEL]

PATH: files or folders (default: the working directory, the package); lints them as `urdfcheck lint` does.
`--exclude` names files or folders (by name, like ament_lint) to leave out: then the *.urdf and *.xacro files
of the paths that are not excluded are named one by one (a macro file stands for the robots that include it).
`--xunit-file`: the JUnit file `colcon test-result` reads (its folder is created). Exit 1 on findings at or
above --fail-on (default: the config's, else warning), 2 on an unusable invocation.
"""
from __future__ import annotations

import argparse
import os
import sys

from urdfcheck.cli.common import EXIT_CLEAN, EXIT_FINDINGS, EXIT_USAGE
from urdfcheck.cli.parsing import add_options
from urdfcheck.request.request import LintRequest, UsageError, make_request

SUFFIXES = (".urdf", ".xacro")


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="ament_urdfcheck",
                                description="Check URDF and xacro robot descriptions with urdfcheck (ament_lint "
                                "conventions: paths, --exclude, --xunit-file).")
    p.add_argument("paths", nargs="*", default=[os.curdir], metavar="PATH",
                   help="files or folders to check (default: the working directory)")
    p.add_argument("--exclude", nargs="*", default=[], metavar="NAME",
                   help="file or folder names to leave out")
    p.add_argument("--xunit-file", metavar="FILE", help="write a JUnit (xunit) file for colcon test-result")
    add_options(p, "ament")  # --fail-on, --config, --arg, --package: lint's, from the one table (cli/options.py)
    return p


def model_files(paths, exclude) -> list[str]:
    """The *.urdf / *.xacro files below `paths`, as ament_lint's get_files walks (no hidden or _ folders,
    AMENT_IGNORE respected, `exclude` by name)."""
    out = []
    for path in paths:
        if os.path.isfile(path):
            if os.path.basename(path) not in exclude:
                out.append(path)
            continue
        for here, dirs, files in os.walk(path):
            if "AMENT_IGNORE" in dirs + files:
                dirs[:] = []
                continue
            dirs[:] = sorted(d for d in dirs if d[0] not in "._" and d not in exclude)
            out.extend(os.path.join(here, f) for f in sorted(files) if f.endswith(SUFFIXES) and f not in exclude)
    return [os.path.normpath(f) for f in out]


def test_name(xunit_file: str) -> str:
    """ament_lint's suite name: '<folder>.<file without .xunit.xml>' (e.g. 'my_robot_description.urdfcheck')."""
    folder = os.path.basename(os.path.dirname(os.path.abspath(xunit_file)))
    name = os.path.basename(xunit_file)
    for suffix in (".xml", ".xunit"):
        if name.endswith(suffix):
            name = name[:-len(suffix)]
    return f"{folder}.{name}"


def main(argv=None) -> int:
    ns = parser().parse_args(argv)
    try:
        return _main(ns)
    except UsageError as e:
        print(f"ament_urdfcheck: error: {e}", file=sys.stderr)
        return EXIT_USAGE


def request_from_flags(ns, paths) -> LintRequest:
    from urdfcheck.cli.options import request_fields

    return make_request(paths, **request_fields(ns, "ament"))


def _main(ns) -> int:
    from urdfcheck import run as pipeline
    from urdfcheck.report import escape_bidi, render

    paths = list(ns.paths)
    if ns.exclude:
        missing = [p for p in paths if not os.path.exists(p)]
        if missing:
            raise UsageError(f"no such file or folder: {', '.join(missing)}")
        paths = model_files(paths, set(ns.exclude))
        if not paths:
            print("No files found", file=sys.stderr)
            return EXIT_FINDINGS
    request = request_from_flags(ns, paths)
    result = pipeline.run(request)
    for line in getattr(result, "infos", ()):
        print(f"urdfcheck: info: {line}", file=sys.stderr)
    sys.stdout.write(render("text", result, colour=False, fail_on=result.fail_on))
    if ns.xunit_file:
        import xml.etree.ElementTree as ET

        from urdfcheck.report.junit import as_tree

        root = as_tree(result, result.fail_on)
        root.set("name", test_name(ns.xunit_file))
        ET.indent(root)
        text = '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"
        try:
            os.makedirs(os.path.dirname(os.path.abspath(ns.xunit_file)), exist_ok=True)
            with open(ns.xunit_file, "w", encoding="utf-8") as f:
                f.write(escape_bidi(text))
        except OSError as e:
            raise UsageError(f"cannot write {ns.xunit_file}: {e.strerror}") from None
    return EXIT_FINDINGS if result.failed() else EXIT_CLEAN


def run() -> None:
    """The console entry point."""
    sys.exit(main())


if __name__ == "__main__":  # pragma: no cover
    run()
