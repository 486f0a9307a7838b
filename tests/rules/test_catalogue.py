"""Every catalogue entry is complete, and its examples behave as documented through the real CLI."""
import re

import pytest
from conftest import example_args, lint_json, write_example

from urdfcheck.core.findings import Severity
from urdfcheck.rules import catalogue as rulebook

CATALOGUE = rulebook.catalogue()
WITH_EXAMPLES = sorted(c for c, r in CATALOGUE.items() if r.examples)


def test_catalogue_is_not_empty():
    assert len(CATALOGUE) >= 19


@pytest.mark.parametrize("code", sorted(CATALOGUE))
def test_entry_is_complete(code):
    r = CATALOGUE[code]
    assert re.fullmatch(r"[A-Z]\d{3}", r.code)
    assert re.fullmatch(r"[a-z0-9]+(-[a-z0-9]+)*", r.name), r.name
    assert isinstance(r.severity, Severity)
    for field in ("summary", "rationale", "fix"):
        assert len(getattr(r, field)) > 20, f"{code}: {field} is too thin"


def test_names_are_unique():
    names = [r.name for r in CATALOGUE.values()]
    assert len(names) == len(set(names))


def test_every_check_has_an_entry_and_vice_versa():
    checks = rulebook.load_checks()
    # produced by the loader/engine/verify/recordings/`urdfcheck consumers`, not by checks; C021 and C025 by the
    # planner (a deployment it did not understand; a launch file naming a model file that is not there)
    load_time = {c for c in CATALOGUE if c[0] in "XRVB"} | {"C021", "C025", "P090", "P091"}
    assert set(checks) - set(CATALOGUE) == set(), "checks without catalogue entry"
    assert set(CATALOGUE) - set(checks) - load_time == set(), "catalogue entries without a check"


def test_only_runner_and_verify_rules_lack_examples():
    # R001 needs a broken rule; V codes come from `urdfcheck verify` (tests/verify/test_verify.py), P090/P091 from
    # `urdfcheck consumers` (tests/verify/test_consumers.py); X018 needs a config file found in the checkout
    # (examples run --no-config): tests/request/test_untrusted.py
    assert sorted(c for c in CATALOGUE if not CATALOGUE[c].examples) == ["P090", "P091", "R001", "V001", "V002", "X018"]


@pytest.mark.parametrize("code", WITH_EXAMPLES)
def test_failing_example_reports_the_code(code, tmp_path):
    ex = CATALOGUE[code].examples["fail"]
    target = write_example(ex, tmp_path)
    exit_code, report = lint_json([target, *example_args(ex)], cwd=tmp_path)
    hits = [f for f in report["findings"] if f["code"] == code]
    assert hits, f"{code} not reported; got {[(f['code'], f['message']) for f in report['findings']]}"
    assert all(f["name"] == CATALOGUE[code].name for f in hits)
    assert all(f["location"]["file"] for f in hits)
    if CATALOGUE[code].severity >= Severity.WARNING:
        assert exit_code == 1


@pytest.mark.parametrize("code", WITH_EXAMPLES)
def test_passing_example_does_not_report_the_code(code, tmp_path):
    ex = CATALOGUE[code].examples["pass"]
    target = write_example(ex, tmp_path)
    _, report = lint_json([target, *example_args(ex)], cwd=tmp_path)
    hits = [f for f in report["findings"] if f["code"] == code]
    assert not hits, hits
    errors = [f for f in report["findings"] if f["severity"] == "error"]
    assert not errors, f"the passing example of {code} has errors: {errors}"


def test_index_is_up_to_date():
    import json

    folder = rulebook.catalogue_dir()
    written = [json.loads((folder / name).read_text(encoding="utf-8")) for name in (rulebook.INDEX, rulebook.DETAILS)]
    assert written == json.loads(json.dumps(list(rulebook.split_entries(rulebook.read_entries())))), \
        "rules/index.json or details.json is stale: regenerate them with " \
        "`PYTHONPATH=src python -m urdfcheck.rules.catalogue`"


def test_a_lint_run_reads_the_small_index_only():
    """The run path reads names, severities and options; the long texts and examples come only when asked."""
    rulebook._details.cache_clear()
    rulebook.catalogue.cache_clear()
    cat = rulebook.catalogue()
    assert cat["J001"].severity and cat["J001"].summary
    assert rulebook._details.cache_info().currsize == 0
    assert cat["J001"].rationale and cat["J001"].examples.get("fail")
    assert rulebook._details.cache_info().currsize == 1
    entries = rulebook.read_entries()
    for code, r in cat.items():
        assert r.rationale == str(entries[code]["rationale"]).strip()
        assert r.cases == tuple(entries[code].get("cases") or ())


def test_every_check_module_is_loaded():
    """`load_checks` imports the modules `CHECK_MODULES` names: every module of rules/checks is there."""
    import pkgutil

    from urdfcheck.rules import checks

    in_folder = sorted(f"urdfcheck.rules.checks.{m.name}" for m in pkgutil.iter_modules(checks.__path__))
    assert sorted(rulebook.CHECK_MODULES) == in_folder
