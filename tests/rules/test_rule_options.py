"""Rule options are declared once (rules/*.yaml `options:`): the engine hands each check its options with the
catalogue defaults filled in; no check keeps a fallback of its own. And a check never changes its context:
the consumers a contract check reads are the planner's (`plan.plan.Target.consumers`), found once."""
from __future__ import annotations

import re
from pathlib import Path

from urdfcheck.rules import engine
from urdfcheck.rules.catalogue import catalogue, options_for

SRC = Path(__file__).resolve().parents[2] / "src" / "urdfcheck"


def _model(axis=(0.0, 0.0, 2.0)):
    from urdfcheck.model.build import model_from_string

    return model_from_string(
        '<robot name="r"><link name="base_link"/><link name="arm"/>'
        '<joint name="j" type="revolute"><parent link="base_link"/><child link="arm"/>'
        f'<axis xyz="{" ".join(map(str, axis))}"/><limit lower="0" upper="1" effort="1" velocity="1"/>'
        '</joint></robot>', "r.urdf")


def test_every_check_gets_the_catalogue_defaults():
    cat = catalogue()
    for code, info in cat.items():
        assert options_for((code,)) == info.options, code
    assert options_for(("J007",)) == {"tolerance": 1e-5}
    assert options_for(("C010",)) == {"tolerance": 0.001, "angle_tolerance": 0.001}
    assert options_for(("J007",), {"J007": {"tolerance": 0.5}}) == {"tolerance": 0.5}


def test_a_default_list_is_not_shared_between_runs():
    a = options_for(("F001",))
    a["frames"].append("earth")
    assert options_for(("F001",))["frames"] == ["map", "odom"]


def test_a_bad_option_from_a_hand_made_selection_is_r001_not_a_silent_default():
    sel = engine.Selection(select=("J007", "R001"), options={"J007": {"tolerance": "loose"}})
    found = engine.run_checks(_model(), engine.Context(selection=sel))
    assert [f.code for f in found] == ["R001"] and "J007.tolerance must be number" in found[0].message
    sel = engine.Selection(select=("J007", "R001"), options={"J007": {"tolerence": 0.1}})
    found = engine.run_checks(_model(), engine.Context(selection=sel))
    assert [f.code for f in found] == ["R001"] and "no option 'tolerence'" in found[0].message
    # the declared default applies when nothing is given: a length-2 axis is J007
    found = engine.run_checks(_model(), engine.Context(selection=engine.Selection(select=("J007",))))
    assert [f.code for f in found] == ["J007"]


def test_no_check_keeps_its_own_option_default():
    """`ctx.options.get(name, default)` (or `_opt(ctx, name, default)`) would be a second declaration."""
    bad = []
    for path in sorted(SRC.rglob("*.py")):  # every module: checks live in more than one folder
        for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if re.search(r"\.options\.get\(|\b_opt\(", line):
                bad.append(f"{path.relative_to(SRC)}:{n}: {line.strip()}")
    assert not bad, "\n".join(bad)


def test_checks_do_not_change_their_context(tmp_path):
    """A model in a ROS package with a controller file beside it: the contract checks find the consumers
    through the planner's target (once), and the context they ran with is unchanged."""
    from urdfcheck.plan.plan import plan
    from urdfcheck.request.request import make_request
    from urdfcheck.run import lint_targets

    pkg = tmp_path / "bot"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "config").mkdir()
    (pkg / "package.xml").write_text('<package format="3"><name>bot</name></package>\n')
    (pkg / "urdf" / "bot.urdf").write_text(
        '<robot name="bot"><link name="base_link"/><link name="wheel"/>'
        '<joint name="wheel_joint" type="continuous"><parent link="base_link"/><child link="wheel"/>'
        '<axis xyz="0 1 0"/></joint></robot>\n')
    (pkg / "config" / "controllers.yaml").write_text(
        "controller_manager:\n  ros__parameters:\n    jpc:\n      type: "
        "position_controllers/JointGroupPositionController\n"
        "jpc:\n  ros__parameters:\n    joints: [wheel_jiont]\n")
    targets = plan(make_request([str(pkg)], use_config=False))
    assert len(targets) == 1 and targets[0].contracts is None  # not read before the model is built
    result = lint_targets(list(targets))
    c001 = [f for f in result.findings if f.code == "C001"]  # the misspelt joint, from the file beside the model
    assert len(c001) == 1 and "wheel_jiont" in c001[0].message and c001[0].location.file.endswith("controllers.yaml")
    found = targets[0].contracts
    assert found is not None and found.origin == "discovered"
    assert targets[0].consumers(None) is found  # computed once, kept on the target

    # a context made by hand, without consumers: the checks look beside the model, and write nothing back
    frozen = engine.Context(selection=engine.Selection(select=("C001", "C003")))
    model = _bot_model(pkg / "urdf" / "bot.urdf")
    before = dict(vars(frozen))
    found = engine.run_checks(model, frozen)
    assert "C001" in [f.code for f in found]
    after = dict(vars(frozen))
    before.pop("options"), after.pop("options")  # the engine's own hand-over to each check
    assert before == after and frozen.contracts is None


def _bot_model(path: Path):
    from urdfcheck.model.build import model_from_string

    return model_from_string(path.read_text(), str(path))

