"""The spare expands several models one after another (`expand_batch`, `xacro.batch_children`): each expansion
must find what it finds in a fresh process. Each test runs its expansions in a child (`core.worker.run`), as the
spare does, so the pytest process never runs xacro code."""
from __future__ import annotations

from pathlib import Path

import pytest

from urdfcheck.core import worker
from urdfcheck.load import loader
from urdfcheck.load.xacro import SPARE, SPARE_PRELOAD, batch_children, worker_limits
from urdfcheck.load.xacro import expand as xexpand


def _xacro(tmp_path: Path, name: str, body: str) -> str:
    p = tmp_path / name
    p.write_text('<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                 f'{body}\n</robot>\n')
    return str(p)


def _codes(out: dict) -> list:
    return [out["error"]["code"]] if out.get("error") else []


def _in_turn(jobs):
    """`expand` of each (path, Options kwargs) in turn, in one child process: their outputs."""
    return [xexpand.expand(p, xexpand.Options(**kw)) for p, kw in jobs]


BIG = "".join(f'<link name="l{i}"/>' for i in range(30))
MACROS = ('<xacro:macro name="wheel" params="side"><link name="${side}_wheel"/>'
          '<xacro:property name="seen" value="${side}" scope="global"/></xacro:macro>')


def test_the_second_expansion_has_its_own_element_budget(tmp_path):
    """Each expansion counts its elements from zero: before, the second one in a process ran the first one's
    hooks too, which kept counting on the first one's budget (a false X012 on a model that fits its own)."""
    a = _xacro(tmp_path, "a.urdf.xacro", BIG)
    b = _xacro(tmp_path, "b.urdf.xacro", BIG)
    alone = worker.run(_in_turn, [(b, {"max_evals": 40})], timeout=60)
    assert _codes(alone[0]) == []  # fits its own budget
    first, second = worker.run(_in_turn, [(a, {"max_evals": 40}), (b, {"max_evals": 40})], timeout=60)
    assert _codes(first) == [] and _codes(second) == []
    assert second["xml"] == alone[0]["xml"]


def test_what_a_model_defines_does_not_reach_the_next_one(tmp_path):
    """A global property, a macro and an argument of the first model are unknown to the second, and its
    warnings, markers and included files are its own."""
    a = _xacro(tmp_path, "a.urdf.xacro", MACROS + '<xacro:arg name="side" default="left"/>'
               '<xacro:wheel side="$(arg side)"/><xacro:include filename="missing_in_b.xacro"/>')
    b = _xacro(tmp_path, "b.urdf.xacro", '<link name="${seen}"/><xacro:wheel side="right"/>')
    (tmp_path / "missing_in_b.xacro").write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>')
    alone = worker.run(_in_turn, [(b, {})], timeout=60)[0]
    first, second = worker.run(_in_turn, [(a, {"mappings": {"side": "rear"}}), (b, {})], timeout=60)
    assert _codes(first) == [] and "rear_wheel" in first["xml"]
    assert second == alone
    assert _codes(second) == ["X010"]  # `seen` is undefined there, as in a fresh process


def test_xacro_module_state_is_put_back_after_an_expansion(tmp_path):
    def state_after(path):
        import sys

        import xacro
        from xacro import substitution_args as subst

        def names():
            return {n: getattr(xacro, n) for n in xexpand._PATCHED if n != "_global_symbols"} | \
                {n: getattr(subst, n) for n in xexpand._PATCHED_SUBST if hasattr(subst, n)} | {"stderr": sys.stderr}

        before = names()
        xexpand.expand(path, xexpand.Options())
        after = names()
        return [n for n in before if before[n] is not after[n]]

    p = _xacro(tmp_path, "a.urdf.xacro", MACROS + '<xacro:wheel side="left"/>')
    assert worker.run(state_after, p, timeout=60) == []


@pytest.mark.parametrize("children", [0, 1])
def test_a_batch_expanded_in_the_spare_finds_what_lone_expansions_find(tmp_path, monkeypatch, children):
    """With no idle core the spare expands the whole batch itself (no child: a fork and an exit less per model);
    with one, the first model goes to a child. Either way each outcome is the lone expansion's, and the spare
    delivered them (no fallback to lone expansions)."""
    import urdfcheck.load.xacro as xacro_pkg

    monkeypatch.setattr(xacro_pkg, "batch_children", lambda n: min(children, n - 1))  # the spare inherits it
    paths = [_xacro(tmp_path, "a.urdf.xacro", MACROS + '<xacro:wheel side="left"/>'),
             _xacro(tmp_path, "b.urdf.xacro", '<link name="${seen}"/>'),
             _xacro(tmp_path, "c.urdf.xacro", BIG)]
    worker.keep_spare(SPARE, worker_limits(False, (), loader.XACRO_TIMEOUT), SPARE_PRELOAD)
    try:
        batch = loader.Batch()
        pending = [loader.begin(p, batch=batch) for p in paths]
        assert len(batch.items) == 3
        batch.send()
        got = [p.result() for p in pending]
        assert batch._batch() is not None  # the spare answered for all three
    finally:
        worker.drop_spares()
    for p, exp in zip(paths, got):
        lone = loader.expand(p)
        assert (exp.text, exp.files, exp.findings) == (lone.text, lone.files, lone.findings), p
    assert [f.code for f in got[1].findings] == ["X010"]


def test_children_only_for_idle_cores(monkeypatch):
    import os

    for cores, n, expected in ((1, 3, 0), (2, 2, 0), (2, 4, 0), (3, 2, 1), (4, 4, 2), (8, 4, 3), (8, 1, 0)):
        monkeypatch.setattr(os, "sched_getaffinity", lambda pid, c=cores: set(range(c)))
        assert batch_children(n) == expected, (cores, n)


def test_xacro_is_imported_without_its_command_line():
    """The worker imports xacro without xacro.cli (optparse, textwrap): the stand-in's process_args still reaches
    the real one, and the stand-in leaves no trace in sys.modules. In a fresh interpreter (pytest imports
    textwrap itself)."""
    import subprocess
    import sys

    code = """
import sys
from urdfcheck.load.xacro.xacroimport import xacro
before = sorted(m for m in ("optparse", "textwrap", "xacro.cli") if m in sys.modules)
opts, _ = xacro.process_args(["robot.urdf.xacro", "a:=1"])
print(before, "optparse" in sys.modules, getattr(sys.modules.get("xacro.cli"), "_stand_in", False))
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.stdout.split("\n")[-2] == "[] True False", out.stdout + out.stderr
