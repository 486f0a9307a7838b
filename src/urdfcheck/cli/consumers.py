"""`urdfcheck consumers MODEL [--consumer NAMES]`: load the expanded model into each installed consumer (MuJoCo,
Pinocchio, PyBullet, yourdfpy, urdfdom's check_urdf) in the sandboxed worker, and report per consumer: loaded or
refused (its message, at the source line it names), and what it changed. Exit 1 when a consumer refused the model
or failed (crash, time-out, out of memory); 0 otherwise (a consumer that is not installed is a note)."""
from __future__ import annotations

import json
import sys

from urdfcheck.cli.common import EXIT_CLEAN, EXIT_FINDINGS
from urdfcheck.cli.common import UsageError as _Usage
from urdfcheck.cli.parsing import add_options


def _run(fn):
    from urdfcheck.cli.publish import _run as run

    return run(fn)


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("consumers",
                              help="load the model into MuJoCo, Pinocchio, PyBullet, yourdfpy, urdfdom, sdformat",
                              description=__doc__.split("\n\n")[0])
    p.add_argument("model", metavar="MODEL")
    p.add_argument("--consumer", default=None, metavar="NAMES",
                   help="comma-separated: mujoco, pinocchio, pybullet, yourdfpy, urdfdom, sdformat (default: all)")
    p.add_argument("--format", choices=FORMATS, default="text")
    p.add_argument("--consumer-timeout", type=float, default=None, metavar="SECONDS",
                   help="wall-clock and CPU limit for each consumer (default 30)")
    p.add_argument("--consumer-memory", type=float, default=None, metavar="GIB",
                   help="address space each consumer may add (default 2 GiB)")
    add_options(p, "consumers")
    p.set_defaults(func=_run(cmd_consumers))


def _names(text: str | None) -> tuple[str, ...]:
    from urdfcheck.verify.consumers import CONSUMERS

    if not text:
        return CONSUMERS
    names = tuple(dict.fromkeys(n.strip().lower() for n in text.split(",") if n.strip()))
    for n in names:
        if n not in CONSUMERS:
            raise _Usage(f"unknown consumer {n!r} (use one of {', '.join(CONSUMERS)})")
    return names


def cmd_consumers(ns) -> int:
    from urdfcheck.cli.publish import _load
    from urdfcheck.verify import consumers as C

    names = _names(ns.consumer)
    loaded = _load(ns, want_xml=True)
    if loaded is None:
        return EXIT_FINDINGS
    model, xml = loaded
    if model is None or xml is None:
        raise _Usage(f"cannot expand {ns.model}")
    kw = {}
    if ns.consumer_timeout is not None:
        kw["timeout"] = ns.consumer_timeout
    if ns.consumer_memory is not None:
        kw["memory"] = int(ns.consumer_memory * 1024**3)
    outcomes = C.run(model, xml, names, **kw)
    found = C.findings(outcomes, model)
    sys.stdout.write(render(ns.format, ns.model, outcomes, found))
    return EXIT_FINDINGS if found else EXIT_CLEAN


FORMATS = ("text", "json", "markdown")  # what `render` renders: the --format choices above


def render(fmt: str, model_path: str, outcomes, found) -> str:
    from urdfcheck.report import finish_text

    if fmt not in FORMATS:
        raise ValueError(f"unknown format {fmt!r} (choose from {', '.join(FORMATS)})")

    return finish_text(_render(fmt, model_path, outcomes, found), fmt)


def _render(fmt: str, model_path: str, outcomes, found) -> str:
    from urdfcheck.core.findings import clean_text
    from urdfcheck.report.markdown import code, md

    if fmt == "json":
        return json.dumps({"model": clean_text(model_path, 4096), "consumers": [o.to_dict() for o in outcomes],
                           "findings": [{"code": f.code, "name": f.name, "severity": str(f.severity),
                                         "message": f.message, "location": {"file": f.location.file,
                                                                            "line": f.location.line}}
                                        for f in found]}, indent=2) + "\n"
    where = {id(o): o.location for o in outcomes}
    if fmt == "markdown":
        lines = [f"## Consumers of `{code(model_path)}`", "", "| consumer | result | message / changes |",
                 "| --- | --- | --- |"]
        for o in outcomes:
            detail = o.message if not o.loaded else "; ".join(o.changes) or "no change"
            loc = f" ({where[id(o)]})" if where[id(o)] is not None else ""
            lines.append(f"| {md(o.consumer)} | {md(o.status)} | {md(detail, 800)}{md(loc)} |")
        notes = sorted({n for o in outcomes for n in o.notes})
        return "\n".join(lines + ([""] + [f"- {md(n)}" for n in notes] if notes else [])) + "\n"
    lines = []
    for o in outcomes:
        head = f"{o.consumer:10s} {o.status}"
        if o.status != "loaded":
            loc = f"{where[id(o)]}: " if where[id(o)] is not None else ""
            lines.append(f"{head}: {loc}{clean_text(o.message, 800)}")
        else:
            lines.append(head + (": " + "; ".join(clean_text(c, 400) for c in o.changes) if o.changes else
                                 " (no change)"))
    for n in sorted({n for o in outcomes for n in o.notes}):
        lines.append(f"note: {n}")
    return "\n".join(lines) + "\n"
