"""Attack: text from the model reaches CI logs. Link names and xacro messages carrying newlines plus GitHub
workflow commands (`::error file=...::`), Azure logging commands (`##vso[task.setvariable]`), ANSI/OSC escapes
(via xacro string escapes, C1 CSI via character references, a file name), Unicode line separators and a 100 KB
name. In every output format: no line starts with `::` except our own annotations, no ESC byte, no raw
`##vso[`/`##[`, and the output stays small."""
import json
import re

import pytest
from hostile_arena import arena, formats, line_of  # noqa: F401 (fixture)

OUR_ANNOTATION = re.compile(r"^::(error|warning|notice) file=[^:\n]*(,line=\d+)?(,col=\d+)?,title=[^:\n]*::[^\n]*$")
LINE_BREAKS = re.compile(r"\r\n|[\n\r\x0b\x0c\x1c\x1d\x1e\x85\u2028\u2029]")


PER_FINDING = 4096  # bytes a finding may take in any format once its texts are truncated


def baseline(arena) -> dict[str, int]:
    """Output size per format for a benign model with one finding (SARIF carries the whole rule table)."""
    entry = arena.write("urdf/benign.urdf", '<robot name="v">\n  <link name="a"/>\n  <link name="b"/>\n</robot>\n')
    return {fmt: len(r.out.encode("utf-8")) for fmt, r in arena.lint_all_formats(entry).items()}


def assert_inert(fmt: str, out: str, base: dict, n_findings: int) -> None:
    size = len(out.encode("utf-8"))
    assert size <= base[fmt] + PER_FINDING * n_findings, f"{fmt}: {size} bytes for {n_findings} findings"
    for bad in ("\x1b", "\x9b", "\x07", "\x00", "\r", "\x85"):
        assert bad not in out, f"{fmt}: {bad!r} in output"
    # split on every character some terminal or CI log viewer treats as a line break
    for ln in LINE_BREAKS.split(out):
        s = ln.lstrip()
        if s.startswith("::"):
            assert fmt == "github" and OUR_ANNOTATION.match(ln), f"{fmt}: injected command line {ln[:200]!r}"
        assert not s.startswith(("##vso[", "##[")), f"{fmt}: {ln[:200]!r}"
    if fmt == "github":
        for ln in out.splitlines():
            if ln.startswith("::"):
                data = ln.split("::", 2)[2]
                assert "::" not in data.replace("%3A", ""), ln[:300]  # no second command start in the data
    # elsewhere `::` inside a line is inert (the runner reads a workflow command only where a line starts, after
    # blanks: checked above), so `gz::sim::systems::DiffDrive` stays copyable (issue 42)
    assert "##vso[" not in out and "##[error]" not in out
    if fmt in ("json", "sarif"):
        json.loads(out)


@pytest.mark.parametrize("name", ["report_injection.urdf", "report_injection.urdf.xacro"])
def test_injection_is_defused_in_every_format(arena, name):
    entry = arena.data(name)
    base = baseline(arena)
    outs = arena.lint_all_formats(entry)
    report = json.loads(outs["json"].out)
    for fmt, r in outs.items():
        assert_inert(fmt, r.out, base, len(report["findings"]))
    assert report["findings"], "the hostile names must still produce (defused) findings"
    if name.endswith(".xacro"):  # the fatal() message is reported, at its line, defused
        fatal = [f for f in report["findings"] if f["code"] == "X010"]
        assert fatal and fatal[0]["location"]["line"] == line_of(entry, "xacro.fatal"), report["findings"]
        assert "from-fatal" in fatal[0]["message"]


def test_100kb_name_is_truncated_everywhere(arena):
    name = "A" * 100_000
    big = "::error file=x::" + "B" * 100_000
    entry = arena.write("urdf/big.urdf", f'<robot name="{name}">\n  <link name="base_link"/>\n'
                        f'  <link name="{name}"/>\n  <link name="{name}"/>\n  <link name="{big}"/>\n'
                        f'  <joint name="{big}" type="bogus"><parent link="{name}"/><child link="{big}"/></joint>\n'
                        "</robot>\n")
    base = baseline(arena)
    r = arena.lint(entry)
    for fmt, out in arena.lint_all_formats(entry).items():
        assert_inert(fmt, out.out, base, len(r.findings))
        assert "A" * 1000 not in out.out and "B" * 1000 not in out.out, fmt
    assert any(f["location"]["line"] == 4 and f["code"] == "S007" for f in r.findings), r.codes()


def test_hostile_file_names_are_defused(arena):
    """A file name is the one place where raw ESC and newlines reach a report without any XML escaping."""
    evil = "evil\x1b[31m\n::error file=x::pwned\r##vso[task.setvariable variable=x]1.urdf"
    base = baseline(arena)
    (arena.pkg / "urdf" / evil).write_text('<robot name="v">\n  <link name="a"/>\n  <link name="b"/>\n</robot>\n')
    n = len(arena.lint(arena.pkg / "urdf" / evil).findings)
    for fmt, r in arena.lint_all_formats(arena.pkg / "urdf" / evil).items():
        assert_inert(fmt, r.out, base, n)
        assert "pwned" in r.out or fmt == "markdown", fmt


def test_messages_from_hostile_yaml_values_are_defused(arena):
    """Values loaded from YAML can carry raw ESC and newlines straight into the expanded document."""
    arena.write("config/evil.yaml", 'name: "a\\e[31m\\n::error file=x::pwned\\n##vso[task.setvariable variable=x]1"\n')
    entry = arena.write("urdf/y.urdf.xacro", '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <link name="a"/>\n'
                        '  <link name="${xacro.load_yaml(\'../config/evil.yaml\').name}"/>\n</robot>\n')
    base = baseline(arena)
    n = len(arena.lint(entry).findings)
    for fmt, r in arena.lint_all_formats(entry).items():
        assert_inert(fmt, r.out, base, n)
