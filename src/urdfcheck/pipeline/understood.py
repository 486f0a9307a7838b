"""Deployments not understood are findings (issue 20): C021, info, in every report format.

A launch file that starts robot_state_publisher with a model urdfcheck cannot read (a model read with
`FileContent(...)`, a path built with `$(eval find(pkg) + ...)`, a file name built from a launch argument,
a robot_description from another package's helper function, a URDF generated at calibration time) is a
deployment whose contracts go unchecked. Saying so only in `--list` hid it; each becomes one finding at the
construct, naming the launch file and the config lines that tell urdfcheck which model it runs.
"""
from __future__ import annotations

from urdfcheck.core.findings import Finding, Location, Severity, clean_text

CODE, NAME = "C021", "deployment-not-understood"


def findings(deployments, settings, shown) -> list[Finding]:
    """One C021 per deployment without a model (`Deployment.model` None), under `settings`' selection."""
    sel = settings.selection
    if not deployments or not sel.enabled(CODE):
        return []
    out, seen = [], set()
    for d in deployments:
        if d.launch is None:
            continue
        why, loc = _construct(d)
        launch = shown(d.launch.file)
        key = (launch, why, str(loc))
        if key in seen:
            continue
        seen.add(key)
        variant = f" [{d.variant}]" if d.variant else ""
        msg = (f"{launch}{variant} starts robot_state_publisher, but {why}: the contracts of this deployment "
               f"(controllers, drivers, TF owners) are not checked; tell urdfcheck the model it runs in "
               f"urdfcheck.yaml: `models: [{{path: <the model file>, launch: [{launch}]}}]`")
        where = loc._replace(file=shown(loc.file)) if loc is not None else Location(launch)
        out.append(Finding(CODE, sel.severity_of(CODE, Severity.INFO), clean_text(msg, 1000), where, name=NAME,
                           model=launch, variant=d.variant))
    return out


def _construct(d) -> tuple[str, Location | None]:
    """What was not understood, and where: the last note about the model (the planner writes it last)."""
    for msg, loc in reversed(d.notes):
        if "model" in msg:
            text = msg.replace("the model robot_state_publisher gets is not understood",
                               "the model it is given is not understood")
            return text, loc
    return "the model it is given is not understood", d.rsp
