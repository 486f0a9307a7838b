"""Adding a rule (issue 24): further catalogue examples with their own config run through the real CLI,
`references:` reach the docs and SARIF, the generated tables (docs/design.md, README's count) follow the
catalogue, and the scaffold writes a typed stub that ruff accepts."""
import json
import re
import shutil
import subprocess
import sys

import pytest
from conftest import REPO, example_args, run_cli, write_example

from urdfcheck.rules import catalogue as rulebook
from urdfcheck.rules import docs

CATALOGUE = rulebook.catalogue()
CASES = [(code, i) for code, r in sorted(CATALOGUE.items()) for i, _ in enumerate(r.cases)]


@pytest.mark.parametrize("code,i", CASES, ids=[f"{c}-{i}" for c, i in CASES])
def test_each_case_behaves_as_it_says_with_its_own_config(code, i, tmp_path):
    case = CATALOGUE[code].cases[i]
    target = write_example(case, tmp_path)
    flags = ["--no-config"] if case.get("config") is None else \
        ["--config", str(tmp_path / "urdfcheck.yaml"), "--trust-config"]  # the catalogue's own: a loosening option too
    exit_code, out, err = run_cli(["lint", "--format", "json", *flags, target, *example_args(case)], cwd=tmp_path)
    assert exit_code in (0, 1), err
    hits = [f for f in json.loads(out)["findings"] if f["code"] == code]
    assert bool(hits) == (case["expect"] == "fail"), (case.get("title"), hits)


def test_some_rules_have_cases_and_references():
    assert any(r.cases for r in CATALOGUE.values())
    assert sum(1 for r in CATALOGUE.values() if r.references) >= 5


def test_references_reach_the_docs_and_sarif(tmp_path):
    with_refs = [r for r in CATALOGUE.values() if r.references]
    page = docs.page(with_refs[0].code, fmt="markdown")
    assert all(ref["url"] in page for ref in with_refs[0].references)
    assert with_refs[0].references[0]["url"] in docs.page(with_refs[0].code)
    r = with_refs[0]
    ex = r.examples["fail"]
    target = write_example(ex, tmp_path)
    code, out, _ = run_cli(["lint", "--format", "sarif", "--no-config", target, *example_args(ex)], cwd=tmp_path)
    rules = {x["id"]: x for x in json.loads(out)["runs"][0]["tool"]["driver"]["rules"]}
    assert rules[r.code]["helpUri"] == r.references[0]["url"]


@pytest.mark.parametrize("bad,why", [
    ({"cases": [{"urdf": "<robot/>"}]}, "expect"),
    ({"cases": [{"expect": "fail", "config": "select: [S]"}]}, "mapping"),
    ({"references": ["https://example.org"]}, "url"),
    ({"references": [{"url": "http://x", "what": "y"}]}, "https"),
    ({"references": [{"url": "https://x"}]}, "what"),
])
def test_malformed_cases_and_references_are_catalogue_errors(tmp_path, bad, why):
    import yaml

    entry = yaml.safe_load((REPO / "rules" / "J007.yaml").read_text())
    (tmp_path / "J007.yaml").write_text(yaml.safe_dump({**entry, **bad}))
    with pytest.raises(rulebook.CatalogueError, match=why):
        rulebook.read_entries(tmp_path)


def test_design_md_rule_table_is_generated_from_the_catalogue():
    text = (REPO / "docs" / "design.md").read_text(encoding="utf-8")
    assert docs.design_table() in text, "docs/design.md's rule table is stale: " \
        "`PYTHONPATH=src python -m urdfcheck.rules.scaffold --regenerate`"


def test_readme_counts_the_rules_of_the_catalogue():
    text = (REPO / "README.md").read_text(encoding="utf-8")
    m = re.search(r"\*\*Check\*\*: (\d+) rules", text)
    assert m, "README.md: the '**Check**: N rules' sentence is gone"
    assert int(m.group(1)) == len(CATALOGUE), f"README.md says {m.group(1)} rules, the catalogue has {len(CATALOGUE)}"


def test_scaffold_writes_a_typed_stub_ruff_accepts_and_the_index(tmp_path):
    pytest.importorskip("ruff")
    (tmp_path / "rules").mkdir()
    shutil.copy(REPO / "rules" / "J007.yaml", tmp_path / "rules")
    checks = tmp_path / "src" / "urdfcheck" / "rules" / "checks"
    checks.mkdir(parents=True)
    shutil.copy(REPO / "src" / "urdfcheck" / "rules" / "checks" / "joints.py", checks)
    shutil.copy(REPO / "pyproject.toml", tmp_path)
    from urdfcheck.rules.scaffold import scaffold

    written = scaffold(tmp_path, "J099", "joint-name-too-long", "joints")
    assert tmp_path / "rules" / "index.json" in written
    assert "J099" in json.loads((tmp_path / "rules" / "index.json").read_text())
    proc = subprocess.run([sys.executable, "-m", "ruff", "check", "--no-cache", str(checks / "joints.py")],
                          cwd=tmp_path, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "-> Iterator[Problem]" in (checks / "joints.py").read_text()


def test_rule_docs_are_current():
    assert (REPO / "docs" / "rules.md").read_text(encoding="utf-8") == docs.rules_markdown()
