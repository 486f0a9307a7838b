"""T rules: TF ownership of a deployment (T001..T006), over the graph its analysis (`graph`, beside) builds.
"""
from __future__ import annotations

from urdfcheck.consumers.consumers import Consumers
from urdfcheck.consumers.consumers import consumers_of as consumers
from urdfcheck.consumers.tfclaims import claims_from_localization, claims_from_odom
from urdfcheck.core import lazyre
from urdfcheck.core.evidence import Step
from urdfcheck.core.findings import Problem
from urdfcheck.core.paths import shown
from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.rules.catalogue import check
from urdfcheck.rules.checks.tf.graph import (
    PublisherInfo,
    TFGraph,
    cycles,
    duplicate_owners,
    multiple_parents,
    not_one_tree,
    prefix_collisions,
    static_and_dynamic,
    untrusted_hint,
    vouched_claims,
)
from urdfcheck.rules.checks.tf.graph import deployment_graph as _graph
from urdfcheck.rules.checks.tf.graph import distinct_locations as _dedupe_locs

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context


# --- T001..T006: TF ownership ------------------------------------------------------------------------------
def _alternatives(p, c: Consumers) -> bool:
    """Discovered launch files of a package are often alternatives (sim/real): a conflict only between
    claims of different launch files is not reported unless the config says they run together."""
    if c.origin == "config" or not p.claims:
        return False
    if any(cl.source != "launch" for cl in p.claims):
        return False
    return len({cl.loc.file for cl in p.claims}) > 1


def _has_consumer_claims(g: TFGraph) -> bool:
    return any(cl.source != "model" for cl in g.claims)


def _as_problem(p, prefer_consumer: bool = True, hint: str = "") -> Problem:
    claims = list(p.claims)
    at = p.loc
    if at is None and claims:
        first = next((cl for cl in claims if cl.source != "model"), claims[0]) if prefer_consumer else claims[0]
        at = first.loc
    return Problem(p.message + hint, at=at, related=_dedupe_locs((cl.loc for cl in claims), at),
                   data={"frames": list(p.frames)})


def _tf_problems(model, ctx, analysis):
    """(problem, consumers) of one TF-graph analysis, skipping conflicts between launch-file alternatives."""
    c = consumers(model, ctx)
    g = _graph(model, c)
    if not _has_consumer_claims(g):
        return
    for p in analysis(g):
        if not _alternatives(p, c) and not _apart(p, model, c):
            yield p


def _apart(p, model, c: Consumers) -> bool:
    """A Gazebo plugin's claim against a controller's or driver's belong to different deployments unless those
    run in the simulator: the model loads ros2_control into Gazebo, or the one deployment read (a launch chain or
    a config's launch files) starts the simulator. Launch files found beside the model are often alternatives
    (sim and real), so they do not count."""
    sources = {cl.source for cl in p.claims}
    if "gazebo" not in sources or not sources & {"controller", "driver"}:
        return False
    from urdfcheck.consumers.gazebo import controllers_in_sim, launch_starts_sim

    if controllers_in_sim(model):
        return False
    return not (c.origin in ("deployment", "config") and launch_starts_sim(c.launch))


@check("T001", needs="consumers")
def duplicate_tf_owner(model: Model, ctx: Context) -> Iterator[Problem]:
    said = set()
    for p in _tf_problems(model, ctx, duplicate_owners):
        said.add(p.frames)
        yield _as_problem(p)
    yield from _unlaunched_duplicates(model, consumers(model, ctx), said)


_RL_ODOM_INPUT = lazyre.compile(r"^(odom|twist|pose)\d+$")


def _unlaunched_duplicates(model, c: Consumers, said: set):
    """T001 between parameter files of the model's package that no launch file of the deployment reads (a
    drive controller with enable_odom_tf and robot_localization with publish_tf, both on odom -> base_link).
    They claim nothing in the deployment's own graph; among themselves, two owners of one edge are a defect
    wherever they run together. That they do is evidence when the filter fuses the controller's odometry (its
    odomN input names the controller), else a guess from the package (said as info, naming how to confirm)."""
    ctrls = [ctl for ctl in c.controllers if getattr(ctl, "elsewhere", None) and ctl.odom_tf is not None]
    drivers = [d for d in c.drivers if getattr(d, "elsewhere", None) and getattr(d, "odom_tf", None) is not None]
    loc_nodes = list(getattr(c, "elsewhere_localization", ()) or ())
    if not loc_nodes and len(ctrls) + len(drivers) < 2:
        return
    base = c.frames.get("base", "base_link")
    g = TFGraph()
    g.extend(claims_from_odom((ctl.odom_tf for ctl in ctrls), base, "controller"))
    g.extend(claims_from_odom((d.odom_tf for d in drivers), base, "driver"))
    g.extend(claims_from_localization(loc_nodes))
    inputs = set()  # the topics the localization nodes fuse
    for n in loc_nodes:
        for key, v in (getattr(n, "values", None) or {}).items():
            if _RL_ODOM_INPUT.match(str(key)) and isinstance(getattr(v, "value", None), str):
                inputs.add(v.value.strip("/").split("/")[0])
    for p in duplicate_owners(g):
        if p.frames in said or len({cl.loc.file for cl in p.claims}) < 2:
            continue
        owners = {cl.owner for cl in p.claims if cl.source in ("controller", "driver")}
        fused = bool(owners) and owners <= inputs
        files = " and ".join(sorted({shown(cl.loc.file) for cl in p.claims}))
        steps = () if fused else (Step(
            "deployment", f"{files} together", "package",
            confirm="load both from the launch file that runs them (or name them in urdfcheck.yaml under the "
                    "model's controllers: and launch:)"),)
        got = _as_problem(p, hint=("; both in parameter files of the package that no launch file read here loads"
                                   + (" (the filter fuses the controller's odometry, so they run together)"
                                      if fused else "")))
        got.rests_on = steps
        yield got


@check("T002", needs="consumers")
def static_and_dynamic_tf(model: Model, ctx: Context) -> Iterator[Problem]:
    for p in _tf_problems(model, ctx, static_and_dynamic):
        yield _as_problem(p)


@check("T003", needs="consumers")
def tf_multiple_parents(model: Model, ctx: Context) -> Iterator[Problem]:
    c = consumers(model, ctx)
    for p in _tf_problems(model, ctx, multiple_parents):
        hint = ""
        child = p.frames[0] if p.frames else ""
        prefix = c.rsp_prefix
        link = child[len(prefix):] if prefix and child.startswith(prefix) else child
        if link in model.links and model.root and link != model.root and \
                any(cl.source in ("controller", "driver", "localization") for cl in p.claims):
            hint = (f"; {link} is not the model's root: publish odometry to {prefix}{model.root} "
                    f"(base_frame_id / base_link_frame)")
        yield _as_problem(p, hint=hint)


@check("T004", needs="consumers")
def tf_cycle(model: Model, ctx: Context) -> Iterator[Problem]:
    for p in _tf_problems(model, ctx, cycles):
        if not all(cl.source == "model" for cl in p.claims):  # the model's own cycle is S005
            yield _as_problem(p)


@check("T005", needs="consumers")
def tf_not_one_tree(model: Model, ctx: Context) -> Iterator[Problem]:
    c = consumers(model, ctx)
    g = _graph(model, c)
    if not _has_consumer_claims(g) or len(model.roots) > 1:
        return  # several roots in the model itself: S001
    # an untrusted config's declared owners do not join the trees (rules.checks.tf.graph.vouched_claims)
    plain = vouched_claims(g)
    for p in not_one_tree(plain, c.frames):
        got = _as_problem(p, hint=untrusted_hint(g, plain.frames) if not not_one_tree(g, c.frames) else "")
        got.absent = "publish the transform that joins them"
        yield got


@check("T006", needs="consumers")
def frame_prefix_collision(model: Model, ctx: Context) -> Iterator[Problem]:
    c = consumers(model, ctx)
    groups = [c.launch] if c.origin == "config" else [[li] for li in c.launch]  # discovered: per file
    for group in groups:
        pubs = [PublisherInfo(s.name, s.frame_prefix, s.loc, s.namespace)
                for li in group for s in li.state_publishers if not s.condition]
        for p in prefix_collisions(pubs):
            yield _as_problem(p, prefer_consumer=False)
