"""GitHub Actions workflow commands: levels, properties, and the runner's escaping rules."""
import re
from pathlib import Path

from conftest import run_cli
from samples import BAD

from urdfcheck.core.findings import Finding, Location, Severity
from urdfcheck.report import render
from urdfcheck.report.github import escape_data, escape_property
from urdfcheck.run import Result, Target

COMMAND = re.compile(r"^::(error|warning|notice) ((file|line|col|title)=[^,:]*)(,(file|line|col|title)=[^,:]*)*::.*$")


def test_escaping_rules():
    assert escape_data("50% a\r\nb") == "50%25 a%0D%0Ab"
    assert escape_property("a:b,c%d\ne") == "a%3Ab%2Cc%25d%0Ae"


def test_cli_annotations(tmp_path):
    (tmp_path / "urdf").mkdir()
    (tmp_path / "urdf" / "bad.urdf").write_text(BAD)
    code, out, _ = run_cli(["lint", "--no-config", "--format", "github", "--select", "U", "urdf/bad.urdf"],
                           cwd=tmp_path)
    assert code == 1
    lines = out.splitlines()
    assert lines[0].startswith("::warning file=urdf/bad.urdf,line=5,title=U002 unknown-element::unknown element")
    assert COMMAND.match(lines[0])
    assert not lines[-1].startswith("::")


def test_levels_and_properties():
    findings = [
        Finding("S001", Severity.ERROR, "two roots: a, b", Location("r.urdf", 3, 2), "multiple-roots"),
        Finding("J010", Severity.INFO, "floating 100%", Location("dir,x/r:1.urdf"), "floating-joint",
                related=(Location("r.urdf", 9),)),
    ]
    out = render("github", Result(findings, [Target(Path("r.urdf"))], {})).splitlines()
    assert out[0] == "::error file=r.urdf,line=3,col=2,title=S001 multiple-roots::two roots: a, b"
    assert out[1] == ("::notice file=dir%2Cx/r%3A1.urdf,title=J010 floating-joint::floating 100%25"
                      "%0Asee also r.urdf:9")
    assert all(COMMAND.match(line) for line in out[:2])


def test_via_lines_are_escaped_into_one_command():
    f = Finding("U002", Severity.WARNING, "m", Location("a.xacro", 5, via=(Location("b.xacro", 11),)), "x")
    out = render("github", Result([f], [], {})).splitlines()
    assert out[0].endswith("::m%0Avia macro call at b.xacro:11")
    assert len(out) == 2
