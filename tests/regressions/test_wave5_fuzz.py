"""Inputs the wave-5 fuzzers (fuzz/jointstates.py, fuzz/configbags.py) found, minimised: a joint-state file the
runner names (`publish --joint-states`, `bag MODEL FILE`, `lint --bag`) that ended in an internal error, ran past
the budget, or printed the pull request's bidi controls as they are."""
import json
import shutil
from pathlib import Path

import pytest
from conftest import run_cli

FIXTURES = Path(__file__).resolve().parent.parent / "fixtures" / "ros1"
ALL_JOINTS = ["left_wheel_joint", "right_wheel_joint", "arm_joint"]


def _robot(tmp_path):
    shutil.copyfile(FIXTURES / "robot.urdf", tmp_path / "robot.urdf")


def _no_internal_error(code, out, err):
    assert code in (1, 2), (code, err)
    assert "internal error" not in out + err and "Traceback" not in out + err, err


@pytest.mark.parametrize("stamp", ["[.inf, 0]", "{sec: .inf}"])
def test_publish_an_infinite_stamp_part_is_a_rejected_message(tmp_path, stamp):
    """fuzz/jointstates.py: `stamp: [.inf, 0]` raised OverflowError (int(inf)) out of JointState.from_dict, which
    `publish` caught as TypeError/ValueError only."""
    _robot(tmp_path)
    (tmp_path / "js.yaml").write_text(f"- {{name: [arm_joint], position: [1], stamp: {stamp}}}\n")
    code, out, err = run_cli(["publish", "robot.urdf", "--joint-states", "js.yaml"], cwd=tmp_path)
    _no_internal_error(code, out, err)


def test_publish_a_position_past_a_double_is_a_rejected_message(tmp_path):
    """fuzz/jointstates.py: a 400-digit integer position raised OverflowError (float(int)) out of from_dict."""
    _robot(tmp_path)
    (tmp_path / "js.json").write_text(json.dumps([{"name": ["arm_joint"], "position": [10**400], "stamp": 1}]))
    code, out, err = run_cli(["publish", "robot.urdf", "--joint-states", "js.json"], cwd=tmp_path)
    _no_internal_error(code, out, err)
    assert "out of range" in out


def test_publish_an_infinite_position_publishes_nan(tmp_path):
    """fuzz/jointstates.py: `position: [.inf]` for a revolute joint: math.sin(inf) raised ValueError in the
    publisher (robot_state_publisher, through C's sin, publishes NaN)."""
    _robot(tmp_path)
    (tmp_path / "js.yaml").write_text("- {name: [arm_joint], position: [.inf], stamp: 1}\n")
    code, out, err = run_cli(["publish", "robot.urdf", "--joint-states", "js.yaml"], cwd=tmp_path)
    assert "internal error" not in err and "Traceback" not in err, err
    doc = json.loads(out)
    (tf,) = [t for t in doc["messages"][0]["/tf"] if t["child"] == "arm_link"]
    assert all(v != v for v in tf["rotation"])  # NaN


@pytest.mark.parametrize("command", [["bag", "robot.urdf", "js.yaml"], ["lint", "robot.urdf", "--bag", "js.yaml"],
                                     ["publish", "robot.urdf", "--joint-states", "js.yaml"]])
def test_a_stamp_past_int64_nanoseconds_is_a_finding(tmp_path, command):
    """fuzz/jointstates.py: a stamp of 10**400 seconds was read; the finding's "(at +N s)" divided it into a float:
    OverflowError out of the recording checks."""
    _robot(tmp_path)
    (tmp_path / "js.yaml").write_text(
        "- {name: [arm_joint, left_wheel_joint, right_wheel_joint], position: [1, 0, 0], stamp: 1}\n"
        "- {name: [arm_joint], position: [1, 2], stamp: {sec: " + "9" * 400 + "}}\n")
    code, out, err = run_cli(command + ["--no-cache"] * (command[0] != "publish"), cwd=tmp_path)
    _no_internal_error(code, out, err)
    if command[0] != "publish":
        assert "B014" in out and "out of range" in out


def test_a_huge_joint_name_gets_no_hint_and_costs_no_memory():
    """fuzz/jointstates.py: a recording naming a 48 MB joint spent 14 s and 2 GB in "did you mean" (difflib indexes
    the word first), past `--budget 3`. A word whose length no option comes near gets no hint, at no cost."""
    import tracemalloc

    from urdfcheck.core.findings import closest

    word = "a" * 4_000_000
    tracemalloc.start()
    try:
        assert closest(word, ["arm_joint", "left_wheel_joint"]) is None
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 4_000_000, peak  # difflib's index of the word: over 100 MB
    assert closest("arm_jiont", ["arm_joint", "left_wheel_joint"]) == "arm_joint"


@pytest.mark.parametrize("name", ["\u202ejs.yaml", "\u2066js.yaml"])
def test_publish_shows_bidi_controls_of_a_file_name(tmp_path, name):
    """fuzz/jointstates.py: a joint-state file whose name holds U+202E: `publish` printed it as it is in its error
    and in the recording findings on stderr (lint's reports show `\\u202e`)."""
    _robot(tmp_path)
    (tmp_path / name).write_text("- {name: [ghost_joint], position: [1], stamp: 1}\n")
    code, out, err = run_cli(["publish", "robot.urdf", "--joint-states", name], cwd=tmp_path)
    assert code == 1
    assert name[0] not in err and f"\\u{ord(name[0]):04x}" in err
    (tmp_path / name).unlink()
    (tmp_path / name).symlink_to("/proc/self/environ")
    code, out, err = run_cli(["publish", "robot.urdf", "--joint-states", name], cwd=tmp_path)
    assert code == 2
    assert name[0] not in err and f"\\u{ord(name[0]):04x}" in err


def test_publish_stops_at_the_budget(tmp_path):
    """fuzz/jointstates.py: `publish --budget 3` of a 24 MB list of 100,000 JointStates ran on for minutes (the
    budget covered only the model's loading) and held every message in memory. Its output now stops when the
    budget is spent, and says so (exit 1)."""
    _robot(tmp_path)
    item = json.dumps({"name": ALL_JOINTS, "position": [0.1, 0.2, 0.3], "stamp": 1.0})
    (tmp_path / "js.json").write_text("[" + ",".join([item] * 400_000) + "]")
    code, out, err = run_cli(["publish", "robot.urdf", "--joint-states", "js.json", "--budget", "2"], cwd=tmp_path)
    assert code == 1, err
    assert "time budget (2 s) ran out" in err
    doc = json.loads(out)  # what was written is a whole document
    assert 0 < len(doc["messages"]) < 400_000


def test_a_megabyte_joint_name_is_quoted_cut(tmp_path):
    """fuzz/jointstates.py: `bag` of a 63 MiB recording naming one 63 MiB joint ran past `--budget 3` by 7 s:
    the findings quoted the name whole (B001, B002) and every report's text cleaning ran its expressions over it
    before cutting it to 500 characters. The name is cut where it is quoted, and the cleaning cuts first."""
    import tracemalloc

    from urdfcheck.bag import check_recording
    from urdfcheck.core.findings import clean_text
    from urdfcheck.model.build import model_from_string

    _robot(tmp_path)
    doc = [{"name": ["ghost_joint", "arm_joint"], "position": [0.1, 0.2], "stamp": 0.5},
           {"name": ["n" * 2_000_000], "position": [1], "stamp": 1}]
    (tmp_path / "js.json").write_text(json.dumps(doc))
    model = model_from_string((tmp_path / "robot.urdf").read_text())
    found = check_recording(model, str(tmp_path / "js.json"), text=True, runner=True)
    assert {f.code for f in found} >= {"B001"}
    assert all(len(f.message) < 5000 for f in found), [len(f.message) for f in found]

    text = "\x1b[31m" + "x" * 5_000_000
    tracemalloc.start()
    try:
        out = clean_text(text)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert out == "x" * 499 + "\u2026"
    assert peak < 1_000_000, peak  # each expression copied the 5 MB text


@pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")
@pytest.mark.parametrize("target", ["/nowhere/robot.urdf", "../../outside.urdf"])
def test_diff_base_and_config_from_a_revision_whose_model_is_a_link_names_no_absolute_path(tmp_path, target):
    """fuzz/gitrev.py (seed 3641): `lint --diff-base REV --config-from REV` where REV's model is a link out of the
    checkout (git keeps it; the base revision's copy leaves it out) and REV's config names that model: the config
    error said "no such file: /abs/tmp/urdfcheck-rev-XXXX/pkg/urdf/robot.urdf"."""
    import os
    import subprocess
    import tempfile

    env = dict(os.environ, GIT_CONFIG_NOSYSTEM="1", HOME=str(tmp_path), GIT_AUTHOR_NAME="a",
               GIT_AUTHOR_EMAIL="a@b", GIT_COMMITTER_NAME="a", GIT_COMMITTER_EMAIL="a@b")
    repo = tmp_path / "r"
    (repo / "pkg" / "urdf").mkdir(parents=True)
    (repo / "pkg" / "urdf" / "robot.urdf").symlink_to(target)
    (repo / "urdfcheck.yaml").write_text("models:\n  - path: pkg/urdf/robot.urdf\n")
    for args in (["init", "-q"], ["add", "-A"], ["commit", "-q", "-m", "x"]):
        subprocess.run(["git", *args], cwd=repo, env=env, check=True, capture_output=True)
    (repo / "pkg" / "urdf" / "robot.urdf").unlink()
    (repo / "pkg" / "urdf" / "robot.urdf").write_text("<robot name='r'><link name='base_link'/></robot>\n")
    code, out, err = run_cli(["lint", "--diff-base", "HEAD", "--config-from", "HEAD"], cwd=repo)
    assert code in (1, 2), err
    assert "internal error" not in out + err
    for p in (str(tmp_path), os.path.realpath(tmp_path), tempfile.gettempdir(), "urdfcheck-rev-"):
        assert p not in out + err, (p, err)
