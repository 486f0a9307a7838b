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
MISSING, MISSING_NAME = "C025", "launch-model-missing"


def findings(deployments, settings, shown) -> list[Finding]:
    """One C021 per deployment without a model (`Deployment.model` None), under `settings`' selection; a C025
    instead where the launch file names a model file of the checkout that does not exist (`Deployment.missing`)."""
    sel = settings.selection
    if not deployments:
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
        if getattr(d, "missing", ""):
            if sel.enabled(MISSING):
                out.append(_missing(d, loc, sel, shown))
            continue
        if not sel.enabled(CODE):
            continue
        variant = f" [{d.variant}]" if d.variant else ""
        code = _source_line(loc)
        if code:
            why += f" (`{code}`)"
        model, rel, config = _config_line(d.launch.file, shown)
        msg = (f"{launch}{variant} starts robot_state_publisher, but {why}: the contracts of this deployment "
               f"(controllers, drivers, TF owners) are not checked; tell urdfcheck the model it runs in "
               f"{config}: `models: [{{path: {model}, launch: [{rel}]}}]`")
        where = loc._replace(file=shown(loc.file)) if loc is not None else Location(launch)
        out.append(Finding(CODE, sel.severity_of(CODE, Severity.INFO), clean_text(msg, 1000), where, name=NAME,
                           model=launch, variant=d.variant))
    return out


def _missing(d, loc, sel, shown) -> Finding:
    """C025: the launch file runs xacro on (or loads) a model file that is not there. It rests on the launch file
    being a deployment (evidence: it starts robot_state_publisher) run with its defaults; a launch-argument value
    other than the default may need files its users give (an info, core.evidence `choice`)."""
    from urdfcheck.core.evidence import Step
    from urdfcheck.rules import engine

    path = next((m for m, _ in reversed(d.notes) if m.startswith("model file ")), "")
    path = path[len("model file "):].rsplit(" not found in the workspace", 1)[0]
    launch = shown(d.launch.file)
    variant = f" [{d.variant}]" if d.variant else ""
    code = _source_line(loc)
    near = _nearest_model(d.missing, path)
    # the suggestion before the source line: a report may shorten a long message from its end
    msg = (f"{launch}{variant} gives robot_state_publisher the model file {path}, which does not exist"
           + (f" (did you mean {shown(near)}?)" if near else "") + ": the launch fails here, so nothing of this "
           "deployment starts" + (f" (`{code}`)" if code else ""))
    where = loc._replace(file=shown(loc.file)) if loc is not None else Location(launch)
    f = Finding(MISSING, sel.severity_of(MISSING, Severity.ERROR), clean_text(msg, 1000), where, name=MISSING_NAME,
                model=launch, variant=d.variant)
    if d.variant:  # a choice or a flipped boolean launch argument (a literal path: no "model=" file match)
        step = Step("deployment", f"{launch}{variant}", "choice", "name the arguments that value needs under "
                    "models: in urdfcheck.yaml")
    elif getattr(d, "included_elsewhere", False):  # its includer (not followed) may pass another model path
        step = Step("deployment", launch, "included", "lint the launch file that includes it")
    else:
        step = Step("deployment", launch, "launched")
    return engine.on_evidence([f], (step,))[0]


def _nearest_model(pkg: str, missing: str) -> str:
    """The model file of the package whose name is closest to the missing one (a misspelling, a renamed file)."""
    import difflib
    import os

    from urdfcheck.load.discover import discover

    try:
        found = discover(pkg)
    except OSError:
        return ""
    files = [*found.models, *found.probes]
    names = {os.path.basename(str(f)): str(f) for f in files}
    best = difflib.get_close_matches(os.path.basename(missing), list(names), n=1, cutoff=0.6)
    return names[best[0]] if best else ""


def _construct(d) -> tuple[str, Location | None]:
    """What was not understood, and where: the last note about the model (the planner writes it last)."""
    for msg, loc in reversed(d.notes):
        if "model" in msg:
            text = msg.replace("the model robot_state_publisher gets is not understood",
                               "the model it is given is not understood")
            return text, loc
    return "the model it is given is not understood", d.rsp


MAX_SNIPPET = 100


def _config_line(launch: str, shown) -> tuple[str, str, str]:
    """(model path, launch path, config file) for the config line that tells urdfcheck: paths relative to the
    launch file's package, where that config goes; the model named when the package holds exactly one."""
    import os
    from pathlib import Path

    from urdfcheck.load.discover import discover
    from urdfcheck.load.packages import enclosing_package

    pkg = enclosing_package(Path(os.path.abspath(launch)).parent)
    if pkg is None:
        return "<the model file>", shown(launch), "urdfcheck.yaml"
    try:
        models = discover(str(pkg)).models
    except OSError:
        models = ()
    model = os.path.relpath(models[0], pkg) if len(models) == 1 else "<the model file>"
    return model, os.path.relpath(os.path.abspath(launch), pkg), shown(os.path.join(pkg, "urdfcheck.yaml"))


def _source_line(loc: Location | None) -> str:
    """The line of the construct that was not understood: the first line from `loc` on (a few lines: the
    node's call) that names robot_description, else the line at `loc`; trimmed; "" when unreadable."""
    if loc is None or not loc.line or not loc.file:
        return ""
    from urdfcheck.core import door

    try:
        lines = door.read_bytes(loc.file, limit=4 * 1024 * 1024).decode("utf-8", "replace").splitlines()
    except (OSError, ValueError):
        return ""
    if loc.line > len(lines):
        return ""
    near = lines[loc.line - 1:loc.line + 8]
    line = next((x for x in near if "robot_description" in x or "robot_urdf" in x), near[0])
    text = " ".join(line.split()).replace("`", "'")
    return text if len(text) <= MAX_SNIPPET else text[:MAX_SNIPPET - 1] + "\u2026"
