"""Each fact written once: every flag declared once with the request field it fills (cli/options.py), the choices
and the schemas' enums from one list each, one list of launch-file endings, and every entry point (CLI, API,
pytest plugin, ament, pre-commit) making the same request from the same options."""
from __future__ import annotations

import json
import re

import pytest
from conftest import REPO, run_cli

import urdfcheck
from urdfcheck.cli import options

ROS1 = REPO / "tests" / "fixtures" / "ros1"


def _lint_parser():
    from urdfcheck.cli.main import build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    return sub.choices


def test_every_option_of_every_command_is_declared_in_the_table():
    """A flag added by hand to a parser (not through the table) would be missing from the cache's and bag's
    lists of flags that take a value: it is caught here."""
    declared = {f for o in options.OPTIONS for f in o.flags}
    for command, parser in _lint_parser().items():
        if command != "lint":  # the command the cache and `bag` read words of
            continue
        for action in parser._actions:
            for flag in action.option_strings:
                assert flag in declared or flag in ("-h", "--help"), (command, flag)


def test_the_table_says_which_flags_take_a_value_as_argparse_does():
    lint = _lint_parser()["lint"]
    for action in lint._actions:
        for flag in action.option_strings:
            if flag in ("-h", "--help"):
                continue
            assert (flag in options.valued_flags("lint")) == (action.nargs != 0), flag
            assert (flag in options.plain_flags("lint")) == (action.nargs == 0), flag


def test_every_field_an_option_fills_is_a_request_field():
    from urdfcheck.request.request import LintRequest

    for o in options.OPTIONS:
        assert o.field is None or o.field in LintRequest._fields, o.flags


@pytest.mark.parametrize("schema, path", [
    ("config", ("properties", "target", "enum")),
    ("config", ("properties", "profiles", "items", "enum")),
])
def test_schema_enums_are_the_lists_the_cli_takes(schema, path):
    data = json.loads((REPO / "src" / "urdfcheck" / "schemas" / f"{schema}.schema.json").read_text())
    node = data
    for key in path:
        node = node[key]
    assert tuple(node) == options.choices("targets" if "target" in path else "profiles")


def _enums(node, key, out):
    if isinstance(node, dict):
        for k, v in node.items():
            if k == key and isinstance(v, dict) and "enum" in v:
                out.append(tuple(v["enum"]))
            elif k == key and isinstance(v, dict) and "items" in v and "enum" in v["items"]:
                out.append(tuple(v["items"]["enum"]))
            _enums(v, key, out)
    elif isinstance(node, list):
        for v in node:
            _enums(v, key, out)
    return out


@pytest.mark.parametrize("schema", ["config", "report"])
def test_every_severity_and_profile_enum_of_the_schemas_is_the_one_list(schema):
    data = json.loads((REPO / "src" / "urdfcheck" / "schemas" / f"{schema}.schema.json").read_text())
    severities = _enums(data, "severity", []) + _enums(data, "fail_on", [])
    assert severities and all(set(e) == set(options.choices("severities")) for e in severities)
    profiles = _enums(data, "profile", []) + _enums(data, "profiles", [])
    assert profiles and all(e == options.choices("profiles") for e in profiles)


def test_lint_format_and_target_choices_come_from_the_lists():
    from urdfcheck.report import FORMATS

    lint = _lint_parser()["lint"]
    by_dest = {a.dest: a for a in lint._actions}
    assert tuple(by_dest["format"].choices) == tuple(FORMATS)
    assert tuple(by_dest["target"].choices) == options.choices("targets")
    for name in options.choices("profiles"):  # --profile takes a comma-separated list: its help names them all
        assert name in by_dest["profile"].help


# --- every --format: the list its renderer declares ---------------------------------------------------------

TINY = """<robot name="r"><link name="a"/><link name="b"/>
<joint name="j" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0 0 1"/><axis xyz="0 0 1"/>
<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>"""


def _rules(fmt):
    from urdfcheck.rules import docs

    return docs.listing(fmt)


def _consumers(fmt):
    from urdfcheck.cli.consumers import render

    return render(fmt, "robot.urdf", [], [])


def _diff(fmt):
    from urdfcheck.diff.compare import DiffResult, Pair
    from urdfcheck.report.diff import render

    return render(fmt, DiffResult("HEAD", "working tree", [Pair("urdf/r.urdf", "", "added")]))


def _tree(fmt):
    from urdfcheck.model.build import model_from_string
    from urdfcheck.publisher.tree_view import render

    return render(model_from_string(TINY), fmt)


def _tf(fmt):
    from urdfcheck.cli.publish import render_tf

    return render_tf(fmt, "a", "b", {"j": 0.5}, [[1.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, 1.0, 1.0], [0, 0, 0, 1.0]])


def _verify(fmt):
    from urdfcheck.cli.publish import render_verify
    from urdfcheck.verify.compare import VerifyReport

    return render_verify(fmt, VerifyReport("r", "robot.urdf", 10, 0, 1e-9, ["j"]))


def _lint(fmt):
    from urdfcheck.finish.result import Result
    from urdfcheck.report import render

    return render(fmt, Result([], []))


# command -> (module, name of the renderer's list, one render per format)
RENDERERS = {
    "rules": ("urdfcheck.rules.docs", "FORMATS", _rules),
    "consumers": ("urdfcheck.cli.consumers", "FORMATS", _consumers),
    "diff": ("urdfcheck.report.diff", "FORMATS", _diff),
    "tree": ("urdfcheck.publisher.tree_view", "FORMATS", _tree),
    "tf": ("urdfcheck.cli.publish", "TF_FORMATS", _tf),
    "verify": ("urdfcheck.cli.publish", "VERIFY_FORMATS", _verify),
    "lint": ("urdfcheck.report", "FORMATS", _lint),
}


def test_every_command_with_a_format_has_its_renderer_listed_here():
    with_format = {c for c, p in _all_parsers().items() if any(a.dest == "format" for a in p._actions)}
    assert with_format == set(RENDERERS)


def _all_parsers():
    from urdfcheck.cli.main import build_parser

    sub = next(a for a in build_parser()._actions if a.dest == "command")
    return sub.choices


@pytest.mark.parametrize("command", sorted(RENDERERS))
def test_format_choices_are_what_the_renderer_renders(command):
    """The CLI offers exactly the renderer's list; each format in it is rendered (each differently: none falls back
    to another), and a format outside it is refused by the renderer, so no format is rendered but not offered."""
    import importlib

    module, name, render = RENDERERS[command]
    formats = tuple(getattr(importlib.import_module(module), name))
    by_dest = {a.dest: a for a in _all_parsers()[command]._actions}
    assert tuple(by_dest["format"].choices) == formats
    outputs = {fmt: render(fmt) for fmt in formats}
    assert all(isinstance(o, str) and o for o in outputs.values()), outputs
    assert len(set(outputs.values())) == len(formats), outputs
    with pytest.raises(ValueError):
        render("no-such-format")


# --- the bugs of issue 42 ------------------------------------------------------------------------------------

def test_bag_takes_every_lint_option_with_a_value(tmp_path):
    """`urdfcheck bag MODEL REC --profile mujoco` read `mujoco` as a second recording (exit 2)."""
    code, out, err = run_cli(["bag", str(ROS1 / "robot.urdf"), str(ROS1 / "clean.bag"), "--profile", "mujoco",
                              "--format", "json"], cwd=tmp_path)
    assert code in (0, 1), err
    assert json.loads(out)["findings"] is not None


def test_bag_argv_reads_every_valued_flag_as_taking_its_value():
    from urdfcheck.cli.main import bag_argv

    for flag in options.valued_flags("lint"):
        argv = bag_argv(["model.urdf", "rec.bag", flag, "VALUE"])
        assert argv[:2] == ["lint", "model.urdf"], (flag, argv)
        assert argv[argv.index(flag) + 1] == "VALUE" and argv[argv.index("rec.bag") - 1] == "--bag", (flag, argv)


def test_consumers_takes_no_config(tmp_path):
    """The README says consumers takes `--config FILE` / `--no-config`: it was an unrecognized argument."""
    for extra in (["--no-config"], ["--config", str(tmp_path / "urdfcheck.yaml")]):
        (tmp_path / "urdfcheck.yaml").write_text("fail_on: error\n")
        code, out, err = run_cli(["consumers", str(ROS1 / "robot.urdf"), "--consumer", "urdfdom", *extra],
                                 cwd=tmp_path)
        assert "unrecognized" not in err and code in (0, 1), (extra, code, err)


def test_every_command_that_loads_a_model_takes_the_config_options():
    for command, parser in _lint_parser().items():
        flags = {f for a in parser._actions for f in a.option_strings}
        if {"--arg", "--package"} <= flags:
            assert {"--config", "--no-config"} <= flags, command


def test_publish_ros_flag_and_its_deprecated_spelling(tmp_path, capsys):
    for flag in ("--ros", "--profile"):
        code, out, err = run_cli(["tree", str(ROS1 / "robot.urdf"), flag, "ros1", "--format", "json"], cwd=tmp_path)
        assert code == 0, err
        assert ("deprecated" in err) == (flag == "--profile"), err


# --- launch-file endings: one list ---------------------------------------------------------------------------

def test_every_reader_of_launch_files_knows_every_ending():
    import yaml

    from urdfcheck.finish.collapse import _LAUNCH
    from urdfcheck.load.discover import LAUNCH_SUFFIXES
    from urdfcheck.plan import deployments, plan

    hooks = yaml.safe_load((REPO / ".pre-commit-hooks.yaml").read_text())
    for suffix in LAUNCH_SUFFIXES:
        name = "launch/bot" + suffix
        assert plan._is_launch(name) and deployments._is_launch(name), suffix
        assert _LAUNCH.search(name), suffix
        for hook in hooks:
            assert re.search(hook["files"], name), (hook["id"], suffix)


STATIC_ONLY = """from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        Node(package="tf2_ros", executable="static_transform_publisher",
             arguments=["0", "0", "0.1", "0", "0", "0", "base_link", "laser"]),
    ])
"""


@pytest.mark.parametrize("name", ["bot.launch.py", "bot_launch.py"])
def test_zero_config_launch_file_named_either_way_is_read(tmp_path, name):
    """`bot_launch.py` (no robot_state_publisher in it: the package's consumers, found by the package walk) hid
    the T001 error that `bot.launch.py` reports in a zero-config package."""
    from conftest import lint_json
    from test_tf_owners import URDF, write

    root = write(tmp_path / "bot", {"package.xml": "<package format='3'><name>bot</name></package>\n",
                                    "urdf/bot.urdf": URDF.format(extra=""), "launch/" + name: STATIC_ONLY})
    _, report = lint_json(["--select", "T,X"], cwd=root)
    found = [(f["code"], f["location"]["file"]) for f in report["findings"]]
    assert found == [("T001", "launch/" + name)], found


# --- every entry point makes the same request from the same options -----------------------------------------

XACRO = """<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="size" default="1"/>
  <link name="base_link"><visual><geometry><box size="$(arg size) 1 1"/></geometry></visual></link>
</robot>
"""


@pytest.fixture
def pkg(tmp_path):
    root = tmp_path.resolve() / "bot"
    (root / "urdf").mkdir(parents=True)
    (root / "package.xml").write_text("<package format='3'><name>bot</name></package>\n")
    (root / "urdf" / "bot.urdf.xacro").write_text(XACRO)
    (root / "other.yaml").write_text("ignore: [S]\n")
    (root / "base.json").write_text(json.dumps({"version": 1, "findings": []}))
    return root


@pytest.fixture
def requests(monkeypatch):
    """The requests handed to the pipeline (run.run), each run going on as usual."""
    import urdfcheck.run as pipeline

    seen = []
    real = pipeline.run

    def recording(request, *a, **kw):
        seen.append(request)
        return real(request, *a, **kw)

    monkeypatch.setattr(pipeline, "run", recording)
    return seen


def _same(a, b, skip=()):
    fa = {k: getattr(a, k) for k in a._fields if k not in skip}
    fb = {k: getattr(b, k) for k in b._fields if k not in skip}
    assert fa == fb


def test_cli_api_ament_and_pre_commit_make_one_request(pkg, requests, monkeypatch):
    from urdfcheck.cli import ament

    monkeypatch.chdir(pkg)
    words = ["--fail-on", "error", "--config", "other.yaml", "--arg", "size:=2", "--package", f"bot={pkg}"]
    code, _, err = run_cli(["lint", *words, "."], cwd=pkg)
    assert code in (0, 1), err
    cli = requests[-1]
    urdfcheck.lint(["."], args={"size": "2"}, fail_on="error", config="other.yaml", packages={"bot": str(pkg)})
    _same(requests[-1], cli)
    assert ament.main([".", *words]) in (0, 1)
    _same(requests[-1], cli)
    import yaml

    for hook in yaml.safe_load((REPO / ".pre-commit-hooks.yaml").read_text()):
        entry = hook["entry"].split()
        assert entry[0] == "urdfcheck"
        staged = ["urdf/bot.urdf.xacro"] if hook.get("pass_filenames", True) else []
        code, _, err = run_cli(entry[1:] + words + staged, cwd=pkg)
        assert code in (0, 1), err
        _same(requests[-1], cli, skip=("paths",))
    # the options only lint and the API take
    more = ["--trusted", "--allow-env", "HOME", "--timeout", "7", "--max-elements", "900", "--budget", "50",
            "--select", "S,J", "--ignore", "J002", "--target", "jazzy", "--profile", "mujoco,kdl", "--root", str(pkg),
            "--baseline", "base.json", "--max-files", "99", "--no-config"]
    run_cli(["lint", *words, *more, "."], cwd=pkg)
    cli = requests[-1]
    urdfcheck.lint(["."], args={"size": "2"}, fail_on="error", config="other.yaml", packages={"bot": str(pkg)},
                   trusted=True, allow_env=["HOME"], timeout=7.0, max_elements=900, budget=50.0, select=["S", "J"],
                   ignore=["J002"], target="jazzy", profiles="mujoco,kdl", root=str(pkg), baseline="base.json",
                   max_files=99, use_config=False)
    _same(requests[-1], cli)


def test_pytest_plugin_makes_the_request_lint_makes(pkg, requests, monkeypatch, capsys):
    ini = pkg / "pytest.ini"
    ini.write_text("[pytest]\n")
    monkeypatch.setenv("PYTEST_DISABLE_PLUGIN_AUTOLOAD", "1")
    monkeypatch.chdir(pkg)
    code = pytest.main(["-p", "urdfcheck.pytest_plugin", "-p", "no:cacheprovider", "--urdfcheck",
                        "--urdfcheck-fail-on", "error", "--urdfcheck-baseline", "base.json", "-c", str(ini),
                        "--rootdir", str(pkg), "-q", "-m", "urdfcheck", "-p", "no:randomly", str(pkg)])
    capsys.readouterr()
    assert code in (0, 1), code
    plugin = requests[-1]
    # the plugin reads the baseline from the rootdir (pytest may run from elsewhere): lint given that file
    run_cli(["lint", "--fail-on", "error", "--baseline", str(pkg / "base.json"), "--root", str(pkg)], cwd=pkg)
    _same(plugin, requests[-1])
