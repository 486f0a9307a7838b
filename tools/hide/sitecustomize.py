"""Make installed modules absent for one run, to check that tests needing them skip cleanly:

    URDFCHECK_HIDE=pinocchio PYTHONPATH=tools/hide:src python -m pytest tests/...

Every finder answers "no such module" for them (importlib.util.find_spec returns None, import raises
ModuleNotFoundError), as on a machine without them."""
import os
import sys

_HIDDEN = tuple(n for n in os.environ.get("URDFCHECK_HIDE", "").split(",") if n)


def _hidden(name):
    return isinstance(name, str) and name.split(".")[0] in _HIDDEN


def _hide(finder):
    real = finder.find_spec
    if isinstance(finder, type):
        def find_spec(cls, name, path=None, target=None):
            return None if _hidden(name) else real(name, path, target)
        finder.find_spec = classmethod(find_spec)
    else:
        def find_spec(name, path=None, target=None):
            return None if _hidden(name) else real(name, path, target)
        finder.find_spec = find_spec


for _f in sys.meta_path:
    _hide(_f)
