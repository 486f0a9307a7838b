"""core/progress: a status line on a terminal's stderr while targets are checked; nothing otherwise."""
from __future__ import annotations

import io
import os

from conftest import REPO, run_cli

from urdfcheck.core import progress


class Terminal(io.StringIO):
    def isatty(self):
        return True


def test_progress_on_a_terminal(monkeypatch):
    monkeypatch.setattr(progress, "DELAY", 0.0)
    monkeypatch.setattr(progress, "INTERVAL", 0.0)
    term = Terminal()
    progress.to_terminal(term)
    for i in range(3):
        progress.step(i, 3, f"model{i}.urdf")
    progress.close()
    text = term.getvalue()
    assert "urdfcheck: 0/3 checked; model0.urdf" in text and "2/3 checked; model2.urdf" in text
    assert text.endswith("\r\x1b[K")  # erased before the report


def test_nothing_when_not_a_terminal_or_quick(monkeypatch):
    pipe = io.StringIO()
    progress.to_terminal(pipe)
    progress.step(0, 1, "m")
    progress.close()
    assert pipe.getvalue() == ""
    term = Terminal()
    progress.to_terminal(term)  # a short run: under DELAY, nothing
    progress.step(0, 1, "m")
    progress.close()
    assert term.getvalue() == ""
    progress.to_terminal(None)  # --quiet
    progress.step(0, 1, "m")


def test_lint_reports_each_target(monkeypatch):
    """A lint of the AGV package (three targets) through the CLI: one step per target, stderr only."""
    monkeypatch.setattr(progress, "DELAY", 0.0)
    monkeypatch.setattr(progress, "INTERVAL", 0.0)
    seen = []
    monkeypatch.setattr(progress, "to_terminal", lambda stream: seen.append(("quiet", stream is None)))
    monkeypatch.setattr(progress, "step", lambda done, total, label: seen.append((done, total, str(label))))
    code, out, err = run_cli(["lint", str(REPO / "examples" / "agv")])
    assert code == 0, err
    steps = [s for s in seen if s[0] != "quiet"]
    assert [s[:2] for s in steps] == [(i, len(steps)) for i in range(len(steps))] and len(steps) >= 3
    assert seen[0] == ("quiet", False)
    code, out, err = run_cli(["lint", "--quiet", str(REPO / "examples" / "agv")])
    assert ("quiet", True) in seen


def test_a_terminal_of_no_width_still_shows_the_line(monkeypatch):
    """A pseudo-terminal whose size was never set reports 0 columns (`script`, some CI runners)."""

    monkeypatch.setattr(progress, "DELAY", 0.0)
    monkeypatch.setattr(progress, "INTERVAL", 0.0)
    monkeypatch.setattr(os, "get_terminal_size", lambda fd: os.terminal_size((0, 0)))
    term = Terminal()
    term.fileno = lambda: 2
    progress.to_terminal(term)
    progress.step(0, 2, "robot.urdf")
    progress.close()
    assert "urdfcheck: 0/2 checked; robot.urdf" in term.getvalue()


def test_the_line_names_targets_as_the_report_does(monkeypatch, tmp_path):
    monkeypatch.setattr(progress, "DELAY", 0.0)
    seen = []
    monkeypatch.setattr(progress, "step", lambda done, total, label: seen.append(str(label)))
    monkeypatch.chdir(REPO / "examples")
    code, out, err = run_cli(["lint", str(REPO / "examples" / "agv")])
    assert code == 0, err
    assert seen and all(not os.path.isabs(s) and s.startswith("agv/") for s in seen), seen


def test_a_later_pass_counts_on(monkeypatch):
    """The libraries no model included are linted in a second pass: the count goes on, it does not restart."""
    monkeypatch.setattr(progress, "DELAY", 0.0)
    monkeypatch.setattr(progress, "INTERVAL", 0.0)
    term = Terminal()
    progress.to_terminal(term)
    progress.step(1, 2, "robot.urdf.xacro")
    with progress.after(2):
        progress.step(0, 1, "lib.xacro")
    progress.step(0, 1, "other.urdf")
    progress.close()
    text = term.getvalue()
    assert "2/3 checked; lib.xacro" in text and "0/1 checked; other.urdf" in text
