"""`urdfcheck consumers`: real consumers in the sandboxed worker, their verdicts located, crashes and hangs bounded."""
import json
import textwrap

import pytest
from conftest import run_cli

INR = '<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>'
ARM = textwrap.dedent(f"""\
<robot name="r">
  <link name="base_link">{INR}</link>
  <link name="arm">CHILD</link>
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
</robot>
""")


def _model(tmp_path, child):
    p = tmp_path / "robot.urdf"
    p.write_text(ARM.replace("CHILD", child))
    return p


def test_mujoco_refusal_is_located(tmp_path):
    pytest.importorskip("mujoco")
    p = _model(tmp_path, "")
    code, out, err = run_cli(["consumers", str(p), "--consumer", "mujoco", "--format", "json"], cwd=tmp_path)
    assert code == 1, err
    data = json.loads(out)
    mj = data["consumers"][0]
    assert mj["status"] == "rejected" and "mjMINVAL" in mj["message"]
    assert mj["location"]["line"] == 3
    assert data["findings"][0]["code"] == "P090"


def test_loaded_with_changes_and_meshes_replaced(tmp_path):
    pytest.importorskip("mujoco")
    pytest.importorskip("pinocchio")
    p = _model(tmp_path, INR + '<collision><geometry><mesh filename="package://nowhere/arm.stl"/></geometry></collision>')
    code, out, err = run_cli(["consumers", str(p), "--consumer", "mujoco,pinocchio"], cwd=tmp_path)
    assert code == 0, (out, err)
    assert "mujoco     loaded" in out and "pinocchio  loaded" in out
    assert "1 <mesh> file replaced by 0.1 0.1 0.1 m boxes" in out
    code, out, _ = run_cli(["consumers", str(p), "--consumer", "mujoco", "--format", "markdown"], cwd=tmp_path)
    assert out.startswith("## Consumers of") and "| mujoco | loaded |" in out


def test_unknown_consumer_is_usage_error(tmp_path):
    p = _model(tmp_path, INR)
    code, _, err = run_cli(["consumers", str(p), "--consumer", "gazebo"], cwd=tmp_path)
    assert code == 2 and "unknown consumer 'gazebo'" in err


def test_a_hanging_or_crashing_consumer_ends_as_a_finding(tmp_path, monkeypatch):
    from urdfcheck.load import loader
    from urdfcheck.verify import consumers as C

    def hang(path):
        while True:
            pass

    def crash(path):
        import os
        import signal

        os.kill(os.getpid(), signal.SIGSEGV)

    p = _model(tmp_path, INR)
    exp = loader.expand(str(p), {})
    model = loader.build_model(exp)
    monkeypatch.setitem(C.JOBS, "yourdfpy", hang)
    monkeypatch.setitem(C.JOBS, "pybullet", crash)
    monkeypatch.setattr(C, "available", lambda name: True)
    outcomes = C.run(model, exp.clean_text(), ("yourdfpy", "pybullet"), timeout=1.0)
    assert [o.status for o in outcomes] == ["timeout", "crashed"]
    found = C.findings(outcomes, model)
    assert [f.code for f in found] == ["P091", "P091"]


def test_mujoco_log_never_lands_in_the_checked_tree(tmp_path):
    """MuJoCo writes MUJOCO_LOG.TXT into its working directory on a warning (equal limits here): the consumer
    runs in the model copy's temporary folder, so the user's tree stays as it was."""
    pytest.importorskip("mujoco")
    p = _model(tmp_path, INR)
    p.write_text(p.read_text().replace('lower="-1" upper="1"', 'lower="0.5" upper="0.5"'))
    before = sorted(x.name for x in tmp_path.iterdir())
    code, out, err = run_cli(["consumers", str(p), "--consumer", "mujoco"], cwd=tmp_path)
    assert code in (0, 1), err
    assert sorted(x.name for x in tmp_path.iterdir()) == before


def test_sdformat_drops_a_massless_link_and_refuses_a_massless_root(tmp_path):
    import shutil

    if shutil.which("ign") is None:
        pytest.skip("ign sdf (Debian ignition-tools, libsdformat-dev) not installed")
    p = _model(tmp_path, "")  # 'arm' has no <inertial>: dropped, the model loads
    code, out, err = run_cli(["consumers", str(p), "--consumer", "sdformat", "--format", "json"], cwd=tmp_path)
    sdf = json.loads(out)["consumers"][0]
    assert sdf["status"] == "loaded" and any("'arm'" in c or "arm" in c for c in sdf["changes"]), sdf
    p.write_text(ARM.replace(INR, "", 1).replace("CHILD", INR))  # the root has none: nothing left
    code, out, err = run_cli(["consumers", str(p), "--consumer", "sdformat", "--format", "json"], cwd=tmp_path)
    sdf = json.loads(out)["consumers"][0]
    assert code == 1 and sdf["status"] == "rejected" and "link" in sdf["message"], sdf
