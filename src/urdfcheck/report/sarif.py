"""SARIF 2.1.0 for GitHub code scanning (`github/codeql-action/upload-sarif`) and other SARIF viewers.

One run; the rule metadata (name, summary, rationale, fix and examples) comes from the catalogue, so
code scanning shows the same help as `urdfcheck rules CODE`. Paths below the working directory are
relative URIs against `%SRCROOT%` (run urdfcheck from the repository root); others are `file://` URIs.
`partialFingerprints` hash code + file + message (line numbers removed), never the line, so an alert
survives lines moving; identical findings in one file get an occurrence number.
"""
from __future__ import annotations

import hashlib
import json
import os
from collections import Counter
from pathlib import PurePosixPath
from urllib.parse import quote

from urdfcheck.core.findings import Location, Severity, clean_text

SCHEMA_URI = "https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/sarif-schema-2.1.0.json"
INFORMATION_URI = "https://pypi.org/project/urdfcheck/"
FINGERPRINT = "urdfcheck/v1"
LEVELS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}


def information_uri() -> str:
    """The project's Homepage/Repository URL when the installed metadata has one."""
    try:
        from importlib.metadata import PackageNotFoundError, metadata

        urls = metadata("urdfcheck").get_all("Project-URL") or []
    except (ImportError, PackageNotFoundError, OSError):
        urls = []
    for want in ("homepage", "repository", "source", "documentation"):
        for item in urls:
            label, _, url = item.partition(",")
            if label.strip().lower() == want and url.strip().startswith(("http://", "https://")):
                return url.strip()
    return INFORMATION_URI


def artifact(file: str) -> dict:
    """artifactLocation for a display path: relative -> %SRCROOT%, absolute -> file:// URI. The name is not
    cleaned: percent-encoding leaves nothing to interpret, and the URI must name the file's own bytes for code
    scanning to find it (a name that is not UTF-8 included)."""
    if os.path.isabs(file):
        from pathlib import Path

        try:
            return {"uri": Path(file).as_uri()}
        except (ValueError, UnicodeError):
            pass
    posix = file.replace(os.sep, "/").replace("\\", "/")
    posix = str(PurePosixPath(posix)) if posix else "."
    # a file name that is not UTF-8 keeps its own bytes, percent-encoded (surrogateescape gives them back)
    return {"uri": quote(posix.encode("utf-8", "surrogateescape"), safe="/-._~"), "uriBaseId": "%SRCROOT%"}


def physical(loc: Location) -> dict:
    out: dict = {"artifactLocation": artifact(loc.file)}
    if loc.line and loc.line > 0:
        region = {"startLine": int(loc.line)}
        if loc.column and loc.column > 0:
            region["startColumn"] = int(loc.column)
        out["region"] = region
    return out


def _rule(r) -> dict:
    from urdfcheck.rules import docs as ruledocs

    return {
        "id": r.code,
        "name": r.name,
        "shortDescription": {"text": " ".join(r.summary.split())},
        "fullDescription": {"text": " ".join(r.rationale.split()) or " ".join(r.summary.split())},
        "help": {"text": ruledocs.help_text(r), "markdown": ruledocs.help_markdown(r)},
        "defaultConfiguration": {"level": LEVELS[r.severity]},
        "properties": {"tags": [r.family], "problem.severity": str(r.severity)},
        **({"helpUri": r.references[0]["url"]} if r.references else {}),
    }


def _fallback_rule(code: str, name: str) -> dict:
    return {"id": code, "name": name or code, "shortDescription": {"text": name or code},
            "defaultConfiguration": {"level": "warning"}}


def fingerprint(f) -> str:
    from urdfcheck.finish.baseline import normalise_message, portable_path

    text = "\x1f".join([f.code, portable_path(f.location.file), normalise_message(f.message)])
    return hashlib.sha256(text.encode("utf-8", "surrogateescape")).hexdigest()[:32]


def _where(f, totals, describe) -> str:
    where = describe(f, totals)
    return f" [{clean_text(where)}]" if where else ""


def as_dict(result) -> dict:
    from urdfcheck import __version__
    from urdfcheck.rules import catalogue as rulebook

    cat = rulebook.catalogue()
    rules = [_rule(cat[c]) for c in sorted(cat)]
    index = {r["id"]: i for i, r in enumerate(rules)}
    for f in result.findings:
        if f.code not in index:
            index[f.code] = len(rules)
            rules.append(_fallback_rule(f.code, f.name))

    from urdfcheck.finish.collapse import describe, variant_totals

    totals = variant_totals(result.targets, result.root)
    seen: Counter = Counter()
    results = []
    for f in result.findings:
        fp = fingerprint(f)
        seen[fp] += 1
        related = []
        for v in f.location.via:
            related.append({"id": len(related) + 1, "physicalLocation": physical(v),
                            "message": {"text": "expanded from this xacro macro call"}})
        for r in f.related:
            related.append({"id": len(related) + 1, "physicalLocation": physical(r),
                            "message": {"text": "related location"}})
        for a in f.also:
            related.append({"id": len(related) + 1, "physicalLocation": physical(a.location),
                            "message": {"text": "the same problem again: " + clean_text(a.message)}})
        item = {
            "ruleId": f.code,
            "ruleIndex": index[f.code],
            "level": LEVELS[f.severity],
            "message": {"text": (clean_text(f.message) or f.code) + _where(f, totals, describe)},
            "locations": [{"physicalLocation": physical(f.location)}],
            "partialFingerprints": {FINGERPRINT: f"{fp}:{seen[fp]}"},
        }
        if related:
            item["relatedLocations"] = related
        props = {}
        if f.model:
            props["model"] = clean_text(f.model, 4096)
        if f.variant:
            props["variant"] = clean_text(f.variant)
        if props:
            item["properties"] = props
        results.append(item)

    return {
        "$schema": SCHEMA_URI,
        "version": "2.1.0",
        "runs": [{
            "tool": {"driver": {
                "name": "urdfcheck",
                "version": __version__,
                "semanticVersion": __version__,
                "informationUri": information_uri(),
                "rules": rules,
            }},
            "columnKind": "unicodeCodePoints",
            "results": results,
        }],
    }


def render(result, **_) -> str:
    return json.dumps(as_dict(result), indent=2, ensure_ascii=False) + "\n"
