"""The evidence rule (issue 37): a finding is a warning or an error only if every planning step under it has evidence.

The planner makes choices a check then rests on: which file is a robot, which parameter file goes with which model,
which launch file is the deployment, which feature of a link is the wheel. Each choice is recorded as a `Step`,
saying how it was made (`how`). Some ways are evidence (the user or a config named it; a launch file runs it; a
plugin's `<parameters>`, an include or a `$(find)`/`package://` path names it; the file is a whole robot that
nothing includes; it is the only model of its package); the others are guesses (joint names overlap; same package
among several models; a feature picked by shape). A finding resting on a guess is said at info, naming its weakest
step and how to confirm it (`confirm`: the config line or reference that would make it evidence).

Steps ride on a target (`Target.evidence`: how the model and its deployment were chosen), on a consumer file
(how it was paired with the model) and on a `Problem` (`rests_on`: the pairings and features a check used). The
engine applies the rule in one place (`rules.engine`), as it applies the open-world rule; the JSON report lists
the steps of every finding.
"""
from __future__ import annotations

from urdfcheck.core.records import TupleRecord

# how a step was taken -> (is it evidence, words for a message)
HOW = {
    "named": (True, "named on the command line"),
    "config": (True, "named in the config"),
    "launched": (True, "run by a launch file"),
    "referenced": (True, "named by a reference (a plugin's <parameters>, an include, a $(find) or package:// path)"),
    "complete": (True, "a whole robot that no other file includes"),
    "only": (True, "the only model of its package"),
    # the file named on the command line is a fragment its robot includes only under these argument values: the
    # variant that reaches it is how that file is used (plan.plan.Planner.reaching, load.reach)
    "reaching": (True, "the argument values under which the robot includes the file named on the command line"),
    "overlap": (False, "paired by the joint names it shares with the model"),
    "package": (False, "paired only because it lies in the same package"),
    "probe": (False, "a file that may be a fragment of another model"),
    "shape": (False, "picked by its shape"),
    "guess": (False, "a guess"),
    # issue 37's precision pass (docs/triage.md): guesses the corpora showed
    # a discovered model no launch file runs: the values its required xacro arguments get are unknown
    "undeployed": (False, "no launch file of the checkout runs it, so the values of its required arguments are "
                          "unknown"),
    # boolean options flipped together (automatic variants): each option alone is linted as a variant of its own
    "combination": (False, "options set together in a way no launch file or config was seen to use"),
    # a controller configured in the deployment's parameter files that none of its (all read) spawners starts
    "idle": (False, "configured but not spawned by this deployment (another launch-argument choice may start it)"),
    # a launch-argument value other than the default (a variant) whose model reads a file that does not exist
    "choice": (False, "a launch-argument value other than the default, which may need other arguments its users give"),
    # a launch file that another launch file includes (the include not followed to it): the includer may pass it
    # other arguments than its defaults (plan.understood: a model path that does not exist)
    "included": (False, "a launch file that other launch files include, which may pass it other arguments"),
    # a xacro argument a launch file passes from a launch argument without default
    "required": (False, "a launch argument without default, which the launch file's users give"),
    # a package the checkout references but does not hold: the workspace's business (a dependency), unless the
    # runner named where it lives
    "outside": (False, "a package outside the checkout, which the workspace that builds it provides"),
}


class Step(TupleRecord):
    """One planning step a finding rests on.

    what: the kind of step ("model", "deployment", "parameters", "wheel"...); subject: what was chosen, as
    reports show it ("config/controllers.yaml for urdf/robot.urdf.xacro"); how: a key of HOW; confirm: how the
    user makes it evidence ("add it under models: in urdfcheck.yaml", "load it from a launch file")."""

    what: str
    subject: str
    how: str
    confirm: str = ""

    @property
    def strong(self) -> bool:
        return HOW.get(self.how, (False, ""))[0]

    def describe(self) -> str:
        return f"{self.what} {self.subject}: {HOW.get(self.how, (False, self.how))[1]}"

    def as_json(self) -> dict:
        out = {"what": self.what, "subject": self.subject, "how": self.how, "evidence": self.strong}
        if self.confirm:
            out["confirm"] = self.confirm
        return out


def weakest(steps) -> Step | None:
    """The first step without evidence, or None when every step has evidence."""
    for s in steps:
        if not s.strong:
            return s
    return None


def demotion(steps) -> str | None:
    """The words added to a finding said at info because a step under it is a guess, or None."""
    s = weakest(steps)
    if s is None:
        return None
    out = f"; said as info, since {s.describe()}"
    if s.confirm:
        out += f" (to confirm: {s.confirm})"
    return out
