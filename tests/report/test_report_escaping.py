"""What each report format escapes, and only there (issues 36 and 42).

GitHub reads a workflow command only where a line starts (`::error ...`): the zero-width space that defuses `::`
belongs in the annotations format, while `gz::sim::systems::DiffDrive` stays copyable in the others. Markdown
(lint's, diff's, consumers') makes HTML, links, @mentions and bare URLs inert; bidi controls are made visible in
every format; terminal escape sequences never reach the progress line; a file name that is not UTF-8 is shown by
its bytes and does not stop --report/--output; a node or frame named after its launch file (`__file__`) does not
show the runner's absolute path.
"""
from __future__ import annotations

import io
import json
import os
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest
from conftest import run_cli

from urdfcheck.core import progress
from urdfcheck.core.findings import Finding, Location, Severity, clean_text
from urdfcheck.report import render
from urdfcheck.report.markdown import md
from urdfcheck.run import Result, Target

PLUGIN = "gz::sim::systems::DiffDrive"


def _result(message: str, file: str = "r.urdf") -> Result:
    f = Finding("G003", Severity.WARNING, message, Location(file, 4), "plugin", model=file)
    return Result([f], [Target(Path(file))], {})


@pytest.mark.parametrize("fmt", ["text", "json", "sarif", "junit", "markdown"])
def test_double_colons_stay_as_written_outside_the_annotations(fmt):
    out = render(fmt, _result(f"plugin {PLUGIN} needs a joint"), fail_on=Severity.WARNING)
    if fmt == "markdown":
        assert PLUGIN in out.replace("\\", "")  # `_` and `:` are not escaped; nothing between the colons
    else:
        assert PLUGIN in out
    assert "\u200b" not in out


def test_annotations_defuse_every_double_colon():
    out = render("github", _result(f"plugin {PLUGIN} ::error::x"), fail_on=Severity.WARNING)
    command = out.splitlines()[0]
    data = command.split("::", 2)[2]
    assert "::" not in data and "gz:\u200b:sim" in data


def test_a_line_never_starts_a_workflow_command():
    assert clean_text("::error file=x::pwned").startswith(":\u200b:")
    assert clean_text("  ::warning::x").startswith("  :\u200b:")
    assert clean_text("a::b") == "a::b"
    out = render("text", _result("m", file="::error::x.urdf"), fail_on=Severity.WARNING)
    assert not any(ln.lstrip().startswith("::") for ln in out.splitlines())


def test_markdown_wraps_bare_urls_in_code_spans():
    s = md("see https://evil.example/login and www.evil.example for @team")
    assert "`https://evil.example/login`" in s and "`www.evil.example`" in s
    assert "@team" not in s
    assert md("<img src=x> [a](b)") == "&lt;img src=x&gt; \\[a\\](b)"


def _lint_md(tmp_path, link: str) -> str:
    (tmp_path / "r.urdf").write_text(f'<robot name="r"><link name="base"/><link name="{link}"/>'
                                     f'<joint name="j" type="fixed"><parent link="base"/><child link="{link}"/>'
                                     f'</joint><bogus/></robot>')
    return run_cli(["lint", "--no-config", "--no-cache", "--format", "markdown", "r.urdf"], cwd=tmp_path)[1]


HOSTILE_LINK = "x&lt;img src=y&gt;[c](https://evil.example) @team \u202eabc"


def test_diff_markdown_makes_names_inert(tmp_path):
    old, new = tmp_path / "old", tmp_path / "new"
    old.mkdir()
    new.mkdir()
    (old / "r.urdf").write_text('<robot name="r"><link name="base"/></robot>')
    (new / "r.urdf").write_text(f'<robot name="r"><link name="base"/><link name="{HOSTILE_LINK}"/>'
                                f'<joint name="j&lt;b&gt;" type="fixed"><parent link="base"/>'
                                f'<child link="{HOSTILE_LINK}"/></joint></robot>')
    for fmt in ("markdown", "text", "json"):
        code, out, err = run_cli(["diff", "old", "new", "--format", fmt], cwd=tmp_path)
        assert code == 0, err
        assert "\u202e" not in out, fmt  # bidi made visible in every format
        if fmt == "markdown":
            assert "<img" not in out and "<b>" not in out
            assert "](https://" not in out and "@team" not in out
            assert "`https://evil.example)`" in out or "`https://evil.example`" in out


def test_consumers_markdown_makes_messages_inert():
    from urdfcheck.cli.consumers import render as consumers_render

    o = SimpleNamespace(consumer="mujoco", status="refused", loaded=False, location=None, changes=[],
                        notes=["see https://evil.example @team"],
                        message="<img src=x> [c](https://evil.example) @team \u202eabc")
    out = consumers_render("markdown", "r.urdf", [o], [])
    assert "<img" not in out and "@team" not in out and "](https://" not in out and "\u202e" not in out
    assert "`https://evil.example`" in out
    text = consumers_render("text", "r.urdf", [o], [])
    assert "\u202e" not in text


class Terminal(io.StringIO):
    def isatty(self):
        return True


def test_progress_line_strips_terminal_escapes(monkeypatch):
    monkeypatch.setattr(progress, "DELAY", 0.0)
    monkeypatch.setattr(progress, "INTERVAL", 0.0)
    term = Terminal()
    progress.to_terminal(term)
    progress.step(0, 1, "a\x1b]52;c;c2VjcmV0\x07b\x1b]8;;https://evil.example\x1b\\c\u202ed.urdf")
    progress.close()
    text = term.getvalue()
    assert "\x1b]" not in text and "\x07" not in text and "c2VjcmV0" not in text and "evil" not in text
    assert "\u202e" not in text and "abc" in text
    assert text.replace("\r\x1b[K", "").count("\x1b") == 1  # our own erase-line only


def _bytes_name_dir(tmp_path) -> Path:
    name = os.fsdecode(b"bad\xff.urdf")
    try:
        (tmp_path / name).write_text('<robot name="r"><link name="a"/><link name="b"/></robot>')
    except (OSError, UnicodeError):
        pytest.skip("this file system refuses names that are not UTF-8")
    return tmp_path


@pytest.mark.skipif(sys.platform == "win32", reason="file names are UTF-16 there")
@pytest.mark.parametrize("fmt", ["text", "json", "sarif", "junit", "github", "markdown"])
def test_a_file_name_that_is_not_utf8_does_not_stop_the_reports(tmp_path, fmt):
    d = _bytes_name_dir(tmp_path)
    code, out, err = run_cli(["lint", "--no-config", "--no-cache", ".", "--format", fmt, "--output", "out.txt",
                              "--report", "sarif=out.sarif", "--report", "markdown=out.md"], cwd=d)
    assert code == 1, err  # two roots: a finding, as with any other name
    shown = (d / "out.txt").read_text(encoding="utf-8")
    assert "bad\\xff.urdf" in shown.replace("\\\\", "\\")
    sarif = json.loads((d / "out.sarif").read_text(encoding="utf-8"))
    uris = {r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] for r in sarif["runs"][0]["results"]}
    assert uris == {"bad%FF.urdf"}  # the file's own bytes, percent-encoded
    assert "bad\\xff.urdf" in (d / "out.md").read_text(encoding="utf-8").replace("\\\\", "\\")


def test_a_baseline_with_a_name_that_is_not_utf8(tmp_path):
    d = _bytes_name_dir(tmp_path)
    code, _, err = run_cli(["lint", "--no-config", "--no-cache", ".", "--write-baseline", "b.json"], cwd=d)
    assert code == 0, err
    code, out, err = run_cli(["lint", "--no-config", "--no-cache", ".", "--baseline", "b.json"], cwd=d)
    assert code == 0, (out, err)


LAUNCH = """import os
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    urdf = os.path.join(os.path.dirname(__file__), '..', 'urdf', 'r.urdf')
    with open(urdf) as f:
        desc = f.read()
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher', name=__file__,
             parameters=[{'robot_description': desc}]),
        Node(package='tf2_ros', executable='static_transform_publisher', name='st',
             arguments=['0', '0', '0', '0', '0', '0', __file__, 'base_link']),
    ])
"""


def test_names_from_file_do_not_show_the_runners_path(tmp_path):
    pkg = tmp_path / "pkg"
    (pkg / "launch").mkdir(parents=True)
    (pkg / "urdf").mkdir()
    (pkg / "package.xml").write_text("<package format='3'><name>pkg</name></package>")
    (pkg / "urdf" / "r.urdf").write_text('<robot name="r"><link name="base_link"/></robot>')
    (pkg / "launch" / "bot.launch.py").write_text(LAUNCH)
    code, out, err = run_cli(["lint", "--no-config", "--no-cache", "pkg", "--list"], cwd=tmp_path)
    assert code == 0, err
    assert "static transforms: pkg/launch/bot.launch.py->base_link" in out
    assert str(tmp_path).strip("/") not in out
    code, out, err = run_cli(["lint", "--no-config", "--no-cache", "pkg", "--format", "json"], cwd=tmp_path)
    assert str(tmp_path).strip("/") not in out


def test_list_and_info_lines_show_bidi_controls(tmp_path):
    name = "a\u202eb.urdf"
    (tmp_path / name).write_text('<robot name="r"><link name="a"/></robot>')
    (tmp_path / "c\u202ed.yaml").write_text("x: 1\n")
    code, out, err = run_cli(["lint", "--no-cache", "--list", name], cwd=tmp_path)
    assert code == 0 and "a\\u202eb.urdf" in out and "\u202e" not in out, out + err
    code, out, err = run_cli(["lint", "--no-cache", "c\u202ed.yaml"], cwd=tmp_path)
    assert "c\\u202ed.yaml" in err and "\u202e" not in err + out, err
