"""The fast path of the model build (fastbuild.py) must give exactly what the careful builder gives."""
import random
import re
import sys
from pathlib import Path

import pytest

from urdfcheck.model import build as buildmod
from urdfcheck.model import fastbuild
from urdfcheck.core import xmlfront
from urdfcheck.core.findings import Location

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))
from gen_urdf import generate  # noqa: E402

BASE = generate(12, seed=3)

# one edit each: the irregular ones must reach the careful builder (issues), the regular ones must not differ
EDITS = [
    ('rpy="0 0 0"', 'rpi="0 0 0"'),
    ('rpy="0 0 0"', 'rpy="0 nan 0"'),
    ('rpy="0 0 0"', 'rpy="0 1_0 0"'),
    ('rpy="0 0 0"', 'rpy="0 0"'),
    ('rpy="0 0 0"', 'rpy=" +1e-3  .5\t5. "'),
    ('rpy="0 0 0"', 'rpy="1e308 1e308 1e308"'),
    ('rpy="0 0 0"', 'rpy="0x1 0 0"'),
    ('ixy="0"', 'ixy="x"'),
    ('ixy="0"', ''),
    ('ixy="0"', 'ixy="1e400"'),
    ("<mass value", '<mass foo="1" value'),
    ("<mass value", '<mass __ucsrc="0:3" value'),
    ("<visual>", '<visual name="v">'),
    ("<visual>", "<visual><!-- c -->"),
    ("<collision>", "<collision><verbose/>"),
    ("<collision>", '<collision><material name="x"/>'),
    ("</inertial>", '<mass value="2"/></inertial>'),
    ("</inertial>", "</inertial><inertial/>"),
    ("<inertial>", "<inertial><foo/>"),
    ('<material name="grey"/>', '<material name="grey"><color rgba="1 0 0 1"/></material>'),
    ('<material name="grey"/>', '<material name="grey"><color rgba="1 0 0"/></material>'),
    ('<material name="grey"/>', '<material name="grey"><texture filename="a.png"/></material>'),
    ('<material name="grey"/>', '<material name="grey"><texture/></material>'),
    ('<material name="grey"/>', "<material/>"),
    ('<material name="grey"/>', '<material name=""/>'),
    ("<box size=", '<box extra="1" size='),
    ("</geometry>", '<sphere radius="1"/></geometry>'),
    ("</geometry>", '<x:y xmlns:x="urn:x"/></geometry>'),
    (re.compile(r'<box size="[^"]*"/>'), '<mesh filename="package://a/b.stl" scale="1 2 3"/>'),
    (re.compile(r'<box size="[^"]*"/>'), '<mesh filename=""/>'),
    (re.compile(r'<box size="[^"]*"/>'), '<sphere radius="0.1"/>'),
    (re.compile(r'<box size="[^"]*"/>'), '<capsule radius="0.1" length="1"/>'),
    (re.compile(r'<box size="[^"]*"/>'), '<cone radius="0.1"/>'),
    (re.compile(r'<box size="[^"]*"/>'), ""),
    ("<origin ", "<origin><x/></origin><o "),
    ("<origin xyz", '<origin xmlns:q="urn:q" q:a="1" xyz'),
    ('<link name="link_0001"', '<link name="link_0001" type="x"'),
    ('<link name="link_0001">', '<link name="link_0001"><self_collision_checking/>'),
    ('<link name="link_0001">', '<link name="link_0001"><contact><lateral_friction value="1"/></contact>'),
    ('<link name="link_0001"', "<link"),
    (' type="revolute"', ""),
    (re.compile(r'<parent link="[^"]*"/>'), ""),
    (re.compile(r'<child link="[^"]*"/>'), '<child link="a" foo="b"/>'),
    (re.compile(r'<axis xyz="[^"]*"/>'), "<axis/>"),
    (re.compile(r'<axis xyz="[^"]*"/>'), '<axis xyz="0 0 1"><!--c--></axis>'),
    (re.compile(r' effort="[^"]*"'), ""),
    (re.compile(r' lower="[^"]*"'), ""),
    (re.compile(r' velocity="[^"]*"'), ' velocity="-inf"'),
    ("</joint>", '<mimic joint="joint_0001" multiplier="2" offset="1"/></joint>'),
    ("</joint>", '<mimic joint="j" offset="x"/></joint>'),
    ("</joint>", "<mimic/></joint>"),
    ("</joint>", '<dynamics damping="1"/><dynamics friction="2"/></joint>'),
    ("</joint>", '<calibration rising="1" falling="x"/></joint>'),
    ("</joint>", '<safety_controller k_velocity="1" k_position="2" soft_lower_limit="0"/></joint>'),
    ("</joint>", '<safety_controller k_velocity="1" foo="2"/></joint>'),
    ("</joint>", "<foo/></joint>"),
]


def _edit(text: str, edit) -> str:
    old, new = edit
    return old.sub(new, text, 1) if isinstance(old, re.Pattern) else text.replace(old, new, 1)


def _both(text: str, monkeypatch):
    root, _ = xmlfront.parse(text.encode())
    locate = lambda el: Location("r.urdf", el.sourceline)  # noqa: E731
    fast = buildmod.build(root, locate, "r.urdf")
    with monkeypatch.context() as m:
        def refuse(self, el):
            raise fastbuild.Irregular

        m.setattr(fastbuild.FastParts, "link", refuse)
        m.setattr(fastbuild.FastParts, "joint", refuse)
        careful = buildmod.build(root, locate, "r.urdf")
    return fast, careful


def test_generated_model_takes_the_fast_path_whole(monkeypatch):
    calls = []
    monkeypatch.setattr(buildmod._Builder, "link", lambda self, el: calls.append(el))
    monkeypatch.setattr(buildmod._Builder, "joint", lambda self, el: calls.append(el))
    root, _ = xmlfront.parse(BASE.encode())
    model = buildmod.build(root, lambda el: Location("r.urdf", el.sourceline), "r.urdf")
    assert calls == [] and len(model.link_list) == 12 and len(model.joint_list) == 11


@pytest.mark.parametrize("edit", EDITS, ids=lambda e: str(e[1])[:40])
def test_fast_and_careful_builds_agree(edit, monkeypatch):
    text = _edit(BASE, edit)
    assert text != BASE
    fast, careful = _both(text, monkeypatch)
    assert fast == careful and repr(fast) == repr(careful)


def test_fast_and_careful_builds_agree_on_combined_edits(monkeypatch):
    rng = random.Random(7)
    for _ in range(60):
        text = BASE
        for edit in rng.sample(EDITS, 3):
            text = _edit(text, edit)
        fast, careful = _both(text, monkeypatch)
        assert fast == careful and repr(fast) == repr(careful), text
