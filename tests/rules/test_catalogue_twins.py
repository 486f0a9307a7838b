"""The catalogues a run reads are the JSON twins of the YAML files people edit: a stale twin fails here."""
import subprocess
import sys
from pathlib import Path

import pytest

TOOL = Path(__file__).resolve().parents[2] / "tools" / "catalogues.py"


def test_every_json_twin_matches_its_yaml():
    r = subprocess.run([sys.executable, str(TOOL), "--check"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


@pytest.mark.parametrize("module, reader", [("urdfcheck.consumers.catalog", "catalogue"),
                                            ("urdfcheck.consumers.localization", "owners")])
def test_the_run_reads_what_the_yaml_says(module, reader):
    import importlib

    import yaml

    mod = importlib.import_module(module)
    source = Path(mod.__file__).parent / ("controller_types.yaml" if reader == "catalogue" else "tfowners.yaml")
    assert getattr(mod, reader)() == yaml.safe_load(source.read_text(encoding="utf-8"))
