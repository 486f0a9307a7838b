"""G rules: visual and collision geometry, meshes on disk, materials and colours."""
from __future__ import annotations

import fnmatch
import os
from pathlib import Path

from urdfcheck.core.findings import Problem
from urdfcheck.core.paths import shown
from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.rules.catalogue import check

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context

_REMOTE = ("http://", "https://", "ftp://")
_KNOWN_SHAPES = ("box", "cylinder", "sphere", "mesh", "capsule")


def _shapes(model):
    """(link, shape) for every visual and collision, in document order."""
    for link in model.link_list:
        for s in link.visuals + link.collisions:
            yield link, s


def _what(link, shape) -> str:
    named = f" {shape.name!r}" if shape.name else ""
    return f"{shape.kind}{named} of link {link.name!r}"


# --- G001 ------------------------------------------------------------------------------------------

def _base_dir(model, ctx) -> Path:
    entry = getattr(ctx.expanded, "entry", None) or model.source
    return Path(entry).parent


def _resolver(model, ctx):
    r = ctx.resolver
    if r is None:
        from urdfcheck.load.packages import Resolver

        r = Resolver(near=Path(model.source).resolve())
    return r


def _case_hint(path: Path, listing: dict) -> str:
    """A hint when the folder holds the file under another case (Windows and macOS exports: Base.STL)."""
    folder = path.parent
    names = listing.get(folder)
    if names is None:
        try:
            names = os.listdir(folder)
        except OSError:
            names = []
        listing[folder] = names
    low = path.name.lower()
    for n in names:
        if n.lower() == low and n != path.name:
            return f" (there is {n!r}: file names are case-sensitive)"
    return ""


@check("G001")
def mesh_not_found(model: Model, ctx: Context) -> Iterator[Problem]:
    """One finding per unique mesh URI (at its first use; the other uses are related locations)."""
    ignore = [str(p) for p in ctx.options["ignore"]]
    resolver = _resolver(model, ctx)
    base = _base_dir(model, ctx)
    uses: dict[str, list] = {}  # uri -> [(link, shape)], in document order
    for link, shape in _shapes(model):
        g = shape.geometry
        if g is not None and g.kind == "mesh" and g.filename and g.filename.strip():
            uses.setdefault(g.filename.strip(), []).append((link, shape))
    listing: dict = {}
    for uri, where in uses.items():
        problem = _mesh_verdict(uri, resolver, base, ignore, listing)
        if not problem:
            continue
        link, shape = where[0]
        more = len(where) - 1
        also = f" (and {more} more use{'s' if more > 1 else ''})" if more else ""
        yield Problem(f"mesh {_shown_uri(uri)!r} of the {_what(link, shape)}{also}: {problem}", at=shape.geometry,
                      related=tuple(s.geometry for _, s in where[1:]))


def _shown_uri(uri: str) -> str:
    """A mesh URI as reports show paths: `file:///$(find pkg)/m.dae` expands to the runner's absolute folder,
    which a report must not print (issue 37); the path after `file://` is shown like any path."""
    if uri.startswith("file://") and uri[len("file://"):].startswith("/"):
        path = "/" + uri[len("file://"):].lstrip("/")
        got = shown(path)
        return got if got != path else uri
    if os.path.isabs(uri):
        return shown(uri)
    return uri


def _mesh_verdict(uri: str, resolver, base: Path, ignore: list[str], listing: dict) -> str | None:
    if any(fnmatch.fnmatchcase(uri, pat) for pat in ignore):
        return None
    if uri.lower().startswith(_REMOTE):
        return None  # fetched over the network by resource_retriever; not checked offline
    if uri.startswith("package://") and uri[len("package://"):].startswith("/"):
        return ("the URI has no package name (package:/// with three slashes), which ROS's resource_retriever "
                "cannot resolve: write package://PACKAGE/path")
    path, problem = resolver.resolve_uri(uri, base)
    if path is None:
        if problem and problem.startswith("package "):
            name = uri[len("package://"):].partition("/")[0]
            return f"{problem}, so the mesh cannot be checked (pass --package {name}=PATH)"
        return (f"{problem or 'cannot resolve it'}; RViz and MoveIt (resource_retriever) read package://, "
                "file:// and http(s):// URIs")
    if not resolver.allowed(path):
        return ("the file is outside the package roots, not checked (a mesh outside the packages only exists on "
                "this machine: reference it with package://)")
    if os.path.isfile(path):
        return None
    if os.path.isdir(path):
        return f"{shown(path)} is a folder, not a mesh file"
    return f"file not found ({shown(path)}){_case_hint(Path(path), listing)}"


# --- G002 ------------------------------------------------------------------------------------------

@check("G002")
def non_positive_size(model: Model, ctx: Context) -> Iterator[Problem]:
    for link, shape in _shapes(model):
        g = shape.geometry
        if g is None:
            continue
        if g.kind == "box" and g.size is not None:
            x, y, z = g.size
            if x > 0 and y > 0 and z > 0:
                continue
            bad = [f"{axis}={v:g}" for axis, v in zip("xyz", g.size) if v <= 0]
            if bad:
                yield Problem(f"box of the {_what(link, shape)} has non-positive size {', '.join(bad)} "
                              f"(size=\"{' '.join(f'{v:g}' for v in g.size)}\")", at=g)
        elif g.kind in ("cylinder", "capsule", "sphere"):
            bad = []
            if g.radius is not None and g.radius <= 0:
                bad.append(f"radius={g.radius:g}")
            if g.kind != "sphere" and g.length is not None and g.length <= 0:
                bad.append(f"length={g.length:g}")
            if bad:
                yield Problem(f"{g.kind} of the {_what(link, shape)} has non-positive {', '.join(bad)}", at=g)
        elif g.kind == "mesh" and g.scale is not None:
            # a negative scale mirrors the mesh: a common, deliberate way to reuse left parts on the right
            # (Ogre flips face culling for negative scales, MuJoCo mirrors meshes the same way), not reported
            zero = [a for a, v in zip("xyz", g.scale) if v == 0]
            if zero:
                shown = " ".join(f"{v:g}" for v in g.scale)
                yield Problem(f"mesh scale=\"{shown}\" of the {_what(link, shape)} is zero along "
                              f"{', '.join(zero)}: the mesh collapses to a flat or empty shape (invisible in RViz, no "
                              "collision volume)", at=g)


# --- G003 ------------------------------------------------------------------------------------------

@check("G003")
def undefined_material(model: Model, ctx: Context) -> Iterator[Problem]:
    """urdfdom's rule: top-level <material>s are read first; then links in document order, and a visual's
    material name is looked up among the materials known so far. An inline <color>/<texture> registers the
    name; a name-only reference to an unknown material registers an empty (colourless) material under that
    name, which then also wins over a later inline definition."""
    top = {m.name: m for m in model.material_list}
    registered: dict[str, object] = {}  # name -> the visual MaterialRef that registered it
    empty_first: dict[str, object] = {}  # name -> the name-only reference that registered it empty
    inline_defs: dict[str, object] = {}  # name -> first inline definition anywhere
    for link in model.link_list:
        for v in link.visuals:
            ref = v.material
            if ref is not None and ref.name and (ref.rgba is not None or ref.texture):
                inline_defs.setdefault(ref.name, ref)
    for link in model.link_list:
        for v in link.visuals:
            ref = v.material
            if ref is None:
                continue
            if not ref.name:
                # name="" (SolidWorks exporter style) keeps its inline colour: urdfdom looks up only non-empty
                # names. A missing name attribute cannot be told apart here (the builder's concern).
                continue
            name = ref.name
            if name in top:
                m = top[name]
                if m.rgba is None and not m.texture:
                    yield Problem(f"material {name!r} used by the {_what(link, v)} is defined at the top level without "
                                  "<color> or <texture>: urdfdom logs an error and the visual gets no colour",
                                  at=ref, related=(m,))
                continue
            defined_inline = ref.rgba is not None or bool(ref.texture)
            if name in registered:
                if defined_inline and name in empty_first:
                    first = empty_first[name]
                    yield Problem(f"material {name!r} is defined here, but the {_what(link, v)} comes after a "
                                  "name-only reference to it: urdfdom keeps the first, colourless registration and "
                                  "ignores this colour", at=ref, related=(first,))
                continue
            registered[name] = ref
            if defined_inline:
                continue
            empty_first[name] = ref
            later = inline_defs.get(name)
            if later is not None:
                yield Problem(f"material {name!r} of the {_what(link, v)} is referenced by name before it is "
                              "defined (inline, in a later link): urdfdom registers the empty name first, so this "
                              "visual and the defining one both lose their colour; define it at the top level",
                              at=ref, related=(later,))
            else:
                yield Problem(f"material {name!r} of the {_what(link, v)} is never defined: no top-level "
                              "<material> and no visual defines it with <color> or <texture>, so urdfdom registers "
                              "a colourless material and RViz draws the visual in its default colour", at=ref)


# --- G004 ------------------------------------------------------------------------------------------

def _rgba_problem(rgba) -> str | None:
    if rgba is None:
        return None
    bad = [f"{c}={v:g}" for c, v in zip("rgba", rgba) if not 0.0 <= v <= 1.0]
    if not bad:
        return None
    text = f"rgba=\"{' '.join(f'{v:g}' for v in rgba)}\" has {', '.join(bad)} outside [0, 1]"
    if any(v > 1.0 for v in rgba) and all(0.0 <= v <= 255.0 for v in rgba):
        text += " (0-255 values? URDF colours are fractions: divide by 255)"
    return text


@check("G004")
def rgba_out_of_range(model: Model, ctx: Context) -> Iterator[Problem]:
    for m in model.material_list:
        p = _rgba_problem(m.rgba)
        if p:
            yield Problem(f"material {m.name!r}: {p}", at=m)
    for link in model.link_list:
        for v in link.visuals:
            ref = v.material
            if ref is None:
                continue
            p = _rgba_problem(ref.rgba)
            if p:
                yield Problem(f"material {ref.name!r} of the {_what(link, v)}: {p}", at=ref)


# --- G005 ------------------------------------------------------------------------------------------

@check("G005")
def missing_geometry(model: Model, ctx: Context) -> Iterator[Problem]:
    consequence = ("urdfdom rejects it and stops reading the link, so the link's remaining visuals and "
                   "collisions are lost")
    for link, shape in _shapes(model):
        g = shape.geometry
        if g is not None and g.kind in _KNOWN_SHAPES:
            continue
        what = _what(link, shape)
        if g is None:
            yield Problem(f"the {what} has no <geometry>: {consequence}", at=shape)
        elif g.kind == "":
            yield Problem(f"the <geometry> of the {what} is empty: {consequence}", at=g)
        elif g.kind not in _KNOWN_SHAPES:
            yield Problem(f"the <geometry> of the {what} holds <{g.kind}>, which is not a URDF shape (box, cylinder, "
                          f"sphere, mesh): {consequence}", at=g)


# --- G006 ------------------------------------------------------------------------------------------
@check("G006")
def self_collision_at_zero(model: Model, ctx: Context) -> Iterator[Problem]:
    """Collision shapes (primitives, and meshes read through the door) of two non-adjacent links interpenetrate at
    the zero configuration (coal, lazily)."""
    if sum(1 for link in model.link_list if link.collisions) < 2:
        return
    from urdfcheck.rules.meshes import reader
    from urdfcheck.rules.selfcollision import self_collisions

    entry = getattr(ctx.expanded, "entry", None) or model.source
    yield from self_collisions(model, str(entry) if entry else "", float(ctx.options["depth"]), reader(model, ctx))
