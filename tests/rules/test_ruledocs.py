"""`urdfcheck rules`, the rule pages, and the generated docs/rules.md (fails when stale)."""
import json
import re

import pytest
from conftest import REPO, run_cli

from urdfcheck.rules import catalogue as rulebook
from urdfcheck.rules import docs as ruledocs

CATALOGUE = rulebook.catalogue()
REGENERATE = "PYTHONPATH=src python3 -m urdfcheck rules --format markdown > docs/rules.md"


def test_docs_rules_md_is_up_to_date():
    path = REPO / "docs" / "rules.md"
    assert path.is_file(), f"docs/rules.md is missing; generate it with `{REGENERATE}`"
    committed = path.read_text(encoding="utf-8")
    assert committed == ruledocs.rules_markdown(), (
        f"docs/rules.md is stale (the catalogue in rules/ changed); regenerate it with `{REGENERATE}`")


def test_cli_markdown_listing_is_the_docs():
    code, out, _ = run_cli(["rules", "--format", "markdown"])
    assert code == 0 and out == ruledocs.rules_markdown()


def test_listing_names_every_rule():
    code, out, _ = run_cli(["rules"])
    assert code == 0
    listed = [line.split()[0] for line in out.splitlines()]
    assert listed == sorted(CATALOGUE)
    for line in out.splitlines():
        code_, name = line.split()[:2]
        assert name == CATALOGUE[code_].name


def test_json_listing():
    code, out, _ = run_cli(["rules", "--format", "json"])
    data = json.loads(out)
    assert [r["code"] for r in data] == sorted(CATALOGUE)


@pytest.mark.parametrize("code", sorted(CATALOGUE))
def test_rule_page(code):
    r = CATALOGUE[code]
    exit_code, out, _ = run_cli(["rules", code.lower()])
    assert exit_code == 0
    assert out.startswith(f"{code}  {r.name}  ({r.severity}, {r.family})")
    assert " ".join(r.fix.split())[:60] in " ".join(out.split())
    assert "```" not in out  # terminal pages show examples indented, not as Markdown fences
    if r.examples.get("fail"):
        assert "Fails:" in out and "Passes:" in out
    exit_code, md, _ = run_cli(["rules", code, "--format", "markdown"])
    assert md.startswith(f"## {code} {r.name}\n")
    assert md in ruledocs.rules_markdown()
    exit_code, js, _ = run_cli(["rules", code, "--format", "json"])
    assert json.loads(js)["code"] == code


def test_unknown_rule_is_a_usage_error():
    code, out, err = run_cli(["rules", "Q999"])
    assert code == 2 and "no rule" in err and out == ""


def test_index_links_point_at_headings():
    text = ruledocs.rules_markdown()
    anchors = set(re.findall(r"\]\(#([a-z0-9-]+)\)", text))
    headings = {re.sub(r"[^a-z0-9 -]", "", h.lower()).replace(" ", "-")
                for h in re.findall(r"^## (.+)$", text, re.M)}
    assert anchors and anchors <= headings


def test_markdown_escapes_angle_brackets_outside_code():
    assert ruledocs.md("is not <robot>, use `<robot>`") == "is not &lt;robot&gt;, use `<robot>`"
