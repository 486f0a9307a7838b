"""A plain `urdfcheck lint [FLAG...] [PATH...]` is read without argparse (cli.options.plain_lint): the namespace
must be argparse's, word for word, and anything else must go to argparse."""
from __future__ import annotations

import itertools
import subprocess
import sys

import pytest

from urdfcheck.cli.main import _plain_lint, build_parser
from urdfcheck.cli.options import plain_flags


def _argparse(argv):
    return vars(build_parser(with_publish=False, lint_only=True).parse_args(argv))


FLAGS = sorted(plain_flags())
CASES = [["lint"], ["lint", "."], ["lint", "a.urdf", "b/"], ["lint", "--quiet", "."], ["lint", ".", "-q"],
         ["lint", "--no-cache", "--trusted", "pkg", "--trust-config"], ["lint", "--list"], ["lint", "-q", "-q", "x"]]
CASES += [["lint", f, "."] for f in FLAGS] + [["lint", ".", f, g] for f, g in itertools.combinations(FLAGS, 2)]


@pytest.mark.parametrize("argv", CASES, ids=" ".join)
def test_a_plain_command_line_reads_as_argparse_reads_it(argv):
    ours = _plain_lint(argv)
    assert ours is not None
    assert vars(ours) == _argparse(argv)


@pytest.mark.parametrize("argv", [
    ["lint", "--format", "json", "."], ["lint", "--format=json"], ["lint", "--arg", "a:=1", "x.xacro"],
    ["lint", "--qui", "."], ["lint", "-h"], ["lint", "--", "-odd-name.urdf"], ["lint", "-"], ["lint", "--bogus"],
    ["lint", "a", "--quiet", "b"], ["expand", "x.urdf"], ["lint", "-qq"], [],
])
def test_anything_else_goes_to_argparse(argv):
    assert _plain_lint(argv) is None


def test_a_plain_lint_run_imports_no_argparse(tmp_path):
    (tmp_path / "robot.urdf").write_text('<robot name="r"><link name="base_link"/></robot>')
    code = ("import sys; from urdfcheck.cli.main import main; rc = main(['lint', '--quiet', 'robot.urdf']); "
            "print(rc, 'argparse' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert out.stdout.split()[-2:] == ["0", "False"], out.stdout + out.stderr
