"""The mesh file a model's <mesh> names, read through core.meshfile (U012 and G006). A URI that does not resolve,
a file outside the run's packages, a missing file (the corpora ship none) or a format that is not read gives None:
the rules that measure meshes then say nothing about that shape."""
from __future__ import annotations

import os
from pathlib import Path

from urdfcheck.core import meshfile


def reader(model, ctx):
    """`read(geometry) -> Mesh | None` for the model's meshes, resolved as G001 resolves them."""
    entry = getattr(getattr(ctx, "expanded", None), "entry", None) or model.source
    base = Path(entry).parent  # relative mesh names are the model file's neighbours
    resolver = getattr(ctx, "resolver", None)
    if resolver is None:
        from urdfcheck.load.packages import Resolver

        resolver = Resolver(near=Path(model.source).resolve())
    seen: dict[str, meshfile.Mesh | None] = {}

    def read(g):
        uri = (g.filename or "").strip() if g is not None and g.kind == "mesh" else ""
        if not uri or os.path.splitext(uri)[1].lower() not in meshfile.FORMATS:
            return None
        if uri not in seen:
            seen[uri] = _read(uri, resolver, base)
        return seen[uri]

    return read


def _read(uri: str, resolver, base: Path):
    if resolver is None or uri.lower().startswith(("http://", "https://", "ftp://")):
        return None
    try:
        path, _ = resolver.resolve_uri(uri, base)
    except (OSError, ValueError):
        return None
    if path is None or not resolver.allowed(path) or not os.path.isfile(path):
        return None
    return meshfile.read(path)
