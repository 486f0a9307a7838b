"""Known extensions: element and attribute names that real consumers read although URDF does not define them.

The data is `extensions.yaml` beside this module (documented in docs/rules.md, U002/U003): per consumer, the
elements it reads under a URDF element and the attributes it reads on one, with the evidence. Such a name is
not reported as unknown (U002/U003); a near miss of one still is (`<dynamcis>` is a typo, not an extension).
Names a later URDF version defines (`<limit acceleration>`, URDF 1.2) are not extensions: model/grammar.py
knows them, by version (U008).

A consumer may also own a prefix (`drake:` for Drake): any element or attribute named `drake:...`, written
without an xmlns:drake declaration, is its extension (parent "*", name "drake:*" in the registry).

Read lazily, once: a model with no unknown names never loads it.
"""
from __future__ import annotations

import functools
import os

from urdfcheck.core.records import TupleRecord


class Extension(TupleRecord):
    consumer: str  # who reads it ("MuJoCo", "PyBullet")
    evidence: str = ""


@functools.lru_cache(maxsize=1)
def registry() -> dict[tuple[str, str, str], Extension]:
    """(kind, URDF element, name) -> Extension; kind "element" (a child of that element) or "attribute"."""
    from urdfcheck.core.yamlimport import yaml  # only when a model has a name URDF does not define

    with open(os.path.join(os.path.dirname(__file__), "extensions.yaml"), encoding="utf-8") as f:
        data = yaml.load(f, Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader)) or []
    out: dict[tuple[str, str, str], Extension] = {}
    for entry in data:
        ext = Extension(str(entry["consumer"]), " ".join(str(entry.get("evidence") or "").split()))
        for kind in ("elements", "attributes"):
            for parent, names in (entry.get(kind) or {}).items():
                for name in names:
                    out.setdefault((kind[:-1], str(parent), str(name)), ext)
        for prefix in entry.get("prefixes") or ():
            for kind in ("element", "attribute"):
                out.setdefault((kind, "*", f"{prefix}:*"), ext)
    return out


def known(kind: str, parent: str, name: str) -> Extension | None:
    """The extension that defines `name` as a child element (kind "element") or attribute (kind "attribute")
    of the URDF element `parent`, if any."""
    reg = registry()
    found = reg.get((kind, parent, name))
    if found is None and ":" in name:  # drake:foo with no xmlns:drake declared (core/xmlfront.py keeps the name)
        found = reg.get((kind, "*", name.split(":", 1)[0] + ":*"))
    return found


def names(kind: str, parent: str) -> set[str]:
    """Every known extension name of that kind under `parent` (for "did you mean" hints)."""
    return {n for (k, p, n) in registry() if k == kind and p == parent}


def entries() -> list[tuple[str, str, str, Extension]]:
    """(kind, parent, name, extension), for the rule docs."""
    return [(k, p, n, e) for (k, p, n), e in sorted(registry().items())]
