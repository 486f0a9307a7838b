"""Issue 19: the pull request writes the configuration and chooses which files exist.

Trust comes from the person running the tool (flags, environment, API, `--config FILE --trust-config`), never from
a config found in the checkout; config paths stay in the checkout; no silent pass (robots decided from the
expansion, walks cut short said, load findings not deselectable by config, a model that did not load fails the
run); every reader bounded. Each payload below is refused quickly with a located finding or error.
"""
import json
import os
import textwrap
import time

import pytest
from conftest import run_cli

from urdfcheck.request.request import UsageError

SECRET = "ghp_FAKE_SECRET_0123456789"
XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
# refused by the sandbox (X011), evaluated by stock xacro (which then says X010): tells who evaluated it
PROBE = f'<robot name="r" {XACRO_NS}>\n  <link name="base_${{\'\'.__class__.__name__}}"/>\n</robot>\n'
LEAK = f'<robot name="r" {XACRO_NS}>\n  <link name="base_$(optenv GITHUB_TOKEN none)"/>\n</robot>\n'
BROKEN = textwrap.dedent("""\
    <robot name="r" {ns}>
      <link name="base_link"/>
      <joint name="j" type="fixed"><parent link="base_link"/><child link="missing"/></joint>
    </robot>
""").format(ns=XACRO_NS)
FORMATS = ("text", "json", "sarif", "github", "markdown", "junit")


@pytest.fixture(autouse=True)
def secrets(monkeypatch):
    monkeypatch.setenv("GITHUB_TOKEN", SECRET)
    monkeypatch.setenv("AWS_SECRET_ACCESS_KEY", SECRET)


def write(root, files: dict):
    for name, text in files.items():
        p = root / name
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text, encoding="utf-8")
    return root


def lint(root, *args):
    return run_cli(["lint", *args], cwd=root)


def codes(out: str) -> list[str]:
    return [f["code"] for f in json.loads(out)["findings"]]


# --- 1. trust comes from the runner --------------------------------------------------------------------
def _config_in(place: str, body: dict) -> dict:
    """A config holding `body` in each place a config can live, and the file to lint."""
    yaml = "".join(f"{k}: {json.dumps(v)}\n" for k, v in body.items())
    toml = "[tool.urdfcheck]\n" + "".join(f"{k} = {json.dumps(v)}\n" for k, v in body.items())
    if place == "urdfcheck.yaml":
        return {"urdfcheck.yaml": yaml}
    if place == ".urdfcheck.yaml":
        return {".urdfcheck.yaml": yaml}
    if place == "pyproject.toml":
        return {"pyproject.toml": toml}
    return {"urdfcheck.yaml": "select: [ALL]\n", "sub/urdfcheck.yaml": yaml}  # nested: wins below sub/


PLACES = ("urdfcheck.yaml", ".urdfcheck.yaml", "pyproject.toml", "nested")


def _model_path(place: str) -> str:
    return "sub/robot.urdf.xacro" if place == "nested" else "robot.urdf.xacro"


@pytest.mark.parametrize("place", PLACES)
def test_trusted_from_a_found_config_is_ignored(tmp_path, place):
    write(tmp_path, {**_config_in(place, {"trusted": True}), _model_path(place): PROBE})
    code, out, err = lint(tmp_path, "--format", "json", _model_path(place))
    found = json.loads(out)["findings"]
    assert "X011" in codes(out) and "X010" not in codes(out), found  # the sandbox evaluated it
    x018 = [f for f in found if f["code"] == "X018"]
    assert x018 and x018[0]["location"]["line"], found  # located at the key
    assert code == 1


@pytest.mark.parametrize("place", PLACES)
@pytest.mark.parametrize("fmt", FORMATS)
def test_allow_env_from_a_found_config_leaks_nothing(tmp_path, place, fmt):
    write(tmp_path, {**_config_in(place, {"allow_env": ["GITHUB_TOKEN"]}), _model_path(place): LEAK})
    code, out, err = lint(tmp_path, "--format", fmt, _model_path(place))
    assert SECRET not in out and SECRET not in err
    assert "X018" in out and code == 1


def test_raised_limit_from_a_found_config_is_ignored_a_lower_one_kept(tmp_path):
    from urdfcheck.request.config import load_config

    write(tmp_path, {"urdfcheck.yaml": "max_elements: 900000000\n"})
    cfg = load_config(tmp_path / "urdfcheck.yaml")
    assert cfg.max_elements is None and [f.code for f in cfg.notes] == ["X018"]
    write(tmp_path, {"urdfcheck.yaml": "max_elements: 500\n"})
    cfg = load_config(tmp_path / "urdfcheck.yaml")
    assert cfg.max_elements == 500 and not cfg.notes


def test_a_named_and_trusted_config_is_honoured(tmp_path):
    mine = tmp_path / "ci"
    write(mine, {"urdfcheck.yaml": "trusted: true\n"})
    repo = write(tmp_path / "repo", {"robot.urdf.xacro": PROBE})
    code, out, _ = lint(repo, "--format", "json", "--config", mine / "urdfcheck.yaml", "--trust-config",
                        "robot.urdf.xacro")
    assert "X010" in codes(out) and "X018" not in codes(out)  # stock xacro evaluated it: the runner said so


def test_a_named_config_without_trust_config_is_not_trusted(tmp_path):
    write(tmp_path, {"cfg.yaml": "trusted: true\n", "robot.urdf.xacro": PROBE})
    code, out, _ = lint(tmp_path, "--format", "json", "--config", "cfg.yaml", "robot.urdf.xacro")
    assert "X011" in codes(out) and "X018" in codes(out)


def test_trust_config_needs_a_named_config(tmp_path):
    write(tmp_path, {"robot.urdf.xacro": BROKEN})
    with pytest.raises(UsageError, match="--trust-config needs --config"):
        from urdfcheck import lint as api

        api([str(tmp_path / "robot.urdf.xacro")], trust_config=True)


def test_allow_env_from_the_api_is_honoured(tmp_path):
    import urdfcheck

    write(tmp_path, {"urdfcheck.yaml": "allow_env: [HOME]\n", "robot.urdf.xacro": LEAK})
    old = os.getcwd()
    os.chdir(tmp_path)
    try:
        res = urdfcheck.lint(["robot.urdf.xacro"], allow_env=["GITHUB_TOKEN"])
    finally:
        os.chdir(old)
    assert any(SECRET in f.message for f in res.findings)  # the runner asked for it
    assert any(f.code == "X018" for f in res.findings)  # the config did not get to


# --- 2. config paths stay in the checkout --------------------------------------------------------------
@pytest.mark.parametrize("body", [
    "packages: {sys: /}\n",
    "packages: {up: ../../../..}\n",
    "models:\n  - path: /etc/hostname\n",
    "models:\n  - path: ../outside/robot.urdf\n",
    "models:\n  - path: robot.urdf.xacro\n    launch: [../outside/x.launch.xml]\n",
    "models:\n  - path: robot.urdf.xacro\n    controllers: [../outside/c.yaml]\n",
    "models:\n  - path: robot.urdf.xacro\n    localization: [../outside/c.yaml]\n",
    "models:\n  - path: robot.urdf.xacro\n    drivers:\n      - file: ../outside/c.yaml\n        joints: [a]\n",
], ids=["packages-root", "packages-dotdot", "model-abs", "model-dotdot", "launch", "controllers", "localization",
        "drivers"])
def test_config_paths_that_leave_are_a_located_error(tmp_path, body):
    write(tmp_path / "outside", {"robot.urdf": "<robot name='x'><link name='a'/></robot>", "x.launch.xml": "<launch/>",
                                 "c.yaml": "a: 1\n"})
    repo = write(tmp_path / "repo", {"urdfcheck.yaml": body, "robot.urdf.xacro": BROKEN})
    code, out, err = lint(repo)
    assert code == 2
    assert "leaves the checkout" in err and "urdfcheck.yaml:" in err  # file:line of the key


def test_a_config_path_through_a_symlink_out_is_an_error(tmp_path):
    write(tmp_path / "outside", {"robot.urdf": "<robot name='x'><link name='a'/></robot>"})
    repo = write(tmp_path / "repo", {"urdfcheck.yaml": "models:\n  - path: link/robot.urdf\n"})
    os.symlink(tmp_path / "outside", repo / "link")
    code, _, err = lint(repo)
    assert code == 2 and "leaves the checkout" in err


def test_a_trusted_config_may_name_paths_outside(tmp_path):
    write(tmp_path / "outside", {"robot.urdf": "<robot name='x'><link name='base_link'/></robot>"})
    write(tmp_path / "ci", {"cfg.yaml": f"models:\n  - path: {tmp_path / 'outside' / 'robot.urdf'}\n"})
    repo = tmp_path / "repo"
    repo.mkdir()
    code, out, err = lint(repo, "--config", tmp_path / "ci" / "cfg.yaml", "--trust-config")
    assert code == 0, err


def test_a_package_path_outside_cannot_read_files(tmp_path):
    payload = (f'<robot name="r" {XACRO_NS}>\n <xacro:property name="p" value="${{xacro.load_yaml('
               f'\'$(find sys)/etc/passwd\')}}"/>\n <link name="base_link"/>\n</robot>\n')
    write(tmp_path, {"urdfcheck.yaml": "packages: {sys: /}\n", "robot.urdf.xacro": payload})
    code, out, err = lint(tmp_path)
    assert code == 2 and "root:" not in out + err


# --- 3. no silent pass ----------------------------------------------------------------------------------
def _pkg(root, files):
    return write(root, {"package.xml": "<package format='3'><name>p</name></package>", **files})


@pytest.mark.parametrize("decoy", [
    '<!-- <xacro:include filename="robot.urdf.xacro"/> -->',
    '<xacro:if value="false"><xacro:include filename="robot.urdf.xacro"/></xacro:if>',
    '<xacro:macro name="never"><xacro:include filename="robot.urdf.xacro"/></xacro:macro>',
    '<!-- <xacro:include filename="$(find p)/urdf/robot.urdf.xacro"/> -->',
], ids=["comment", "if-false", "uncalled-macro", "comment-find"])
def test_a_decoy_include_does_not_hide_the_robot(tmp_path, decoy):
    _pkg(tmp_path, {"urdf/robot.urdf.xacro": BROKEN,
                    "urdf/decoy.urdf.xacro": f'<robot name="d" {XACRO_NS}>\n  {decoy}\n  <link name="base_link"/>\n'
                                             "</robot>\n"})
    code, out, _ = lint(tmp_path, "--format", "json")
    assert "S003" in codes(out) and code == 1


def test_xacro_element_links_make_a_robot(tmp_path):
    body = (f'<robot name="r" {XACRO_NS}>\n  <xacro:element xacro:name="link" name="base_link"/>\n'
            '  <xacro:element xacro:name="joint" name="j" type="fixed"><parent link="base_link"/>'
            '<child link="missing"/></xacro:element>\n</robot>\n')
    _pkg(tmp_path, {"urdf/robot.urdf.xacro": body})
    code, out, _ = lint(tmp_path, "--format", "json")
    assert "S003" in codes(out) and code == 1


def test_srdf_looking_robot_with_element_links_is_linted(tmp_path):
    body = (f'<robot name="r" {XACRO_NS}>\n  <group name="arm"/>\n  <xacro:element xacro:name="link" name="a"/>\n'
            '  <xacro:element xacro:name="joint" name="j" type="fixed"><parent link="a"/><child link="zz"/>'
            '</xacro:element>\n</robot>\n')
    _pkg(tmp_path, {"urdf/robot.urdf.xacro": body})
    code, out, _ = lint(tmp_path, "--format", "json")
    assert "S003" in codes(out) and code == 1


@pytest.mark.parametrize("named", [True, False])
def test_property_plus_include_is_a_robot(tmp_path, named):
    entry = f'<robot name="r" {XACRO_NS}>\n  <xacro:property name="p" value="1"/>\n' \
            '  <xacro:include filename="body.xacro"/>\n</robot>\n'
    _pkg(tmp_path, {"urdf/robot.urdf.xacro": entry, "urdf/body.xacro": BROKEN.replace('name="r" ', "")})
    code, out, _ = lint(tmp_path, "--format", "json", *(["urdf/robot.urdf.xacro"] if named else []))
    assert "S003" in codes(out) and code == 1


def test_a_named_library_is_never_skipped(tmp_path):
    lib = f'<robot {XACRO_NS}>\n  <xacro:property name="p" value="1"/>\n  <xacro:include filename="x.xacro"/>\n' \
          '</robot>\n'
    _pkg(tmp_path, {"urdf/lib.xacro": lib, "urdf/x.xacro": BROKEN})
    code, out, _ = lint(tmp_path, "--format", "json", "urdf/lib.xacro")
    assert "S003" in codes(out) and code == 1  # its expansion has links: a robot


def test_libraries_only_say_no_robot_found(tmp_path):
    macro = f'<robot {XACRO_NS}>\n  <xacro:macro name="m"><link name="a"/></xacro:macro>\n</robot>\n'
    _pkg(tmp_path, {f"urdf/m{i}.xacro": macro for i in range(3)})
    code, out, _ = lint(tmp_path)
    assert "no robot found: 3 xacro libraries" in out and "All checks passed" not in out
    assert code == 0  # a package of macro libraries alone may exit 0
    code, out, _ = lint(tmp_path, "--format", "markdown")
    assert "nothing checked" in out and "all checks passed" not in out


def test_a_fragment_without_links_is_a_library_after_expansion(tmp_path):
    _pkg(tmp_path, {"urdf/materials.xacro": f'<robot {XACRO_NS}><material name="red"/></robot>\n'})
    code, out, _ = lint(tmp_path)
    assert "no robot found" in out and code == 0


def test_a_cut_short_walk_is_a_finding(tmp_path):
    _pkg(tmp_path, {**{f"a/f{i:03}.txt": "x" for i in range(20)}, "urdf/robot.urdf.xacro": BROKEN})
    code, out, _ = lint(tmp_path, "--format", "json", "--max-files", "10")
    assert "X019" in codes(out) and code == 1


def test_a_cut_short_folder_walk_is_a_finding(tmp_path, monkeypatch):
    from urdfcheck.plan import plan

    monkeypatch.setattr(plan, "MAX_DIRS", 3)
    for i in range(6):
        _pkg(tmp_path / f"p{i}", {"urdf/robot.urdf.xacro": BROKEN})
    code, out, _ = lint(tmp_path, "--format", "json")
    assert "X019" in codes(out) and code == 1


@pytest.mark.parametrize("cfg", ["ignore: [X]\n", "ignore: [X011]\n", "select: [F002]\n", "ignore: [ALL]\n",
                                 "severity: {X: info}\n", "select: [X017, S]\n"])
def test_a_config_cannot_hide_a_refused_expansion(tmp_path, cfg):
    write(tmp_path, {"urdfcheck.yaml": cfg, "robot.urdf.xacro": PROBE})
    code, out, _ = lint(tmp_path, "--format", "json")
    found = json.loads(out)["findings"]
    assert any(f["code"] == "X011" and f["severity"] == "error" for f in found), found
    assert code == 1


def test_the_command_line_may_ignore_but_an_unloaded_model_still_fails(tmp_path):
    write(tmp_path, {"robot.urdf.xacro": PROBE})
    code, out, _ = lint(tmp_path, "--ignore", "X")
    assert code == 1 and "All checks passed" not in out and "not checked" in out


def test_an_includer_that_failed_did_not_check_what_it_included(tmp_path):
    # the only file including the robot fails to expand (a lowered limit): the robot is expanded on its own
    decoy = f'<robot name="d" {XACRO_NS}>\n  <xacro:include filename="robot.urdf.xacro"/>\n  <link name="base_link"/>\n'
    _pkg(tmp_path, {"urdfcheck.yaml": "max_elements: 1\n", "urdf/robot.urdf.xacro": PROBE,
                    "urdf/decoy.urdf.xacro": decoy + "</robot>\n"})
    code, out, _ = lint(tmp_path, "--format", "json")
    assert code == 1 and any(m["path"].endswith("robot.urdf.xacro") for m in json.loads(out)["models"])


# --- 4. bounded everywhere ------------------------------------------------------------------------------
def _peak(fn):
    import tracemalloc

    tracemalloc.start()
    try:
        t0 = time.process_time()
        got = fn()
        return got, tracemalloc.get_traced_memory()[1], time.process_time() - t0
    finally:
        tracemalloc.stop()


def test_python_launch_list_doubling_is_bounded():
    from urdfcheck.consumers.launch import python as pylaunch

    src = ["a0 = ['x', 'y']"] + [f"a{i} = [*a{i - 1}, *a{i - 1}]" for i in range(1, 60)]
    src += ["b0 = {'k': 1}"] + [f"b{i} = {{**b{i - 1}, 'k{i}': b{i - 1}}}" for i in range(1, 40)]
    src += ["c0 = ['x']"] + [f"c{i} = c{i - 1} + c{i - 1}" for i in range(1, 60)]
    src += ["from launch import LaunchDescription", "from launch_ros.actions import Node",
            "def generate_launch_description():",
            "    return LaunchDescription([Node(package='robot_state_publisher', executable='robot_state_publisher',"
            " arguments=a59 + c59, parameters=[{'robot_description': 'x'}])])"]
    import ast

    text = "\n".join(src)
    _, peak, _ = _peak(lambda: pylaunch.read("x.launch.py", ast.parse(text), {}, lambda n: None))
    assert peak < 200 * 2**20


@pytest.mark.parametrize("fmt", ["xml", "yaml"])
def test_let_doubling_is_capped(fmt):
    from urdfcheck.consumers.launch.xml import MAX_VALUE, parse_launch

    if fmt == "xml":
        lines = ['<launch>', '<arg name="a0" default="xxxxxxxxxxxxxxxx"/>']
        lines += [f'<let name="a{i}" value="$(var a{i - 1})$(var a{i - 1})"/>' for i in range(1, 40)]
        lines += ['<node pkg="p" exec="e" name="n"><param name="v" value="$(var a39)"/></node>', '</launch>']
        text, name = "\n".join(lines), "x.launch.xml"
    else:
        lines = ["launch:", "- arg: {name: a0, default: xxxxxxxxxxxxxxxx}"]
        lines += [f"- let: {{name: a{i}, value: '$(var a{i - 1})$(var a{i - 1})'}}" for i in range(1, 40)]
        lines += ["- node: {pkg: p, exec: e, name: n, param: [{name: v, value: '$(var a39)'}]}"]
        text, name = "\n".join(lines), "x.launch.yaml"
    info, peak, cpu = _peak(lambda: parse_launch(text, name))
    assert peak < 64 * MAX_VALUE * 8
    assert info is not None


def test_substitution_growth_stops_at_the_cap():
    from urdfcheck.consumers.launch.xml import MAX_VALUE, _Subst

    s = _Subst("x.launch.xml", {}, {})
    s.fix("a", "x" * (MAX_VALUE // 2 + 1))
    assert s("$(var a)$(var a)") == (None, False)
    assert s("$(var a)")[0] == "x" * (MAX_VALUE // 2 + 1)


def test_baseline_fifo_is_refused_quickly(tmp_path):
    write(tmp_path, {"robot.urdf.xacro": BROKEN})
    os.mkfifo(tmp_path / "b.json")
    code, _, err = lint(tmp_path, "--baseline", "b.json")
    assert code == 2 and "named pipe" in err


def test_baseline_symlink_out_is_refused_without_echo(tmp_path):
    (tmp_path / "secret.json").write_text(json.dumps({"version": 1, "findings": [SECRET]}))
    repo = write(tmp_path / "repo", {"robot.urdf.xacro": BROKEN})
    os.symlink(tmp_path / "secret.json", repo / "b.json")
    code, out, err = lint(repo, "--baseline", "b.json")
    assert code == 2 and "link" in err and SECRET not in out + err


@pytest.mark.parametrize("payload", [
    "[" * 100_000 + "]" * 100_000,
    json.dumps({"version": 1, "findings": [SECRET]}),
    json.dumps({"version": 1, "findings": [{"code": SECRET}]}),
    SECRET,
], ids=["deep", "entry-str", "entry-partial", "not-json"])
def test_baseline_never_echoes_what_it_read(tmp_path, payload):
    write(tmp_path, {"robot.urdf.xacro": BROKEN, "b.json": payload})
    code, out, err = lint(tmp_path, "--baseline", "b.json")
    assert code == 2 and SECRET not in out + err and "internal error" not in err


def test_deep_pyproject_is_a_located_error(tmp_path):
    write(tmp_path, {"pyproject.toml": "[tool.urdfcheck]\nrules = " + "[" * 50_000 + "]" * 50_000 + "\n",
                     "robot.urdf.xacro": BROKEN})
    code, _, err = lint(tmp_path)
    assert code == 2 and "pyproject.toml" in err and "internal error" not in err


def test_deep_yaml_config_is_a_located_error(tmp_path):
    write(tmp_path, {"urdfcheck.yaml": "rules: " + "[" * 50_000 + "]" * 50_000 + "\n", "robot.urdf.xacro": BROKEN})
    code, _, err = lint(tmp_path)
    assert code == 2 and "urdfcheck.yaml" in err and "internal error" not in err


def test_a_reader_recursion_is_a_located_launch_error(monkeypatch):
    from urdfcheck.consumers.common import ConsumerError
    from urdfcheck.consumers.launch import xml as launch

    def deep(*a):
        raise RecursionError

    monkeypatch.setattr(launch, "_parse", deep)
    with pytest.raises(ConsumerError) as e:
        launch.parse_launch("<launch/>", "x.launch.xml")
    assert e.value.location.file == "x.launch.xml"


def test_the_memory_budget_is_a_limit_of_the_run():
    import resource

    from urdfcheck.load.budget import run_budget

    before = resource.getrlimit(resource.RLIMIT_DATA)
    with run_budget(60, 1 << 30):
        soft, _ = resource.getrlimit(resource.RLIMIT_DATA)
        assert soft != resource.RLIM_INFINITY and soft < (1 << 30) + (8 << 30)
        with pytest.raises(MemoryError):
            bytearray(soft + (1 << 20))
    assert resource.getrlimit(resource.RLIMIT_DATA) == before


def test_memory_error_while_checking_is_x017(tmp_path, monkeypatch):
    from urdfcheck import run

    def boom(*a, **k):
        raise MemoryError

    monkeypatch.setattr(run, "_check", boom)
    write(tmp_path, {"robot.urdf.xacro": BROKEN})
    code, out, _ = lint(tmp_path, "--format", "json")
    assert "X017" in codes(out) and code == 1


# --- 5. the checkout's absolute path ----------------------------------------------------------------------
@pytest.mark.parametrize("fmt", FORMATS)
def test_no_absolute_checkout_path_with_the_package_above(tmp_path, fmt):
    pkg = _pkg(tmp_path / "ws" / "pkg", {"urdf/robot.urdf.xacro": BROKEN, "launch/x.txt": "x"})
    code, out, err = lint(pkg / "launch", "--format", fmt, "../urdf/robot.urdf.xacro")
    assert code == 1
    assert str(tmp_path) not in out + err


# --- 6. the grammars of fuzz/trust.py, a few inputs on every run ------------------------------------------
def test_trust_grammar_finds_nothing(monkeypatch, tmp_path):
    import importlib.util

    from conftest import REPO

    spec = importlib.util.spec_from_file_location("fuzz_trust", REPO / "fuzz" / "trust.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    monkeypatch.chdir(tmp_path)
    for var in ("URDFCHECK_DEBUG", *mod.SECRET_VARS):  # the fuzzer sets them: restored after the test
        monkeypatch.setenv(var, "")
    import signal

    monkeypatch.setattr(signal, "signal", lambda *a: None)  # keep the test runner's handlers
    monkeypatch.setattr(mod.signal, "setitimer", lambda *a: None)
    report = tmp_path / "r.json"
    code = mod.main(["--count", "40", "--seed", "7", "--full-every", "20", "--report", str(report)])
    counts = json.loads(report.read_text())["counts"]
    assert code == 0, json.loads(report.read_text())["examples"][:2]
    assert counts["inputs"] == 40 and counts["full"] == 2


# --- 7. "did you mean" hints are bounded per run --------------------------------------------------------
def test_hints_stop_once_the_run_has_compared_its_share(tmp_path):
    from urdfcheck.core import findings as F

    n = 4000  # links; every joint's parent is misspelt: one hint per joint, each against every link
    links = "\n".join(f'<link name="link_{i:05d}"/>' for i in range(n))
    joints = "\n".join(f'<joint name="j{i}" type="fixed"><parent link="lnk_{i - 1:05d}"/>'
                       f'<child link="link_{i:05d}"/></joint>' for i in range(1, n))
    p = tmp_path / "m.urdf"
    p.write_text(f'<robot name="r">\n{links}\n{joints}\n</robot>')  # a line each: a finding each
    code, out, _ = run_cli(["lint", "--no-config", "--format", "json", str(p)])
    found = [f for f in json.loads(out)["findings"] if f["code"] == "S003"]
    messages = [f["message"] for f in found] + [a["message"] for f in found for a in f.get("also", ())]
    hinted = [m for m in messages if "did you mean" in m]
    assert code == 1 and len(messages) >= n - 1
    assert 0 < len(hinted) <= F.HINT_CANDIDATES // n + 1
    assert F.closest("lnk_00001", [f"link_{i:05d}" for i in range(100)]) is None  # spent: until the next run
    F.reset_hints()
    assert F.closest("lnk_00001", [f"link_{i:05d}" for i in range(100)]) == "link_00001"
    F._hints_left[0] = 0
    assert F.closest("revolut", ["revolute", "prismatic"]) == "revolute"  # a small set is never refused
    F.reset_hints()


@pytest.mark.parametrize("body", [f"<link name=\"l${{xacro.load_yaml('{name}')}}\"/>"
                                  for name in ("x", "missing.yaml", "../urdf")]
                         + ["<xacro:include filename='nothere.xacro'/><link name='a'/>",
                            "<xacro:include filename='../urdf'/><link name='a'/>"])
def test_a_file_that_fails_to_read_names_no_absolute_path(tmp_path, body):
    """The fuzzer's find: a missing (or folder) load_yaml target or include said "[Errno 2] ... '/abs/path'" after
    our own words, with the model named by an absolute path from another working directory."""
    urdf = tmp_path / "ws" / "pkg" / "urdf"
    urdf.mkdir(parents=True)
    (urdf.parent / "package.xml").write_text("<package format='3'><name>pkg</name></package>")
    model = urdf / "p.urdf.xacro"
    model.write_text(f"<robot name='r' xmlns:xacro='http://www.ros.org/wiki/xacro'>{body}</robot>")
    (tmp_path / "elsewhere").mkdir()
    code, out, _ = run_cli(["lint", "--no-config", "--no-cache", "--format", "json", str(model)],
                           cwd=tmp_path / "elsewhere")
    assert code == 1
    messages = [f["message"] for f in json.loads(out)["findings"]]
    assert messages and not any(str(tmp_path) in m for m in messages), messages


def test_a_quoted_absolute_path_in_a_librarys_words_is_shown_as_reports_show_paths(tmp_path, monkeypatch):
    """Defence in depth for the find above: whatever a library quotes of a path it built is shown relative to the
    working directory, or not at all when outside it."""
    from types import SimpleNamespace

    from urdfcheck.load.xacro import expand

    monkeypatch.chdir(tmp_path)
    inside = tmp_path / "pkg" / "urdf" / "x.yaml"
    err = OSError(f"cannot read '{inside}' nor \"/etc/secret.yaml\"")
    got = expand._describe(err, SimpleNamespace(macrostack=[]))["message"]
    assert str(tmp_path) not in got and "/etc/secret" not in got
    assert "'pkg/urdf/x.yaml'" in got and "a file outside the working directory" in got
