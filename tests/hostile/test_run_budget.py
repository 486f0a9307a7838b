"""Attack: many models, each with automatic variants, each spending its expansion's whole allowance. Per expansion
the worker stops it (20 s, 20 000 elements), but 8 models x 8 variants multiply that: issue 11 measured 62 s for one
model with 3 boolean args. The run has one budget (`--budget`, load/budget.py): it ends within it, and every model
or variant it could not lint is an X017 finding at the model's file."""
import json
import time

from conftest import run_cli

NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
# 3 boolean args (8 automatic variants); a doubling macro that runs into the element limit (about a second each)
BOMB = f"""<robot name="r@I@" {NS}>
  <xacro:arg name="a" default="true"/>
  <xacro:arg name="b" default="false"/>
  <xacro:arg name="c" default="true"/>
  <xacro:macro name="m" params="n">
    <xacro:if value="${{n > 0}}"><xacro:m n="${{n - 1}}"/><xacro:m n="${{n - 1}}"/></xacro:if>
  </xacro:macro>
  <link name="base_link"/>
  <xacro:m n="30"/>
</robot>
"""


def _package(root, models=8):
    pkg = root / "hostile_description"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text('<?xml version="1.0"?>\n<package format="3"><name>hostile_description</name>'
                                     '<version>0.0.0</version><description>d</description>'
                                     '<maintainer email="a@b.c">a</maintainer><license>BSD</license></package>\n')
    for i in range(models):
        (pkg / "urdf" / f"m{i}.urdf.xacro").write_text(BOMB.replace("@I@", str(i)))
    return pkg


def test_eight_models_by_eight_variants_end_within_the_run_budget(tmp_path):
    _package(tmp_path)
    budget = 6.0
    t0 = time.monotonic()
    code, out, err = run_cli(["lint", "--no-config", "--format", "json", "--budget", str(budget),
                              "hostile_description"], cwd=tmp_path)
    seconds = time.monotonic() - t0
    assert code == 1, err
    assert "Traceback" not in err and "internal error" not in err, err
    assert seconds <= budget + 4.0, f"took {seconds:.1f} s for a budget of {budget} s"
    findings = json.loads(out)["findings"]
    budget_hits = [f for f in findings if f["code"] == "X017"]
    assert budget_hits, [f["code"] for f in findings]
    for f in budget_hits:  # located at the model that was not linted, naming the variant(s)
        assert f["location"]["file"].endswith(".urdf.xacro") and "not linted" in f["message"]
        assert f.get("variant"), f
    linted = {f["location"]["file"] for f in findings if f["code"] == "X012"}
    unlinted = {f["location"]["file"] for f in budget_hits}
    assert len(linted | unlinted) == 8  # every model is accounted for


def test_a_run_within_budget_has_no_budget_finding(tmp_path):
    pkg = tmp_path / "ok_description"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>ok_description</name></package>")
    (pkg / "urdf" / "r.urdf").write_text('<robot name="r"><link name="base_link"/></robot>\n')
    code, out, err = run_cli(["lint", "--no-config", "--format", "json", "ok_description"], cwd=tmp_path)
    assert "X017" not in [f["code"] for f in json.loads(out)["findings"]], out


def test_million_sibling_links_are_refused_before_parsing(tmp_path):
    p = tmp_path / "huge.urdf"
    with open(p, "w") as f:
        f.write('<robot name="r">\n')
        for i in range(1_000_000):
            f.write(f'<link name="l{i}"/>\n')
        f.write("</robot>\n")
    t0 = time.monotonic()
    code, out, err = run_cli(["lint", "--no-config", "--format", "json", "huge.urdf"], cwd=tmp_path)
    seconds = time.monotonic() - t0
    assert code == 1, err
    f = [f for f in json.loads(out)["findings"] if f["code"] == "X017"]
    assert f and "links and joints" in f[0]["message"], out[:2000]
    assert seconds < 3.0, seconds


def test_the_main_process_memory_budget_stops_the_run_with_findings(tmp_path, monkeypatch):
    pkg = tmp_path / "m_description"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>m_description</name></package>")
    for i in range(3):
        (pkg / "urdf" / f"r{i}.urdf").write_text('<robot name="r"><link name="base_link"/></robot>\n')
    monkeypatch.setenv("URDFCHECK_RUN_BUDGET", "300:1")  # 1 MiB: this process is already above it
    code, out, err = run_cli(["lint", "--no-config", "--format", "json", "m_description"], cwd=tmp_path)
    assert code == 1, err
    hits = [f for f in json.loads(out)["findings"] if f["code"] == "X017"]
    assert len({f["location"]["file"] for f in hits}) == 3 and "memory budget" in hits[0]["message"]
