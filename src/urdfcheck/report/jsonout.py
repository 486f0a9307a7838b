"""JSON report, schema `urdfcheck.schemas/report.schema.json` (version 1)."""
from __future__ import annotations

import json

from urdfcheck.core.findings import clean_text
from urdfcheck.core.paths import shown

SCHEMA_VERSION = 1


def location(loc) -> dict:
    out = {"file": clean_text(loc.file, 4096), "line": loc.line, "column": loc.column}
    if loc.via:
        out["via"] = [{"file": clean_text(v.file, 4096), "line": v.line} for v in loc.via]
    return out


def as_dict(result) -> dict:
    from urdfcheck import __version__

    counts = {"error": 0, "warning": 0, "info": 0}
    for f in result.findings:
        counts[str(f.severity)] += 1
    root = getattr(result, "root", "")
    return {
        "schema_version": SCHEMA_VERSION,
        "tool": {"name": "urdfcheck", "version": __version__},
        "models": [{"path": clean_text(shown(t.path, root), 4096), "variant": clean_text(t.variant),
                    "args": {k: clean_text(shown(v, root) if str(v).startswith("/") else v)  # a file: relative
                             for k, v in sorted(t.args.items())}} for t in result.targets],
        "summary": counts,
        "findings": [
            {
                "code": f.code,
                "name": f.name,
                "severity": str(f.severity),
                "message": clean_text(f.message),
                "location": location(f.location),
                "related": [location(r) for r in f.related],
                "model": clean_text(f.model, 4096),
                "variant": clean_text(f.variant),
                # every model/variant the same problem was found in (one entry when just `model`/`variant`)
                "where": [{"model": clean_text(p.model, 4096), "variant": clean_text(p.variant),
                           **({"message": clean_text(p.message)} if p.message else {})} for p in f.places()],
                # the same problem at other lines of the file (one finding, each place kept)
                **({"also": [{"location": location(a.location), "message": clean_text(a.message)}
                             for a in f.also]} if f.also else {}),
                # the consumer whose behaviour the finding predicts (--profile; rules/checks/profiles)
                **({"profile": f.profile} if f.profile else {}),
                # every active profile whose consumer refuses or changes the model for this finding
                **({"profiles": list(f.profiles)} if len(f.profiles) > 1 else {}),
                # the planning steps it rests on (core.evidence): how the model, parameter files, features were chosen
                **({"evidence": [{k: clean_text(v) if isinstance(v, str) else v for k, v in s.as_json().items()}
                                 for s in f.evidence]} if f.evidence else {}),
            }
            for f in result.findings
        ],
    }


def render(result, **_) -> str:
    return json.dumps(as_dict(result), indent=2, sort_keys=True) + "\n"
