"""Inputs the wave-4 fuzzers (fuzz/recordings.py, fuzz/configs.py, fuzz/gitrev.py) found, minimised: each once
leaked an absolute path or ended in a traceback, and stays fixed."""
import os
import shutil
import subprocess
from pathlib import Path

import pytest
from conftest import run_cli

FIXTURES = Path(__file__).resolve().parent.parent / "fixtures" / "ros1"


def _robot(tmp_path):
    shutil.copyfile(FIXTURES / "robot.urdf", tmp_path / "robot.urdf")


def test_dangling_link_in_a_recording_folder_names_no_absolute_path(tmp_path):
    """fuzz/recordings.py: metadata.yaml of a rosbag2 folder a link to a missing file; the B014 message quoted
    the OSError with the real path of the runner's workspace."""
    _robot(tmp_path)
    (tmp_path / "rec").mkdir()
    os.symlink("rec.bag", tmp_path / "rec" / "metadata.yaml")
    (tmp_path / "rec" / "x.db3").write_bytes(b"SQLite format 3\x00" + bytes(100))
    code, out, err = run_cli(["bag", "robot.urdf", "rec", "--no-config", "--format", "json"], cwd=tmp_path)
    assert code == 1, err
    assert "B014" in out
    for p in (str(tmp_path), os.path.realpath(tmp_path)):
        assert p not in out + err


def test_a_5000_digit_integer_in_a_yaml_recording_is_a_finding(tmp_path):
    """fuzz/recordings.py: PyYAML raised ValueError (Python's int-to-str digit limit) out of the recording
    reader: an internal error instead of B014."""
    pytest.importorskip("yaml")
    _robot(tmp_path)
    (tmp_path / "rec.yaml").write_text("- name: [arm_joint]\n  position: [1]\n  stamp: " + "9" * 5000 + "\n")
    code, out, err = run_cli(["bag", "robot.urdf", "rec.yaml", "--no-config", "--format", "json"], cwd=tmp_path)
    assert code == 1, err
    assert "B014" in out and "Traceback" not in out + err


def test_a_nul_character_in_a_config_path_is_a_config_error(tmp_path):
    """fuzz/configs.py: `models: [{path: "\\0"}]` raised ValueError (embedded null byte) out of the config
    loader."""
    (tmp_path / "robot.urdf").write_text("<robot name='r'><link name='a'/></robot>\n")
    (tmp_path / "urdfcheck.yaml").write_text('models: [{"path": "\\u0000"}]\n')
    code, out, err = run_cli(["lint"], cwd=tmp_path)
    assert code == 2
    assert "NUL" in err and "Traceback" not in out + err


@pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")
def test_diff_git_of_a_folder_without_models_names_no_absolute_path(tmp_path):
    """fuzz/gitrev.py: `diff --git REV dup` where dup holds no model said "no URDF or xacro model found in
    /abs/path/to/the/checkout/dup" (and the revision's temporary folder)."""
    env = dict(os.environ, GIT_CONFIG_NOSYSTEM="1", HOME=str(tmp_path), GIT_AUTHOR_NAME="a",
               GIT_AUTHOR_EMAIL="a@b", GIT_COMMITTER_NAME="a", GIT_COMMITTER_EMAIL="a@b")
    repo = tmp_path / "r"
    (repo / "dup").mkdir(parents=True)
    (repo / "dup" / "notes.txt").write_text("x\n")
    for args in (["init", "-q"], ["add", "-A"], ["commit", "-q", "-m", "x"]):
        subprocess.run(["git", *args], cwd=repo, env=env, check=True, capture_output=True)
    code, out, err = run_cli(["diff", "--git", "HEAD", "dup"], cwd=repo)
    assert code == 2
    assert "no URDF or xacro model found" in err
    for p in (str(tmp_path), os.path.realpath(tmp_path), "urdfcheck-rev-"):
        assert p not in out + err


@pytest.mark.parametrize("fmt", ["ros1", "mcap"])
def test_a_chunk_of_millions_of_empty_records_stops_at_the_budget(tmp_path, fmt):
    """fuzz/recordings.py: a ROS 1 chunk (bz2 or lz4, a few KB) inflating to its declared size in zeros: millions
    of empty records, read with no look at the run's budget (`--budget 3` ran for 7.5 s and then said "nothing
    was checked"). Now the budget holds inside a chunk: B014 says the budget ran out."""
    pytest.importorskip("lz4")
    pytest.importorskip("rosbags")
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "fuzz"))
    import recordings

    _robot(tmp_path)
    size = 128 * 1024**2  # 16 million empty records: far longer than a one-second budget to walk
    if fmt == "ros1":
        plain = recordings.bagwriter.write(tmp_path / "plain", "ros1", recordings._events()).read_bytes()
        rec = "rec.bag"
        (tmp_path / rec).write_bytes(recordings.ros1_rechunk(plain, "lz4", size, inner=bytes(size)))
    else:  # 14 million empty MCAP records (opcode 0, length 0)
        folder = recordings.bagwriter.write(tmp_path / "plain", "mcap", recordings._events())
        plain = next(folder.glob("*.mcap")).read_bytes()
        rec = "rec.mcap"
        (tmp_path / rec).write_bytes(recordings.mcap_rechunk(plain, "lz4", size, inner=bytes(size)))
    code, out, err = run_cli(["bag", "robot.urdf", rec, "--no-config", "--format", "json", "--budget", "1"],
                             cwd=tmp_path)
    assert code == 1, err
    assert "B014" in out and "time budget" in out


@pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")
@pytest.mark.parametrize("flags", [["--config-from", "HEAD"], ["--diff-base", "HEAD", "--config-from", "HEAD"]])
def test_config_from_a_path_leaving_the_config_folder_names_no_absolute_path(tmp_path, flags):
    """fuzz/gitrev.py: the base revision's config names `../nothere/c.yaml`; its paths are made absolute to be
    read from a temporary copy, and the error said "no such file: /abs/runner/nothere/c.yaml" (with --diff-base:
    a path in the base revision's temporary folder)."""
    env = dict(os.environ, GIT_CONFIG_NOSYSTEM="1", HOME=str(tmp_path), GIT_AUTHOR_NAME="a",
               GIT_AUTHOR_EMAIL="a@b", GIT_COMMITTER_NAME="a", GIT_COMMITTER_EMAIL="a@b")
    repo = tmp_path / "r"
    (repo / "pkg" / "urdf").mkdir(parents=True)
    (repo / "pkg" / "urdf" / "robot.urdf").write_text("<robot name='r'><link name='base_link'/></robot>\n")
    (repo / "urdfcheck.yaml").write_text("models:\n  - path: pkg/urdf/robot.urdf\n"
                                         "    controllers: [../nothere/c.yaml]\n")
    for args in (["init", "-q"], ["add", "-A"], ["commit", "-q", "-m", "x"]):
        subprocess.run(["git", *args], cwd=repo, env=env, check=True, capture_output=True)
    code, out, err = run_cli(["lint", *flags], cwd=repo)
    assert code == 2
    assert "../nothere/c.yaml" in err
    import tempfile

    for p in (str(tmp_path), os.path.realpath(tmp_path), tempfile.gettempdir() + "/nothere"):
        assert p not in out + err


def test_a_db3_whose_schema_sql_is_a_blob_is_read(tmp_path):
    """fuzz/recordings.py: a mutated .db3 whose sqlite_master holds a table's sql as a blob: TypeError
    (bytes.startswith(str)) out of the sqlite reader."""
    import sqlite3

    _robot(tmp_path)
    p = tmp_path / "rec.db3"
    c = sqlite3.connect(p)
    c.execute("CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT, type TEXT, serialization_format TEXT, "
              "offered_qos_profiles TEXT)")
    c.execute("CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER, timestamp INTEGER, data BLOB)")
    c.commit()
    c.execute("PRAGMA writable_schema = ON")
    c.execute("UPDATE sqlite_master SET sql = CAST(sql AS BLOB) WHERE name = 'messages'")
    c.commit()
    c.close()
    code, out, err = run_cli(["bag", "robot.urdf", "rec.db3", "--no-config", "--format", "json"], cwd=tmp_path)
    assert code in (0, 1), err
    assert "Traceback" not in out + err and "internal error" not in out + err
