"""Markdown for pull-request comments: summary table, findings table, TF tree as Mermaid."""
import re
from pathlib import Path

from conftest import run_cli

from urdfcheck.core.findings import Finding, Location, Place, Severity
from urdfcheck.report import render
from urdfcheck.report.markdown import MAX_CHARS, md, mermaid
from urdfcheck.run import Result, Target

ARM = """<robot name="r">
  <link name="base_link"/>
  <link name="arm"/>
  <link name="hand"/>
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/>
    <child link="arm"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
  <joint name="wrist" type="fixed">
    <orign xyz="0 0 0.5"/>
    <parent link="arm"/>
    <child link="hand"/>
  </joint>
</robot>
"""


def table_rows(text, header):
    lines = text.splitlines()
    i = lines.index(header)
    rows = []
    for line in lines[i + 2:]:
        if not line.startswith("|"):
            break
        rows.append(line)
    return rows


def cells(row):
    return [c.strip() for c in re.split(r"(?<!\\)\|", row)[1:-1]]


def test_cli_markdown(tmp_path):
    (tmp_path / "arm.urdf").write_text(ARM)
    code, out, _ = run_cli(["lint", "--no-config", "--format", "markdown", "--select", "U", "arm.urdf"],
                           cwd=tmp_path)
    assert code == 1
    assert out.startswith("## urdfcheck")
    summary = table_rows(out, "| model | variant | errors | warnings | info |")
    assert [cells(r) for r in summary] == [["arm.urdf", "–", "0", "1", "0"]]
    findings = table_rows(out, "| severity | rule | location | message |")
    assert len(findings) == 1
    sev, rule, where, msg = cells(findings[0])
    assert "warning" in sev and "U002" in rule and where == "arm.urdf:12"
    assert "&lt;orign&gt;" in msg
    block = out.split("```mermaid\n", 1)[1].split("```", 1)[0].splitlines()
    assert block[0] == "flowchart TD"
    nodes = dict(re.findall(r'^  (n\d+)\["([^"]*)"\]$', "\n".join(block), re.M))
    ids = {v: k for k, v in nodes.items()}
    assert set(ids) == {"base_link", "arm", "hand"}
    assert f'  {ids["base_link"]} -->|"shoulder #40;revolute#41;"| {ids["arm"]}' in block
    assert f'  {ids["arm"]} -->|"wrist #40;fixed#41;"| {ids["hand"]}' in block


def test_clean_run(tmp_path):
    (tmp_path / "ok.urdf").write_text('<robot name="r">\n  <link name="base_link"/>\n</robot>\n')
    code, out, _ = run_cli(["lint", "--no-config", "--format", "markdown", "--select", "U", "ok.urdf"],
                           cwd=tmp_path)
    assert code == 0
    assert "all checks passed" in out and "### Findings" not in out
    assert "```mermaid" in out


def test_unloadable_model_and_variants():
    t1 = Target(Path("r.urdf.xacro"), variant="a")
    t2 = Target(Path("r.urdf.xacro"), variant="b")
    f = Finding("X001", Severity.ERROR, "broken", Location("r.urdf.xacro", 1), "xml-syntax",
                model="r.urdf.xacro", variant="a", where=(Place("r.urdf.xacro", "a"), Place("r.urdf.xacro", "b")))
    out = render("markdown", Result([f], [t1, t2], {("r.urdf.xacro", "a"): None, ("r.urdf.xacro", "b"): None}),
                 fail_on=Severity.WARNING)
    rows = [cells(r) for r in table_rows(out, "| model | variant | errors | warnings | info |")]
    assert rows == [["r.urdf.xacro", "a", "1", "0", "0"], ["r.urdf.xacro", "b", "1", "0", "0"]]
    assert "not loaded" in out


def test_escaping_helpers():
    assert md("a|b <img src=x> @team `x` [l](http://e) $x$") == (
        "a\\|b &lt;img src=x&gt; @\u200bteam \\`x\\` \\[l\\](`http://e)` \\$x\\$")
    assert mermaid('a"b]-->c') == "a#34;b#93;#45;#45;#62;c"
    assert mermaid("base_link 1") == "base_link 1"


def test_long_output_stays_under_the_comment_limit():
    findings = [Finding("U002", Severity.WARNING, "x" * 400, Location(f"f{i}.urdf", i), "unknown-element")
                for i in range(1, 2000)]
    out = render("markdown", Result(findings, [Target(Path("r.urdf"))], {}))
    assert len(out) <= MAX_CHARS + 1
    assert "more (see the full report" in out
