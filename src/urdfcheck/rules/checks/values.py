"""U rules: what the model builder could not read (reported where it was written)."""
from __future__ import annotations

from urdfcheck.core.findings import Problem
from urdfcheck.rules.catalogue import check


@check("U001", "U002", "U003", "U004", "U005", "U006")
def unreadable_values(model, ctx):
    for issue in model.issues:
        yield Problem(issue.message, at=issue.loc, code=issue.code)
