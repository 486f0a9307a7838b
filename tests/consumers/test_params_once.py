"""A run parses each parameter file once, though several models' consumers name it (issue 38: the CPU of a cold
lint). The AGV config declares its xacro and its plain URDF with the same controllers and driver files."""
from __future__ import annotations

import os
from pathlib import Path

from urdfcheck.consumers import yamlsrc
from urdfcheck.request.request import make_request
from urdfcheck.run import run

AGV = Path(__file__).resolve().parents[2] / "examples" / "agv"


def test_a_config_s_models_share_one_parse_of_each_parameter_file(monkeypatch):
    parsed: list[str] = []
    real = yamlsrc.load_yaml

    def counting(path, *args, **kwargs):
        parsed.append(os.path.basename(str(path)))
        return real(path, *args, **kwargs)

    monkeypatch.setattr(yamlsrc, "load_yaml", counting)
    monkeypatch.chdir(AGV)
    result = run(make_request(["."]))
    assert len(result.models) == 3 and not result.findings
    assert parsed.count("agv_controllers.yaml") == 1
    assert parsed.count("agv_driver_ros1.yaml") == 1
