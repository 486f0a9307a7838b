"""Write a Model's kinematics back as URDF (links by name, joints with origin, axis, limit, mimic).

Used to hand other tools (Pinocchio, yourdfpy) exactly the kinematics urdfcheck read, when the original
document is not available. Floats are written with repr() so they round-trip exactly.
"""
from __future__ import annotations

from xml.sax.saxutils import quoteattr


def _vec(v) -> str:
    return " ".join(repr(float(x)) for x in v)


def _rpy(origin):
    """rpy as written, or the rpy of a quaternion origin (URDF 1.1), which every reader understands."""
    if origin.quat is None:
        return origin.rpy
    from urdfcheck.core import geometry

    return geometry.rpy(geometry.origin_matrix(origin))


def model_to_urdf(model) -> str:
    out = [f"<robot name={quoteattr(model.name or 'robot')}>"]
    for name in model.links:
        out.append(f"  <link name={quoteattr(name)}/>")
    for j in model.joints.values():
        if j.parent is None or j.child is None:
            continue
        out.append(f"  <joint name={quoteattr(j.name)} type={quoteattr(j.type)}>")
        out.append(f"    <origin xyz={quoteattr(_vec(j.origin.xyz))} rpy={quoteattr(_vec(_rpy(j.origin)))}/>")
        out.append(f"    <parent link={quoteattr(j.parent)}/>")
        out.append(f"    <child link={quoteattr(j.child)}/>")
        if j.type not in ("fixed", "floating"):
            out.append(f"    <axis xyz={quoteattr(_vec(j.axis))}/>")
        lim = j.limit
        if lim is not None or j.type in ("revolute", "prismatic"):
            attrs = []
            for k in ("lower", "upper", "effort", "velocity"):
                v = getattr(lim, k, None) if lim is not None else None
                if v is None and k in ("effort", "velocity"):
                    v = 0.0
                if v is not None:
                    attrs.append(f"{k}={quoteattr(repr(float(v)))}")
            out.append(f"    <limit {' '.join(attrs)}/>")
        if j.mimic is not None:
            mult, off = repr(float(j.mimic.multiplier)), repr(float(j.mimic.offset))
            out.append(f"    <mimic joint={quoteattr(j.mimic.joint)} multiplier={quoteattr(mult)} "
                       f"offset={quoteattr(off)}/>")
        out.append("  </joint>")
    out.append("</robot>")
    return "\n".join(out) + "\n"
