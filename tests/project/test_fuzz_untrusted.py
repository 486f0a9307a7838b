"""A small, fixed slice of the untrusted-input fuzzers (issue 36) on every `pytest` run: hostile recordings, the
pull request's config against a broken robot, hostile git repositories, joint-state files the runner names and
recordings the config declares, each through the real CLI in a forked child. Every input must end with no leak,
traceback, hang, silent pass or write into the checkout. The seeds are fixed, so a CI run sees the same inputs every
time; the full runs are `python3 fuzz/<name>.py --count N`."""
import shutil
import sys
from pathlib import Path

import pytest

FUZZ = Path(__file__).resolve().parents[2] / "fuzz"
sys.path.insert(0, str(FUZZ))

COUNTS = ("leaks", "tracebacks", "hangs", "silent", "writes")


def _clean(stats, examples):
    bad = {k: stats[k] for k in COUNTS + ("exec", "controls", "unread") if stats.get(k)}
    assert not bad, (bad, examples[:3])
    assert stats["inputs"] > 0


def test_recordings_slice():
    pytest.importorskip("rosbags")
    pytest.importorskip("lz4")
    import recordings

    stats, examples, _ = recordings.run(120, 20261128, hang=120, batch=40, cli_every=6, small=True)
    assert stats["inputs"] == 120
    _clean(stats, examples)


def test_configs_slice():
    import configs

    stats, examples, _ = configs.run(150, 20261128, hang=120, batch=50, report=None)
    assert stats["inputs"] == 150
    # the slice reaches past config validation to the gate, not only exit 2
    assert stats["outcomes"].get("exit 1", 0) >= 20, stats["outcomes"]
    _clean(stats, examples)


@pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")
def test_git_revisions_slice():
    import gitrev

    stats, examples, _ = gitrev.run(40, 20261128, nrepos=3, hang=120, batch=20, report=None)
    assert stats["inputs"] == 40
    _clean(stats, examples)


def test_joint_state_files_slice():
    """fuzz/jointstates.py: the joint-state file the runner names (publish --joint-states, bag, lint --bag) as the
    pull request left it: grammar documents, hostile whole files, links out, FIFOs, odd names."""
    pytest.importorskip("yaml")
    import jointstates

    stats, examples, _ = jointstates.run(50, 20261128, hang=120, batch=50, report=None, small=True)
    assert stats["inputs"] == 50
    assert not stats["controls"], examples[:3]
    # the slice reaches the readers: most runs end in findings (exit 1), not in a refusal
    assert sum(v for k, v in stats["outcomes"].items() if k.endswith("exit 1")) >= 25, stats["outcomes"]
    _clean(stats, examples)


def test_config_declared_recordings_slice():
    """fuzz/configbags.py: `bags:` in the pull request's config, beside a broken robot, with the recordings
    grammar's hostile recordings and hostile entries (links out, absolute paths, FIFOs)."""
    pytest.importorskip("rosbags")
    pytest.importorskip("lz4")
    import configbags

    stats, examples, _ = configbags.run(40, 20261128, hang=120, batch=40, report=None, small=True)
    assert stats["inputs"] == 40
    _clean(stats, examples)
