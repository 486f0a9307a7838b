"""Several formats from one run: `--format` on stdout (or --output) plus repeatable `--report FORMAT=FILE`."""
import json
import xml.etree.ElementTree as ET

from conftest import run_cli
from samples import BAD


def test_all_formats_in_one_run(tmp_path):
    (tmp_path / "bad.urdf").write_text(BAD)
    (tmp_path / "out").mkdir()
    code, out, err = run_cli(["lint", "--no-config", "--select", "U", "bad.urdf", "--format", "text",
                              "--report", "sarif=out/r.sarif", "--report", "junit=out/r.xml",
                              "--report", "github=out/r.github", "--report", "markdown=out/r.md",
                              "--report", "json=out/r.json"], cwd=tmp_path)
    assert code == 1, err
    assert "bad.urdf:5  U002" in out
    sarif = json.loads((tmp_path / "out/r.sarif").read_text())
    assert [r["ruleId"] for r in sarif["runs"][0]["results"]] == ["U002"]
    junit = ET.parse(tmp_path / "out/r.xml").getroot()
    assert junit.get("failures") == "1"
    assert (tmp_path / "out/r.github").read_text().startswith("::warning file=bad.urdf,line=5,")
    assert "| severity | rule | location | message |" in (tmp_path / "out/r.md").read_text()
    assert json.loads((tmp_path / "out/r.json").read_text())["findings"][0]["code"] == "U002"
    # extra reports never carry colour codes
    assert "\x1b" not in "".join(p.read_text() for p in (tmp_path / "out").iterdir())


def test_report_with_output_file_and_same_format_twice(tmp_path):
    (tmp_path / "bad.urdf").write_text(BAD)
    code, out, _ = run_cli(["lint", "--no-config", "--select", "U", "bad.urdf", "--format", "sarif", "-o", "a.sarif",
                            "--report", "sarif=b.sarif", "--report", "text=c.txt"], cwd=tmp_path)
    assert code == 1 and out == ""
    assert (tmp_path / "a.sarif").read_text() == (tmp_path / "b.sarif").read_text()
    assert "U002" in (tmp_path / "c.txt").read_text()


def test_unknown_report_format_is_a_usage_error(tmp_path):
    (tmp_path / "bad.urdf").write_text(BAD)
    code, _, err = run_cli(["lint", "--no-config", "bad.urdf", "--report", "pdf=x.pdf"], cwd=tmp_path)
    assert code == 2 and "unknown format" in err


def test_unwritable_report_is_a_usage_error(tmp_path):
    (tmp_path / "bad.urdf").write_text(BAD)
    code, _, err = run_cli(["lint", "--no-config", "bad.urdf", "--report", "junit=missing/dir/x.xml"], cwd=tmp_path)
    assert code == 2 and "cannot write" in err
