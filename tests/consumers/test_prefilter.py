"""contracts/prefilter: a parameter file is skipped only when no value it holds can be a joint name we look for.

The superset test reads every YAML file of the corpus and the examples: for each string value the parser finds
(each joint name that would keep the file in `consumers.openworld.names_a_joint`), the byte filter must pass the
file."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from conftest import CORPUS, REPO

from urdfcheck.consumers.consumers import _names_a_joint
from urdfcheck.consumers.params import parse_params
from urdfcheck.consumers.prefilter import may_name, worth_parsing


def _yaml_files() -> list[Path]:
    roots = [REPO / "examples"] + ([CORPUS] if CORPUS.is_dir() else [])
    out = []
    for root in roots:
        out.extend(p for p in root.rglob("*") if p.suffix.lower() in (".yaml", ".yml") and p.is_file())
    return sorted(out)


def _strings(value):
    if isinstance(value, str):
        yield value
    elif isinstance(value, list):
        for v in value:
            if isinstance(v, str):
                yield v


def test_every_accepted_file_passes():
    files = _yaml_files()
    assert len(files) > 10
    checked = 0
    for path in files:
        data = path.read_bytes()
        try:
            pf = parse_params(data, str(path))
        except Exception:  # noqa: BLE001 - unreadable files are dropped by the reader in any case
            continue
        values = {s for node in pf.nodes.values() for v in node.params.values() for s in _strings(v.value)}
        for name in values:
            assert _names_a_joint(pf, {name}), (path, name)  # the reader keeps the file for this joint...
            assert may_name(data, [name]), (path, name)  # ...so the filter must pass it
            checked += 1
        if values:
            assert worth_parsing(path, sorted(values)[:1])
    assert checked > 100


def test_corpus_files_present_when_corpus_is():
    if not CORPUS.is_dir():
        pytest.skip("shared corpus not present")
    assert len(_yaml_files()) > 200


@pytest.mark.parametrize("text, names, expected", [
    (b"a: {joints: [left_wheel, right_wheel]}\n", ["left_wheel"], True),
    (b"a: {joints: [left_wheel, right_wheel]}\n", ["caster"], False),
    (b'a: "left\\x5fwheel"\n', ["left_wheel"], True),  # an escape: the bytes cannot tell
    (b"\xff\xfea\x00:\x00", ["x"], True),  # UTF-16
    (b"a: b\n", ["two words"], True),  # a folded plain scalar can write it across lines
    (b"a: b\n", ["it's"], True),  # 'it''s'
    (b"a: b\n", [], False),
    (b"a: b\n", [""], True),
])
def test_may_name(text, names, expected):
    assert may_name(text, names) is expected


def test_unreadable_or_huge_file_is_left_to_the_reader(tmp_path):
    assert worth_parsing(tmp_path / "missing.yaml", ["j"])
    big = tmp_path / "big.yaml"
    big.write_bytes(b"a: 1\n" * 500_000)
    assert worth_parsing(big, ["j"])


def test_package_of_many_models_does_not_import_pyyaml(tmp_path):
    """Two models in one package, a parameter file that names no joint of the linted one: PyYAML is never
    imported (the file would be dropped after parsing anyway), and the findings are those of before."""
    (tmp_path / "package.xml").write_text("<package><name>two</name></package>")
    (tmp_path / "urdf").mkdir()
    for name in ("a", "b"):
        (tmp_path / "urdf" / f"{name}.urdf").write_text(
            f'<robot name="{name}"><link name="base"/><link name="l1"/>'
            f'<joint name="{name}_j" type="fixed"><parent link="base"/><child link="l1"/></joint></robot>')
    (tmp_path / "config").mkdir()
    (tmp_path / "config" / "other.yaml").write_text("moveit:\n  planner: RRT\n  joints: [b_j]\n")
    code = ("import sys\nfrom urdfcheck.cli.main import main\n"
            "rc = main(['lint', '--no-config', 'urdf/a.urdf'])\n"
            "print('yaml' in sys.modules, file=sys.stderr); sys.exit(rc)")
    proc = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert proc.returncode in (0, 1), proc.stderr
    assert proc.stderr.strip().splitlines()[-1] == "False", proc.stderr
