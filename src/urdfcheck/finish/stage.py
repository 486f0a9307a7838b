"""The finish of a run, after every target was checked: the baseline, one X013 per package, the deployments not
understood (C021), the level the run fails at, and the planner's own findings."""
from __future__ import annotations

from urdfcheck.core.findings import Finding
from urdfcheck.core.paths import shown
from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.finish.packages import missing_packages_once
from urdfcheck.finish.result import Result, dedupe
from urdfcheck.request.request import LintRequest, UsageError

if TYPE_CHECKING:
    from urdfcheck.plan.plan import Target


def finish_run(result: Result, request: LintRequest, targets: list[Target], noted: list[Finding]) -> Result:
    kept = result.by_target
    if request.baseline:
        from urdfcheck.finish import baseline

        try:
            new = {id(f) for f in baseline.filter_new(request.baseline, result.raw())}
        except (OSError, ValueError) as e:
            raise UsageError(f"cannot read baseline {request.baseline}: {e}") from None
        # a baseline is a file that hides findings: the runner names it, but its content may be the pull
        # request's, so the report says how many it hid (issue 36), never a bare "All checks passed"
        result.baselined = len(dedupe([f for fs in kept for f in fs if id(f) not in new]))
        kept = [[f for f in fs if id(f) in new] for fs in kept]
        result.findings = dedupe([f for fs in kept for f in fs])
    result._finished = (kept, missing_packages_once(result))
    not_understood(result, getattr(targets, "not_understood", ()), request)
    if request.fail_on is not None:
        result.fail_on = request.fail_on
    elif targets[0].settings is not None:
        result.fail_on = targets[0].settings.fail_on
    if noted:  # after the baseline: what lowers the guard is never accepted once and for all
        result.findings = sorted(result.findings + noted, key=Finding.sort_key)
    return result


def not_understood(result: Result, deployments, request: LintRequest) -> None:
    """Deployments whose model was not understood: C021 infos (issue 20), beside the targets' findings."""
    from urdfcheck.plan.understood import findings

    extra = findings(deployments, request.settings(None), shown)
    if extra:
        result.findings = sorted([*result.findings, *extra], key=Finding.sort_key)
