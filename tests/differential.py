"""The differential harness of the consumer profiles (issue 40): load a URDF into each real consumer installable
here and say, on five points, what it did: refused, links kept, masses given, joints changed, mimic kept; then
compare with what the profile predicts (urdfcheck's findings under `--profile NAME` for the refusal,
profiles.behaviour.predict for the rest).

Consumers: MuJoCo, Pinocchio, PyBullet (Python packages), sdformat's URDF converter and validation (`ign sdf -p`
then `ign sdf -k` on its output; Debian ignition-tools + libsdformat) and kdl_parser (`treeFromString`, through a
small C++ probe compiled once from Debian libkdl-parser-dev). Each load runs in its own subprocess with a time-out:
PyBullet and kdl_parser crash on some models, and a crash is an answer (refused), not a failure of the harness.
Meshes are replaced by boxes first (`verify.consumers.without_meshes`): the corpus has none.

Used by tests/rules/test_profiles_diff.py (the mutants, in the normal suite) and tools/profiles_table.py (the corpus).
"""
from __future__ import annotations

import functools
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

CONSUMERS = ("mujoco", "pinocchio", "pybullet", "gazebo", "kdl")
TIMEOUT = 60.0
POINTS = ("refused", "links", "mass", "joints", "mimic")

# --- the probes (each runs in a child python: `python differential.py CONSUMER PATH` prints one JSON line) -----
HINGE, SLIDE = "hinge", "slide"


def _mujoco(path):
    import mujoco

    os.chdir(os.path.dirname(path))  # MUJOCO_LOG.TXT lands next to the copy
    try:
        m = mujoco.MjModel.from_xml_path(path)
    except Exception as e:
        return {"refused": True, "why": str(e)[:300], "version": mujoco.__version__}
    name = mujoco.mj_id2name
    kinds = {0: "free", 1: "ball", 2: SLIDE, 3: HINGE}
    bodies = [name(m, mujoco.mjtObj.mjOBJ_BODY, i) or "" for i in range(m.nbody)]
    joints = {name(m, mujoco.mjtObj.mjOBJ_JOINT, i) or "": kinds.get(int(m.jnt_type[i]), "?") for i in range(m.njnt)}
    for j in [j for j in joints if j.endswith("_TX") and j[:-3] + "_RZ" in joints]:
        joints[j[:-3]] = "planar"  # xml_urdf.cc writes a planar joint as two slides and a hinge
    mimic = [name(m, mujoco.mjtObj.mjOBJ_JOINT, int(m.eq_obj1id[i])) for i in range(m.neq)
             if int(m.eq_type[i]) == int(mujoco.mjtEq.mjEQ_JOINT)]
    return {"refused": False, "version": mujoco.__version__, "links": [b for b in bodies if b != "world"],
            "mass": {b: float(m.body_mass[i]) for i, b in enumerate(bodies) if b != "world"},
            "joints": joints, "mimic": mimic}


def _pinocchio(path):
    import pinocchio

    try:
        m = pinocchio.buildModelFromUrdf(path)
        # the geometry models too, as RobotWrapper.BuildFromURDF builds them: meshes are read here
        for kind in (pinocchio.GeometryType.COLLISION, pinocchio.GeometryType.VISUAL):
            pinocchio.buildGeomFromUrdf(m, path, kind, package_dirs=[os.path.dirname(path)])
    except Exception as e:
        return {"refused": True, "why": str(e)[:300], "version": pinocchio.__version__}
    joints = {}
    for jname, jm in zip(list(m.names)[1:], list(m.joints)[1:]):
        short = jm.shortname()
        kind = ("free" if "FreeFlyer" in short else "planar" if "Planar" in short else
                SLIDE if short.startswith("JointModelP") else HINGE if short.startswith("JointModelR") else short)
        joints[str(jname)] = kind
    bodies = [f.name for f in m.frames if f.type == pinocchio.FrameType.BODY]
    mass = {}
    for f in m.frames:
        if f.type == pinocchio.FrameType.BODY and f.parentJoint > 0 and m.frames[f.previousFrame].type == \
                pinocchio.FrameType.JOINT:
            mass[f.name] = float(m.inertias[f.parentJoint].mass)
    return {"refused": False, "version": pinocchio.__version__, "links": bodies, "mass": mass,
            "joints": joints, "mimic": [n for n, jm in zip(m.names, m.joints) if "Mimic" in jm.shortname()]}


def _pybullet(path):
    import pybullet

    cid = pybullet.connect(pybullet.DIRECT)
    try:
        body = pybullet.loadURDF(path, physicsClientId=cid)  # the default load: free base, inertia recomputed
    except Exception as e:
        return {"refused": True, "why": str(e)[:300]}
    kinds = {0: HINGE, 1: SLIDE, 2: "ball", 3: "planar", 4: "fixed"}
    base = pybullet.getBodyInfo(body, physicsClientId=cid)[0].decode()
    links, mass, joints = [base], {base: pybullet.getDynamicsInfo(body, -1, physicsClientId=cid)[0]}, {}
    for i in range(pybullet.getNumJoints(body, physicsClientId=cid)):
        info = pybullet.getJointInfo(body, i, physicsClientId=cid)
        link = info[12].decode()
        links.append(link)
        mass[link] = pybullet.getDynamicsInfo(body, i, physicsClientId=cid)[0]
        joints[info[1].decode()] = kinds.get(int(info[2]), "?")
    return {"refused": False, "version": str(pybullet.getAPIVersion()), "links": links, "mass": mass,
            "joints": joints, "mimic": []}


def _gazebo(path):
    env = dict(os.environ, IGN_CONFIG_PATH="/usr/share/ignition")
    conv = subprocess.run(["ign", "sdf", "-p", path], capture_output=True, text=True, timeout=TIMEOUT, env=env)
    version = sdformat_version()
    if conv.returncode != 0 or "<sdf" not in conv.stdout:
        return {"refused": True, "why": _tail(conv.stderr), "version": version}
    sdf = path + ".sdf"
    with open(sdf, "w", encoding="utf-8") as f:
        f.write(conv.stdout[conv.stdout.index("<sdf"):])
    check = subprocess.run(["ign", "sdf", "-k", sdf], capture_output=True, text=True, timeout=TIMEOUT, env=env)
    from lxml import etree

    # sdformat copies <gazebo> extension XML as written, undeclared namespace prefixes (PR2's sensor:) included
    root = etree.fromstring(open(sdf, "rb").read(), etree.XMLParser(recover=True, huge_tree=True))
    model = root.find("model")
    links = [] if model is None else model.findall("link")
    if check.returncode != 0 or "Error" in check.stderr + check.stdout or not links:
        why = _tail(check.stderr + check.stdout) if links else "no link left after conversion"
        return {"refused": True, "why": why, "version": version}
    kinds = {"revolute": HINGE, "continuous": HINGE, "prismatic": SLIDE, "fixed": "fixed", "ball": "ball",
             "universal": "universal", "screw": "screw"}
    joints, mimic = {}, []
    for j in model.findall("joint"):
        joints[j.get("name")] = kinds.get(j.get("type"), j.get("type"))
        if j.find("axis/mimic") is not None or j.find("mimic") is not None:
            mimic.append(j.get("name"))
    mass = {}
    for lk in links:
        m = lk.find("inertial/mass")
        mass[lk.get("name")] = float(m.text) if m is not None else 1.0  # sdformat's default inertial
    return {"refused": False, "version": version, "links": [lk.get("name") for lk in links], "mass": mass,
            "joints": joints, "mimic": mimic}


def _kdl(path):
    exe = kdl_probe()
    with open(path, "rb") as f:
        proc = subprocess.run([exe], stdin=f, capture_output=True, text=True, timeout=TIMEOUT)
    if proc.returncode != 0:
        why = "crashed" if proc.returncode < 0 else _tail(proc.stderr) or "treeFromString returned false"
        return {"refused": True, "why": why, "version": kdl_version()}
    kinds = {"Fixed": "fixed", "None": "fixed", "TransAxis": SLIDE, "TransX": SLIDE, "TransY": SLIDE,
             "TransZ": SLIDE}
    links, mass, joints = [], {}, {}
    for line in proc.stdout.splitlines():
        parts = line.split(" ")
        if parts[0] != "SEG" or len(parts) != 5:
            continue
        _, link, joint, kind, m = parts
        links.append(link)
        mass[link] = float(m)
        if joint != "NoName":
            joints[joint] = kinds.get(kind, HINGE)
    return {"refused": False, "version": kdl_version(), "links": links, "mass": mass, "joints": joints,
            "mimic": []}


def _tail(text: str) -> str:
    lines = [ln for ln in text.splitlines() if ln.strip() and "libignition-tools-backward" not in ln]
    return " ".join(lines[-3:])[:300]


PROBES = {"mujoco": _mujoco, "pinocchio": _pinocchio, "pybullet": _pybullet, "gazebo": _gazebo, "kdl": _kdl}

KDL_SOURCE = r"""
#include <kdl_parser/kdl_parser.hpp>
#include <kdl/tree.hpp>
#include <iostream>
#include <iterator>
int main() {
  std::string xml((std::istreambuf_iterator<char>(std::cin)), std::istreambuf_iterator<char>());
  KDL::Tree tree;
  if (!kdl_parser::treeFromString(xml, tree)) return 3;
  for (const auto &kv : tree.getSegments()) {
    const KDL::Segment &s = kv.second.segment;
    std::cout << "SEG " << kv.first << " " << s.getJoint().getName() << " " << s.getJoint().getTypeName() << " "
              << s.getInertia().getMass() << "\n";
  }
  return 0;
}
"""


@functools.cache
def kdl_probe() -> str | None:
    """The compiled probe, or None when g++ or kdl_parser's headers are missing."""
    cxx = shutil.which("g++") or shutil.which("c++")
    if cxx is None or not os.path.exists("/usr/include/kdl_parser/kdl_parser.hpp"):
        return None
    import atexit

    folder = tempfile.mkdtemp(prefix="urdfcheck-kdlprobe-")
    atexit.register(shutil.rmtree, folder, True)
    src, exe = os.path.join(folder, "probe.cpp"), os.path.join(folder, "probe")
    with open(src, "w") as f:
        f.write(KDL_SOURCE)
    proc = subprocess.run([cxx, "-std=c++17", "-O0", src, "-o", exe, "-I/usr/include/eigen3", "-lkdl_parser",
                           "-lorocos-kdl"], capture_output=True, text=True, timeout=300)
    return exe if proc.returncode == 0 else None


@functools.cache
def sdformat_version() -> str:
    return _deb_version("libsdformat12") or _deb_version("libsdformat14") or ""


@functools.cache
def kdl_version() -> str:
    return _deb_version("libkdl-parser") or ""


@functools.cache
def urdfdom_version() -> str:
    return _deb_version("liburdfdom-model") or ""


def _deb_version(prefix: str) -> str:
    try:
        out = subprocess.run(["dpkg-query", "-W", "-f", "${Package} ${Version}\n"], capture_output=True,
                             text=True, timeout=30).stdout
    except (OSError, subprocess.SubprocessError):
        return ""
    for line in out.splitlines():
        name, _, version = line.partition(" ")
        if name.startswith(prefix) and not name.endswith("-dev"):
            return version.split("+")[0].split("-")[0]
    return ""


@functools.cache
def installed() -> tuple[str, ...]:
    import importlib.util

    out = [c for c in ("mujoco", "pinocchio", "pybullet") if importlib.util.find_spec(c) is not None]
    if shutil.which("ign") and sdformat_version():
        out.append("gazebo")
    if kdl_probe() is not None:
        out.append("kdl")
    return tuple(out)


def load_many(consumer: str, paths: list[str]) -> list[dict]:
    """What the consumer did with each model, one subprocess for all (one import of the consumer); after a crash,
    the model that crashed it is answered "refused" and the rest go on in a new subprocess."""
    out: list[dict] = []
    todo = list(paths)
    while todo:
        got = _child(consumer, todo, TIMEOUT * (len(todo) + 1))
        out.extend(got)
        todo = todo[len(got):]
        if todo:  # the child died on todo[0]
            out.append(_crash(consumer, todo[0]))
            todo = todo[1:]
    return out


def _crash(consumer: str, path: str) -> dict:
    got = _child(consumer, [path], TIMEOUT * 2)
    return got[0] if got else {"refused": True, "why": "crashed"}


def _child(consumer: str, paths: list[str], timeout: float) -> list[dict]:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([os.path.dirname(os.path.abspath(__file__))]
                                        + [p for p in sys.path if p.endswith("src")])
    try:
        proc = subprocess.run([sys.executable, os.path.abspath(__file__), consumer, *paths], capture_output=True,
                              text=True, timeout=timeout, env=env, cwd=os.path.dirname(paths[0]))
        stdout = proc.stdout
    except subprocess.TimeoutExpired as e:
        stdout = e.stdout.decode() if isinstance(e.stdout, bytes) else (e.stdout or "")
    return [json.loads(ln[2:]) for ln in stdout.splitlines() if ln.startswith("@@{")]


def load(consumer: str, path: str) -> dict:
    """What the consumer did with the model at `path` (a copy without meshes), in a subprocess."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([os.path.dirname(os.path.abspath(__file__))]
                                        + [p for p in sys.path if p.endswith("src")])
    try:
        proc = subprocess.run([sys.executable, os.path.abspath(__file__), consumer, path], capture_output=True,
                              text=True, timeout=TIMEOUT * 2, env=env, cwd=os.path.dirname(path))
    except subprocess.TimeoutExpired:
        return {"refused": True, "why": "timed out"}
    lines = [ln[2:] for ln in proc.stdout.splitlines() if ln.startswith("@@{")]
    if proc.returncode != 0 or not lines:
        return {"refused": True, "why": f"crashed (exit status {proc.returncode})"}
    return json.loads(lines[-1])


# --- the prediction -------------------------------------------------------------------------------------------
def prepared(path: str, folder: str):
    """(model, copy path) of the model expanded by urdfcheck and written without meshes; None if it does not
    load (urdfcheck reports that itself)."""
    from urdfcheck.load import loader
    from urdfcheck.model.build import model_from_string
    from urdfcheck.verify.consumers import without_meshes

    exp = loader.expand(path, {})
    if exp.root is None:
        return None
    if "urdfcheck-diff: keep meshes" in exp.clean_text():
        return model_from_string(exp.clean_text(), path), path  # a mutant about its mesh files: as written
    text, _ = without_meshes(exp.clean_text(), folder)
    copy = os.path.join(folder, f"m{len(os.listdir(folder)):05d}.urdf")
    with open(copy, "w", encoding="utf-8") as f:
        f.write(text)
    return model_from_string(text, copy), copy


def refusals(copy: str, consumers) -> dict[str, list[str]]:
    """consumer -> the codes of the findings that say it refuses the model: one lint with every profile on (each
    finding names every profile whose consumer it concerns). Any severity: a general rule may say a defect at info
    for its own reasons (S003 on an attachable fragment), the consumer still refuses the model as it is."""
    import urdfcheck
    from urdfcheck.rules.checks.profiles import behaviour

    here = os.getcwd()
    folder = os.path.dirname(copy)
    config = os.path.join(folder, ".urdfcheck-diff.yaml")
    version = sdformat_version() or "12.3"  # the rules' sdformat option: the version loaded here
    with open(config, "w", encoding="utf-8") as f:
        f.write("rules:\n" + "".join(f"  {c}: {{sdformat: '{version}'}}\n" for c in ("P011", "P012", "P052")))
    os.chdir(folder)  # the model's folder is the run's root, as when linted from there
    try:
        res = urdfcheck.lint([copy], profiles=list(consumers), config=config, trust_config=True, root=folder,
                             select=["ALL"])
    finally:
        os.chdir(here)
    return {c: sorted({f.code for f in res.findings if c in (f.profiles or (f.profile,))
                       and behaviour.refuses(f.code, c)}) for c in consumers}


def predict(consumer: str, copy: str, model, version: str = "", why=None) -> dict:
    from urdfcheck.rules.checks.profiles import behaviour

    if why is None:
        why = refusals(copy, (consumer,))[consumer]
    out = behaviour.predict(consumer, model, version)
    out["refused"] = bool(why)
    out["why"] = ",".join(why)
    return out


def compare(pred: dict, truth: dict) -> list[str]:
    """The points on which prediction and consumer differ (a refusal decides alone: nothing else to compare)."""
    if pred["refused"] != truth["refused"]:
        return ["refused"]
    if truth["refused"]:
        return []
    out = []
    if set(pred["links"]) != set(truth["links"]):
        out.append("links")
    for link, m in pred["mass"].items():
        got = truth["mass"].get(link)
        if m is not None and got is not None and not math.isclose(m, got, rel_tol=1e-4, abs_tol=1e-9):
            out.append("mass")
            break
    if any(truth["joints"].get(j, "gone") != k for j, k in pred["joints"].items()):
        out.append("joints")
    if set(pred["mimic"]) != set(truth["mimic"]):
        out.append("mimic")
    return out


def explain(pred: dict, truth: dict, point: str) -> str:
    if point == "refused":
        return (f"predicted {'refusal (' + pred['why'] + ')' if pred['refused'] else 'load'}, consumer "
                + ("refused: " + truth.get("why", "") if truth["refused"] else "loaded"))
    if point == "links":
        p, t = set(pred["links"]), set(truth["links"])
        return f"links predicted not kept {sorted(p - t)[:5]}, kept but predicted gone {sorted(t - p)[:5]}"
    if point == "mass":
        bad = [(k, v, truth["mass"].get(k)) for k, v in pred["mass"].items() if v is not None
               and truth["mass"].get(k) is not None and not math.isclose(v, truth["mass"][k], rel_tol=1e-4,
                                                                       abs_tol=1e-9)]
        return f"masses (link, predicted, got) {bad[:4]}"
    if point == "joints":
        bad = [(j, k, truth["joints"].get(j, "gone")) for j, k in pred["joints"].items()
               if truth["joints"].get(j, "gone") != k]
        return f"joints (name, predicted, got) {bad[:4]}"
    return f"mimic predicted {sorted(pred['mimic'])}, kept {sorted(truth['mimic'])}"


def run(paths, consumers=None, folder=None) -> dict:
    """consumer -> {"agree": [label...], "disagree": [(label, point, explanation)...]} over `paths`
    ((label, path) pairs)."""
    consumers = [c for c in (consumers or CONSUMERS) if c in installed()]
    table = {c: {"agree": [], "disagree": []} for c in consumers}
    own = folder is None
    folder = folder or tempfile.mkdtemp(prefix="urdfcheck-diff-")
    try:
        ready = []
        for label, path in paths:
            got = prepared(path, folder)
            if got is not None:
                ready.append((label, *got))
        from concurrent.futures import ThreadPoolExecutor

        copies = [copy for _, _, copy in ready]
        with ThreadPoolExecutor(max_workers=2) as pool:  # the consumers' subprocesses run while urdfcheck lints
            loading = {c: pool.submit(load_many, c, copies) for c in consumers}
            said = [refusals(copy, consumers) for copy in copies]
            loaded = {c: f.result() for c, f in loading.items()}
        for c in consumers:
            truths = loaded[c]
            for (label, model, copy), truth, why in zip(ready, truths, said):
                pred = predict(c, copy, model, truth.get("version", ""), why[c])
                bad = compare(pred, truth)
                if bad:
                    table[c]["disagree"].append((label, bad[0], explain(pred, truth, bad[0])))
                else:
                    table[c]["agree"].append(label)
    finally:
        if own:
            shutil.rmtree(folder, ignore_errors=True)
    return table


if __name__ == "__main__":
    probe, targets = PROBES[sys.argv[1]], sys.argv[2:]
    if sys.argv[1] in ("gazebo", "kdl"):  # each load is its own process already: several at once, answers in order
        from concurrent.futures import ThreadPoolExecutor

        with ThreadPoolExecutor(max_workers=4) as pool:
            for got in pool.map(probe, targets):
                print("\n@@" + json.dumps(got), flush=True)
    else:
        for target in targets:
            sys.stdout.flush()
            out = json.dumps(probe(target))
            sys.stdout.flush()
            print("\n@@" + out, flush=True)
