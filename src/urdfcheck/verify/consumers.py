"""Load an expanded model into the real consumers (MuJoCo, Pinocchio, PyBullet, yourdfpy, urdfdom's check_urdf),
each in the sandboxed worker (core/worker.py: memory, CPU and wall-clock limits), and say per consumer whether it
loaded the model or refused it (its message, mapped back to the source line where it names a link or joint), and
what it changed compared with the URDF (bodies, joints, fused links, constraints).

Mesh files are not loaded: every <mesh> points to a box STL in a temporary folder, sized to be a 0.1 m cube after
the mesh's scale (the corpus has no meshes, and a consumer's verdict on a missing file says nothing about the
model); each result says how many were replaced.
A consumer that crashes, runs out of memory or hangs ends as a Failure of its worker, reported as a finding.
"""
from __future__ import annotations

import os
import re
import shutil
import tempfile

from urdfcheck.core import lazyre, worker
from urdfcheck.core.findings import Finding, Location, Severity, clean_text
from urdfcheck.core.records import Record

CONSUMERS = ("mujoco", "pinocchio", "pybullet", "yourdfpy", "urdfdom", "sdformat")
MODULE = {"mujoco": "mujoco", "pinocchio": "pinocchio", "pybullet": "pybullet", "yourdfpy": "yourdfpy"}
DEFAULT_TIMEOUT = 30.0
DEFAULT_MEMORY = 2 * 1024**3
MESH_BOX = "0.1 0.1 0.1"


class Outcome(Record):
    """One consumer's verdict. status: loaded | rejected | crashed | timeout | memory | missing (not installed)."""

    _fields = ('consumer', 'status', 'message', 'location', 'changes', 'notes', 'seconds', 'facts')

    def __init__(self, consumer: str, status: str, message: str = "", location: Location | None = None,
                 changes=(), notes=(), seconds: float = 0.0, facts: dict | None = None):
        self.consumer, self.status, self.message, self.location = consumer, status, message, location
        self.changes, self.notes, self.seconds = list(changes), list(notes), seconds
        self.facts = {} if facts is None else facts

    @property
    def loaded(self) -> bool:
        return self.status == "loaded"

    def to_dict(self) -> dict:
        return {"consumer": self.consumer, "status": self.status, "message": clean_text(self.message, 2000),
                "location": None if self.location is None else {"file": self.location.file,
                                                                 "line": self.location.line},
                "changes": [clean_text(c, 2000) for c in self.changes], "notes": list(self.notes),
                "seconds": round(self.seconds, 3)}


def available(name: str) -> bool:
    if name == "urdfdom":
        return shutil.which("check_urdf") is not None
    if name == "sdformat":
        return shutil.which("ign") is not None
    import importlib.util

    try:
        return importlib.util.find_spec(MODULE[name]) is not None
    except (ImportError, ValueError):
        return False


def without_meshes(xml: str, folder: str | None = None) -> tuple[str, int]:
    """The document with every <mesh> file replaced, and how many were. With `folder`: each mesh points to a box
    STL written there, sized so that after the mesh's own `scale` it is a 0.1 m cube (the scale stays, so a
    consumer still reads and checks it); without: the <mesh> becomes a 0.1 m <box>."""
    from urdfcheck.core import xmlfront
    from urdfcheck.core.lxmlimport import etree

    try:
        root = etree.fromstring(re.sub(r"^\s*<\?xml[^>]*\?>", "", xml).encode("utf-8"), xmlfront.parser())
    except etree.XMLSyntaxError:
        return xml, 0  # the consumers get it as it is, and say what they think of it
    n = 0
    boxes: dict[tuple, str] = {}
    # by local name, whatever the namespace: MuJoCo's and PyBullet's readers ignore namespaces, so a
    # `<mesh xmlns="urn:x" filename="/abs/...">` is a mesh they open (issue 36); no file the model names is
    # ever handed to a consumer
    for mesh in [el for el in root.iter() if isinstance(el.tag, str) and etree.QName(el).localname == "mesh"]:
        parent = mesh.getparent()
        if parent is None:
            continue
        n += isinstance(parent.tag, str) and etree.QName(parent).localname == "geometry"
        if folder is None:
            box = etree.Element("box", size=MESH_BOX)
            box.tail = mesh.tail
            parent.replace(mesh, box)
            continue
        scale = _scale(mesh.get("scale"))
        if scale not in boxes:
            boxes[scale] = _box_stl(folder, [0.1 / s if s else 0.1 for s in scale], len(boxes))
        for name in [a for a in mesh.attrib if etree.QName(a).localname == "filename"]:
            del mesh.attrib[name]
        mesh.set("filename", boxes[scale])
    for el in root.iter():  # any other file the model names (a texture, a namespaced copy): dropped
        if not isinstance(el.tag, str) or etree.QName(el).localname == "mesh":
            continue
        for name in [a for a in el.attrib if etree.QName(a).localname == "filename"]:
            del el.attrib[name]
    return etree.tostring(root, encoding="unicode"), n


def _scale(text) -> tuple[float, float, float]:
    try:
        v = [abs(float(x)) for x in (text or "1 1 1").split()]
    except ValueError:
        return (1.0, 1.0, 1.0)
    return tuple(v) if len(v) == 3 and all(x < 1e6 for x in v) else (1.0, 1.0, 1.0)  # type: ignore[return-value]


def _box_stl(folder: str, size, index: int) -> str:
    """A binary STL box of the given size, centred at the origin (12 outward-facing triangles)."""
    import struct

    hx, hy, hz = (s / 2.0 for s in size)
    v = [(x, y, z) for x in (-hx, hx) for y in (-hy, hy) for z in (-hz, hz)]
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
             (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    data = bytearray(b"urdfcheck box".ljust(80, b" ")) + struct.pack("<I", len(faces))
    for a, b, c in faces:
        data += struct.pack("<3f", 0.0, 0.0, 0.0)
        for i in (a, b, c):
            data += struct.pack("<3f", *v[i])
        data += b"\0\0"
    path = os.path.join(folder, f"box{index}.stl")
    with open(path, "wb") as f:
        f.write(data)
    return path


# --- the jobs (run in the child; heavy imports happen there) -------------------------------------------------
def _mujoco_job(path: str) -> dict:
    # MuJoCo writes MUJOCO_LOG.TXT into the working directory on a warning: this child works in the model copy's
    # temporary folder, never in the user's tree
    os.chdir(os.path.dirname(os.path.abspath(path)))
    import mujoco

    try:
        m = mujoco.MjModel.from_xml_path(path)
    except Exception as e:  # the consumer's refusal is the answer, not a failure
        return {"rejected": str(e)}
    name = mujoco.mj_id2name
    jtypes = {0: "free", 1: "ball", 2: "slide", 3: "hinge"}
    return {"version": mujoco.__version__,
            "bodies": [name(m, mujoco.mjtObj.mjOBJ_BODY, i) or "" for i in range(m.nbody)],
            "joints": [(name(m, mujoco.mjtObj.mjOBJ_JOINT, i) or "", jtypes.get(int(m.jnt_type[i]), "?"))
                       for i in range(m.njnt)],
            "equalities": int(m.neq), "mass": [float(x) for x in m.body_mass]}


def _pinocchio_job(path: str) -> dict:
    import pinocchio

    try:
        m = pinocchio.buildModelFromUrdf(path)
    except Exception as e:
        return {"rejected": str(e)}
    return {"version": pinocchio.__version__, "joints": [str(n) for n in m.names][1:], "nq": int(m.nq),
            "nv": int(m.nv), "frames": [f.name for f in m.frames]}


def _pybullet_job(path: str) -> dict:
    import pybullet

    cid = pybullet.connect(pybullet.DIRECT)
    try:
        try:
            body = pybullet.loadURDF(path, physicsClientId=cid)
        except Exception as e:
            return {"rejected": str(e)}
        joints = []
        for i in range(pybullet.getNumJoints(body, physicsClientId=cid)):
            info = pybullet.getJointInfo(body, i, physicsClientId=cid)
            joints.append((info[1].decode(), int(info[2]), info[12].decode()))
        base = pybullet.getBodyInfo(body, physicsClientId=cid)[0].decode()
        masses = {base: pybullet.getDynamicsInfo(body, -1, physicsClientId=cid)[0]}
        for i, (_, _, link) in enumerate(joints):
            masses[link] = pybullet.getDynamicsInfo(body, i, physicsClientId=cid)[0]
        return {"version": "", "joints": joints, "base": base, "mass": masses}
    finally:
        pybullet.disconnect(physicsClientId=cid)


def _yourdfpy_job(path: str) -> dict:
    import yourdfpy

    try:
        u = yourdfpy.URDF.load(path, build_scene_graph=True, load_meshes=False, build_collision_scene_graph=False)
    except Exception as e:
        return {"rejected": f"{type(e).__name__}: {e}"}
    errors = []
    if not u.validate():
        errors = [str(e) for e in getattr(u, "errors", [])] or ["validate() returned False"]
    return {"version": getattr(yourdfpy, "__version__", ""), "joints": list(u.joint_map),
            "actuated": list(u.actuated_joint_names), "invalid": errors}


def _urdfdom_job(path: str, timeout: float) -> dict:
    import subprocess

    exe = shutil.which("check_urdf")
    proc = subprocess.run([exe, path], capture_output=True, text=True, timeout=timeout, env={"PATH": "/usr/bin:/bin"})
    text = (proc.stdout + proc.stderr).strip()
    if proc.returncode != 0:
        return {"rejected": text.splitlines()[-1] if text else f"exit status {proc.returncode}", "output": text}
    return {"version": "", "output": text}


def _sdformat_job(path: str, timeout: float) -> dict:
    """Gazebo's reading: sdformat's URDF converter (`ign sdf -p`), then its validation of the result (`ign sdf -k`),
    as Gazebo's loader validates it (Debian ignition-tools + libsdformat)."""
    import subprocess

    from urdfcheck.core import xmlfront
    from urdfcheck.core.lxmlimport import etree

    exe = shutil.which("ign")
    env = {"PATH": "/usr/bin:/bin", "HOME": os.path.dirname(path)}
    conv = subprocess.run([exe, "sdf", "-p", path], capture_output=True, text=True, timeout=timeout, env=env)
    noise = ("libignition-tools-backward", "No HOME defined")
    lines = [ln for ln in conv.stderr.splitlines() if ln.strip() and not any(n in ln for n in noise)]
    if conv.returncode != 0 or "<sdf" not in conv.stdout:
        return {"rejected": " ".join(lines[-3:]) or f"exit status {conv.returncode}"}
    sdf = os.path.join(os.path.dirname(path), "model.sdf")
    text = conv.stdout[conv.stdout.index("<sdf"):]
    with open(sdf, "w", encoding="utf-8") as f:
        f.write(text)
    check = subprocess.run([exe, "sdf", "-k", sdf], capture_output=True, text=True, timeout=timeout, env=env)
    # <gazebo> extension XML is copied as written, undeclared namespace prefixes included
    root = etree.fromstring(text.encode("utf-8"), xmlfront.parser(recover=True, huge=True))
    model = root.find("model") if root is not None else None
    links = [] if model is None else [lk.get("name") for lk in model.findall("link")]
    said = [ln for ln in (check.stdout + check.stderr).splitlines() if ln.strip() and not any(n in ln for n in noise)]
    if check.returncode != 0 or any("Error" in ln for ln in said):
        return {"rejected": " ".join(ln.strip() for ln in said if "Error" in ln)[:500] or "ign sdf -k failed"}
    if not links:
        return {"rejected": "no link left after conversion (every link without <inertial> or with mass 0 is "
                            "dropped with everything below it)"}
    joints = [(j.get("name"), j.get("type")) for j in model.findall("joint")]
    return {"version": "", "links": links, "joints": joints}


JOBS = {"mujoco": _mujoco_job, "pinocchio": _pinocchio_job, "pybullet": _pybullet_job,
        "yourdfpy": _yourdfpy_job, "urdfdom": _urdfdom_job, "sdformat": _sdformat_job}


# --- what changed -----------------------------------------------------------------------------------------------
def _changes(name: str, facts: dict, model) -> list[str]:
    movable = [j for j in model.joint_list if j.type != "fixed"]
    links = [lk.name for lk in model.link_list]
    out = []
    if name == "mujoco":
        bodies = set(facts["bodies"])
        fused = [n for n in links if n not in bodies and n != "world"]
        if fused:
            out.append(f"{len(fused)} link(s) fused into their parents or the world (fixed joints, fusestatic): "
                       + _few(fused))
        jnames = {n for n, _ in facts["joints"]}
        split = [j.name for j in movable if j.name not in jnames and f"{j.name}_TX" in jnames]
        if split:
            out.append(f"planar joint(s) {_few(split)} became two slides and a hinge (_TX, _TY, _RZ)")
        gone = [j.name for j in movable if j.name not in jnames and j.name not in split]
        if gone:
            out.append(f"movable joint(s) without a MuJoCo joint: {_few(gone)}")
        free = [n for n, t in facts["joints"] if t == "free"]
        if free:
            out.append(f"free joint(s): {_few(free)}")
        if facts["equalities"]:
            out.append(f"{facts['equalities']} equality constraint(s) (from <mimic>)")
    elif name == "pinocchio":
        names = set(facts["joints"])
        gone = [j.name for j in movable if j.name not in names]
        if gone:
            out.append(f"movable joint(s) not in the model: {_few(gone)}")
        dof = sum(1 for j in movable if j.type in ("revolute", "prismatic", "continuous"))
        if facts["nq"] != facts["nv"]:
            out.append(f"nq = {facts['nq']}, nv = {facts['nv']} (continuous joints take cos/sin, floating a "
                       "quaternion)")
        elif facts["nv"] != dof:
            out.append(f"nv = {facts['nv']} for {dof} one-degree-of-freedom joint(s)")
    elif name == "pybullet":
        named = {n for n, _, _ in facts["joints"]}
        gone = [j.name for j in movable if j.name not in named]
        if gone:
            out.append(f"movable joint(s) not in the body: {_few(gone)}")
        defaulted = [lk.name for lk in model.link_list if lk.inertial is None
                     and abs(facts["mass"].get(lk.name, 0.0) - 1.0) < 1e-12]
        if defaulted:
            out.append(f"{len(defaulted)} link(s) without <inertial> got mass 1 kg: {_few(defaulted)}")
    elif name == "sdformat":
        kept = set(facts["links"])
        gone = [n for n in links if n not in kept and n != "world"]
        if gone:
            out.append(f"{len(gone)} link(s) lumped into their parents (fixed joints) or dropped (no mass, with "
                       "everything below them): " + _few(gone))
        jnames = {n for n, _ in facts["joints"]}
        lost = [j.name for j in movable if j.name not in jnames]
        if lost:
            out.append(f"movable joint(s) not in the SDFormat model: {_few(lost)}")
    elif name == "yourdfpy":
        if facts.get("invalid"):
            out.append("validate() failed: " + "; ".join(facts["invalid"][:3]))
        act = set(facts.get("actuated", ()))
        mimic = [j.name for j in movable if j.mimic is not None and j.name not in act]
        if mimic:
            out.append(f"mimic joint(s) not actuated: {_few(mimic)}")
    return out


def _few(items, n: int = 6) -> str:
    items = list(items)
    return ", ".join(items[:n]) + (f" and {len(items) - n} more" if len(items) > n else "")


_NAMED = lazyre.compile(r"""(?:Element name|link|joint|body|Joint|Link)\s*[\[ '"]+([^\]'"]+)[\]'"]""")


def locate(message: str, model) -> Location | None:
    """The source line of the first link or joint the consumer's message names."""
    for m in _NAMED.finditer(message or ""):
        name = m.group(1).strip()
        part = model.joints.get(name) or model.links.get(name)
        if part is not None:
            return part.loc
    return None


# --- running ----------------------------------------------------------------------------------------------------
def run(model, xml: str, consumers=CONSUMERS, *, timeout: float = DEFAULT_TIMEOUT,
        memory: int | None = DEFAULT_MEMORY) -> list[Outcome]:
    """Each consumer's Outcome, in the order asked. Never raises for what a consumer does."""
    folder = tempfile.mkdtemp(prefix="urdfcheck-consumers-")
    text, meshes = without_meshes(xml, folder)
    notes = [f"{meshes} <mesh> file{'' if meshes == 1 else 's'} replaced by {MESH_BOX} m boxes for loading "
             "(their scale kept; mesh files are not read)"] if meshes else []
    path = os.path.join(folder, "model.urdf")
    try:
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        out = []
        for name in consumers:
            out.append(_one(name, path, model, timeout, memory, notes))
        return out
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def _one(name: str, path: str, model, timeout: float, memory, notes) -> Outcome:
    if not available(name):
        hint = {"urdfdom": "check_urdf (Debian liburdfdom-tools)",
                "sdformat": "ign sdf (Debian ignition-tools and libsdformat-dev)"}.get(
                    name, "pip install 'urdfcheck[consumers]'")
        return Outcome(name, "missing", f"not installed ({hint})")
    limits = worker.Limits(memory=memory, timeout=timeout, result=16 * 1024 * 1024)
    job = worker.prepare(JOBS[name], limits=limits, preload=(MODULE.get(name, "subprocess"),), capture="output",
                         name=name)
    job.send(*((path, timeout) if name in ("urdfdom", "sdformat") else (path,)))
    value = job.result()
    seconds = getattr(job, "seconds", 0.0) or 0.0
    if isinstance(value, worker.Failure):
        kind = value.kind if value.kind in ("timeout", "memory") else "crashed"
        tail = value.stderr.strip().splitlines()[-1:] if value.stderr else []
        return Outcome(name, kind, value.message + (f" ({tail[0]})" if tail else ""), notes=notes, seconds=seconds)
    if "rejected" in value:
        msg = value["rejected"]
        if name == "pinocchio" and "does not contain a valid URDF" in msg and job.stderr:
            msg = " ".join(line.strip() for line in job.stderr.splitlines() if line.strip().startswith("Error"))[:500] \
                or msg  # urdfdom says why on stderr
        return Outcome(name, "rejected", msg, locate(msg + " " + (job.stderr or ""), model), notes=notes,
                       seconds=seconds, facts=value)
    return Outcome(name, "loaded", "", changes=_changes(name, value, model), notes=notes, seconds=seconds,
                   facts=value)


def findings(outcomes, model) -> list[Finding]:
    """P090 for a refusal, P091 for a crash, time-out or out-of-memory: located where the message points."""
    out = []
    for o in outcomes:
        if o.status == "rejected":
            out.append(Finding("P090", Severity.ERROR, clean_text(f"{o.consumer} refuses the model: {o.message}"),
                               o.location or model.loc, name="consumer-rejected"))
        elif o.status in ("crashed", "timeout", "memory"):
            out.append(Finding("P091", Severity.ERROR, clean_text(f"{o.consumer} {o.status}: {o.message}"),
                               model.loc, name="consumer-failed"))
    return out
