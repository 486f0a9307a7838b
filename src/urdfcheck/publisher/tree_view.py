"""The TF tree robot_state_publisher builds from a model, as data, text, Mermaid, Graphviz dot or JSON."""
from __future__ import annotations

import json

from urdfcheck.core.findings import clean_text
from urdfcheck.publisher.kinematics import kinematic_tree


def publication(seg) -> str:
    """How robot_state_publisher publishes a segment: "static", "dynamic" or "none"."""
    if seg.kind == "skipped":
        return "none"
    return "dynamic" if seg.kind == "movable" else "static"


def tree_data(model, frame_prefix: str = "", profile="ros2") -> dict:
    from urdfcheck.publisher.state import get_profile

    prof = get_profile(profile)
    tree = kinematic_tree(model)
    pf = lambda f: prof.prefixed(frame_prefix, f)  # noqa: E731
    edges = []
    for s in tree.segments:
        e = {
            "parent": pf(s.parent),
            "child": pf(s.child),
            "joint": s.name,
            "type": s.type,
            "publication": publication(s),
        }
        if s.kind == "fixed" and publication(s) == "static":
            e["topic"] = "/tf_static" if prof.use_tf_static else "/tf"
        elif s.kind == "movable":
            e["topic"] = "/tf"
        if s.joint.mimic is not None:
            e["mimic"] = {"joint": s.joint.mimic.joint, "multiplier": s.joint.mimic.multiplier,
                          "offset": s.joint.mimic.offset}
        if s.zero_axis:
            e["warning"] = "zero axis: published as NaN"
        elif s.type == "planar":
            e["warning"] = "planar: published static at its origin"
        elif s.type == "floating":
            e["warning"] = "floating: not published"
        edges.append(e)
    return {
        "model": model.name,
        "roots": [pf(r) for r in tree.roots],
        "tf_roots": [pf(r) for r in tree.tf_roots],
        "edges": edges,
        "unreachable_joints": list(tree.unreachable),
        "notes": [{"code": n.code, "joint": n.joint, "message": n.message} for n in tree.notes],
    }


def _label(e) -> str:
    extra = ""
    if "mimic" in e:
        extra = f", mimic {e['mimic']['joint']}"
    return f"{e['joint']} ({e['type']}, {e['publication']}{extra})"


def render_text(data: dict) -> str:
    kids: dict[str, list] = {}
    for e in data["edges"]:
        kids.setdefault(e["parent"], []).append(e)
    lines = []

    def walk(frame, prefix):
        items = kids.get(frame, [])
        for i, e in enumerate(items):
            last = i == len(items) - 1
            warn = f"  ! {e['warning']}" if "warning" in e else ""
            lines.append(f"{prefix}{'└── ' if last else '├── '}{clean_text(e['child'])}  "
                         f"[{clean_text(_label(e))}]{warn}")
            walk(e["child"], prefix + ("    " if last else "│   "))

    for r in data["roots"]:
        lines.append(clean_text(r))
        walk(r, "")
    if data.get("unreachable_joints"):
        lines.append("unreachable joints: " + ", ".join(clean_text(j) for j in data["unreachable_joints"]))
    return "\n".join(lines)


def _mermaid_id(name: str, ids: dict) -> str:
    if name not in ids:
        ids[name] = f"n{len(ids)}"
    return ids[name]


def _mermaid_text(s: str) -> str:
    return clean_text(s).replace('"', "#quot;")


def render_mermaid(data: dict) -> str:
    ids: dict[str, str] = {}
    lines = ["graph TD"]
    frames = list(data["roots"]) + [e["child"] for e in data["edges"]]
    for f in frames:
        lines.append(f'    {_mermaid_id(f, ids)}["{_mermaid_text(f)}"]')
    for e in data["edges"]:
        arrow = "-.->" if e["publication"] != "dynamic" else "-->"
        if e["publication"] == "none":
            arrow = "--x"
        a, b = _mermaid_id(e["parent"], ids), _mermaid_id(e["child"], ids)
        lines.append(f'    {a} {arrow}|"{_mermaid_text(_label(e))}"| {b}')
    return "\n".join(lines)


def _dot_text(s: str) -> str:
    return clean_text(s).replace("\\", "\\\\").replace('"', '\\"')


def render_dot(data: dict) -> str:
    lines = ["digraph tf {", "  rankdir=TB;", "  node [shape=box];"]
    frames = list(dict.fromkeys(list(data["roots"]) + [e["child"] for e in data["edges"]]))
    for f in frames:
        lines.append(f'  "{_dot_text(f)}";')
    style = {"dynamic": "solid", "static": "dashed", "none": "dotted"}
    for e in data["edges"]:
        lines.append(f'  "{_dot_text(e["parent"])}" -> "{_dot_text(e["child"])}" '
                     f'[label="{_dot_text(_label(e))}", style={style[e["publication"]]}];')
    lines.append("}")
    return "\n".join(lines)


FORMATS = ("text", "mermaid", "dot", "json")  # what `render` renders: `urdfcheck tree --format` offers these


def render(model, fmt: str = "text", frame_prefix: str = "", profile="ros2") -> str:
    if fmt not in FORMATS:
        raise ValueError(f"unknown format {fmt!r} (choose from {', '.join(FORMATS)})")
    data = tree_data(model, frame_prefix, profile)
    if fmt == "json":
        return json.dumps(data, indent=2)
    if fmt == "mermaid":
        return render_mermaid(data)
    if fmt == "dot":
        return render_dot(data)
    return render_text(data)
