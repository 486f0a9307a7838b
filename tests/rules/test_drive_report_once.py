"""C010-C015 read one drive report per drive, model and options: the six rules do not each compute it again
(issue 38: the CPU of a cold lint). Their findings stay each rule's own (tests/rules/test_contracts_wheels.py)."""
from __future__ import annotations

from pathlib import Path

from urdfcheck.request.request import make_request
from urdfcheck.rules.checks import contracts
from urdfcheck.run import run

AGV = Path(__file__).resolve().parents[2] / "examples" / "agv"


def test_each_drive_is_checked_once_per_model(monkeypatch):
    calls: list = []
    real = contracts.check_drive

    def counting(model, drive, **kw):
        calls.append((id(model), drive.owner))
        return real(model, drive, **kw)

    monkeypatch.setattr(contracts, "check_drive", counting)
    monkeypatch.chdir(AGV)
    result = run(make_request(["."]))
    assert len(result.models) == 3 and not result.findings
    # the controller's drive and the driver's, once each for each of the three models
    assert len(calls) == 6 and len(set(calls)) == 6
