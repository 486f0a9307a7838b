"""Untrusted text (names, file names, messages from a model) cannot inject anything into any report format."""
import json
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from conftest import run_cli

from urdfcheck.core.findings import Finding, Location, Severity
from urdfcheck.report import render
from urdfcheck.run import Result, Target

FORMATS = ["text", "json", "sarif", "junit", "github", "markdown"]
EVIL = ("x\n::error file=pwned.py,line=1::owned\r\n##[error]vso ##vso[task.setvariable]1 "
        "\x1b[31mred\x1b[0m\x07 `|<img src=x>@team")
# XML cannot carry ESC, but a file name can; a link name can carry newlines (character references)
EVIL_FILE = "evil\x1b[31m\n::error::name.urdf"
MODEL = """<robot name="r">
  <link name="base_link"/>
  <link name="a&#10;::error file=x.py::pwned&#13;&#10;##[error]b `|&lt;img&gt;">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="j&#10;::warning::x&quot;]--&gt;n0" type="fixed">
    <parent link="base_link"/>
    <child link="a&#10;::error file=x.py::pwned&#13;&#10;##[error]b `|&lt;img&gt;"/>
    <orign/>
  </joint>
</robot>
"""
OUR_LINE = re.compile(r"^::(error|warning|notice) [^\n]*::[^\n]*$")


def assert_inert(fmt: str, out: str, n_commands: int = 0):
    assert "\x1b" not in out and "\x07" not in out and "\r" not in out
    lines = out.splitlines()
    if fmt == "github":
        commands = [ln for ln in lines if ln.startswith("::")]
        assert len(commands) == n_commands
        assert all(OUR_LINE.match(ln) for ln in commands)
        others = [ln for ln in lines if not ln.startswith("::")]
        assert all(ln.startswith("urdfcheck: ") for ln in others)
        for ln in commands:  # the data part holds no raw command start
            data = ln.split("::", 2)[2]
            assert "::error" not in data and "::warning" not in data and "##[" not in data
    else:
        for ln in lines:
            s = ln.strip()
            assert not s.startswith("::") and not s.startswith("##[") and not s.startswith("##vso[")
        # `::` mid-line is no command (GitHub reads one only where a line starts): it stays as written there
        assert "##[error]" not in out and "##vso[" not in out
    if fmt == "json" or fmt == "sarif":
        doc = json.loads(out)

        def strings(x):
            if isinstance(x, dict):
                for k, v in x.items():
                    yield k
                    yield from strings(v)
            elif isinstance(x, list):
                for v in x:
                    yield from strings(v)
            elif isinstance(x, str):
                yield x

        # (a message may quote a name as Python does, `'a\\n::error'`: a backslash and an n, on one line)
        assert not any("\x1b" in v or "\n::" in v for v in strings(doc))
    if fmt == "junit":
        root = ET.fromstring(out.encode("utf-8"))
        for el in root.iter():
            for v in el.attrib.values():
                assert "\n" not in v and "\x1b" not in v
    if fmt == "markdown":
        assert "<img" not in out and "@team" not in out
        for block in re.findall(r"```mermaid\n(.*?)```", out, re.S):
            for ln in block.splitlines()[1:]:
                assert re.fullmatch(r'  n\d+\["[^"\n`]*"\]|  n\d+ -->\|"[^"\n`|]*"\| n\d+', ln), ln
        for ln in lines:
            if ln.startswith("|"):
                n = len(re.findall(r"(?<!\\)\|", ln))
                assert n in (5, 6), ln  # no cell was split by a name


@pytest.mark.parametrize("fmt", FORMATS)
def test_synthetic_findings(fmt):
    findings = [
        Finding("U002", Severity.ERROR, EVIL, Location(EVIL_FILE, 3, via=(Location(EVIL, 4),)), "unknown-element",
                related=(Location(EVIL, 5),), model=EVIL_FILE, variant="v\n::error::x"),
        Finding("U003", Severity.WARNING, EVIL, Location(EVIL, 1), "unknown-attribute", model=EVIL),
        Finding("U001", Severity.INFO, EVIL, Location(EVIL), "", model=EVIL),
    ]
    targets = [Target(Path(EVIL_FILE), {"a": EVIL}, variant="v\n::error::x"), Target(Path(EVIL))]
    out = render(fmt, Result(findings, targets, {}), colour=False, fail_on=Severity.WARNING)
    assert_inert(fmt, out, n_commands=3)


@pytest.mark.parametrize("fmt", FORMATS)
def test_hostile_model_through_the_cli(tmp_path, fmt):
    (tmp_path / EVIL_FILE).write_text(MODEL)
    code, out, err = run_cli(["lint", "--no-config", "--select", "U", "--format", fmt, "--color", "never",
                              EVIL_FILE], cwd=tmp_path)
    assert code == 1, err
    assert "pwned" in out or fmt == "markdown"  # the finding is there, defused
    _, as_json, _ = run_cli(["lint", "--no-config", "--select", "U", "--format", "json", EVIL_FILE], cwd=tmp_path)
    assert_inert(fmt, out, n_commands=len(json.loads(as_json)["findings"]))
    if fmt == "markdown":
        assert "```mermaid" in out and "pwned" in out.split("```mermaid", 1)[1]
