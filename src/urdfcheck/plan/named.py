"""The deployments of one folder the user named: what the planner and the per-file hook's planning share."""
from __future__ import annotations

from urdfcheck.core.records import Record


class Named(Record):
    """The deployments of one folder the user named, found once for the whole tree.
    deployments: those with a model, minus those defined in a folder whose config declares its models;
    covered: the models (realpath) they load, which are then not linted alone."""

    _fields = ('root', 'deployments', 'covered')

    def __init__(self, root: str, deployments: list, covered: set):
        self.root, self.deployments, self.covered = root, deployments, covered
