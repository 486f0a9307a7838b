"""Recordings made by ROS 2 itself (rosbag2's own test resources, tests/fixtures/ros2/SOURCES.md): sqlite3 and
MCAP, metadata versions 4 to 8, zstd file and message compression, split files. None has JointState or TF
messages: every message is counted as the metadata says, other types are skipped, and a check of a model says that
nothing of it was compared."""
import json
import os
import shutil
from collections import Counter
from pathlib import Path

import pytest
from conftest import run_cli

FIXTURES = Path(__file__).parent.parent / "fixtures" / "ros2"
FOLDERS = ("talker_sqlite3", "talker_mcap", "cdr_test_sqlite3", "cdr_test_mcap", "service_events_mcap",
           "empty_sqlite3", "file_compression")
MODEL = Path(__file__).parent.parent / "fixtures" / "ros1" / "robot.urdf"


@pytest.fixture(autouse=True)
def _fixtures():
    if not (FIXTURES / "talker_mcap" / "metadata.yaml").exists():
        pytest.skip("tests/fixtures/ros2 is absent")


def _read(path: Path) -> tuple[dict, Counter]:
    from urdfcheck.bag import source
    from urdfcheck.bag.inflate import Inflater
    from urdfcheck.core import door

    facts: dict = {}
    counts: Counter = Counter()
    with door.guarded([str(FIXTURES.resolve())], 1 << 30):
        for part in source._parts(str(path.resolve()), True, facts):
            for topic, _typ, _t, _payload, _caller, cdr in part.messages(lambda t, ty: True, Inflater()):
                assert cdr
                counts[topic] += 1
    return facts, counts


def _metadata(folder: Path) -> dict:
    from urdfcheck.core.yamlimport import yaml

    return yaml.safe_load((folder / "metadata.yaml").read_text())["rosbag2_bagfile_information"]


@pytest.mark.parametrize("name", FOLDERS)
def test_every_message_as_the_metadata_counts(name):
    folder = FIXTURES / name
    info = _metadata(folder)
    facts, counts = _read(folder)
    assert facts["ros"] == 2
    declared = {t["topic_metadata"]["name"]: t["topic_metadata"]["type"] for t in info["topics_with_message_count"]}
    assert facts["topics"] == declared
    expected = {t["topic_metadata"]["name"]: t["message_count"] for t in info["topics_with_message_count"]
                if t["message_count"]}
    assert dict(counts) == expected
    assert sum(counts.values()) == info["message_count"]


def test_versions_and_compression_covered():
    infos = [_metadata(FIXTURES / n) for n in FOLDERS]
    assert {i["version"] for i in infos} >= {4, 7, 8}
    assert {i["storage_identifier"] for i in infos} == {"sqlite3", "mcap"}
    assert any(i.get("compression_mode") == "FILE" for i in infos)
    assert all(t["topic_metadata"]["offered_qos_profiles"] for i in infos for t in i["topics_with_message_count"])


def test_message_compression():
    # the last split of a "message"-compressed recording, alone: every payload a zstd frame
    facts, counts = _read(FIXTURES / "message_compression_3.db3")
    assert facts["ros"] == 2
    assert counts == {"/topic": 9, "/rosout": 18}


@pytest.mark.parametrize("name", FOLDERS + ("message_compression_3.db3",))
def test_nothing_of_the_model_compared(name, tmp_path):
    shutil.copyfile(MODEL, tmp_path / "robot.urdf")
    src = FIXTURES / name
    dst = tmp_path / name
    (shutil.copytree if src.is_dir() else shutil.copyfile)(src, dst)
    code, out, err = run_cli(["bag", "robot.urdf", os.path.relpath(dst, tmp_path), "--format", "json",
                              "--no-config"], cwd=tmp_path)
    assert code == 1, err
    findings = json.loads(out)["findings"]
    assert [f["code"] for f in findings] == ["B015"], findings
    assert "nothing was checked" in findings[0]["message"]
