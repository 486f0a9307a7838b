"""A small, fixed slice of the wave-4 fuzzers (issue 36) on every `pytest` run: hostile recordings, the pull
request's config against a broken robot, and hostile git repositories, each through the real CLI in a forked
child. Every input must end with no leak, traceback, hang, silent pass or write into the checkout. The seeds are
fixed, so a CI run sees the same inputs every time; the full runs are `python3 fuzz/<name>.py --count N`."""
import shutil
import sys
from pathlib import Path

import pytest

FUZZ = Path(__file__).resolve().parent.parent / "fuzz"
sys.path.insert(0, str(FUZZ))

COUNTS = ("leaks", "tracebacks", "hangs", "silent", "writes")


def _clean(stats, examples):
    bad = {k: stats[k] for k in COUNTS + ("exec",) if stats.get(k)}
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
