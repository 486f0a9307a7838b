"""xacro as a library, in the sandbox: `expand` (run in the worker), `safeeval` (the evaluator), `yamlguard`.

The names below are what the console needs to fork the xacro worker before it imports anything else
(`cli.main`): the spare's key, the modules it imports while waiting, and the function a job calls.
"""

from urdfcheck.core import lazyre

# the source marker the expander puts on every element (file index, line, macro call chain); the loader reads it
# and strips it (these live here so that reading them does not import the expander and xacro)
SRC_ATTR = "__ucsrc"
STRIP_RE = lazyre.compile(r' __ucsrc="[^"]*"')

# one xacro expansion's allowance in its worker (the request's default, the loader's, the console's spare)
XACRO_TIMEOUT = 20.0  # wall-clock seconds
XACRO_MEMORY = 2 * 1024**3  # bytes of address space on top of what the worker inherits


def worker_limits(trusted: bool, allow_env=(), timeout: float = XACRO_TIMEOUT, memory: int = XACRO_MEMORY):
    """The `core.worker.Limits` an expansion runs under: the loader starts its worker with these, and the console
    forks its spare with them (a spare with other limits is not used)."""
    from urdfcheck.core import worker

    return worker.Limits(memory=memory, timeout=timeout, scrub_env=not trusted, env_keep=tuple(allow_env))


SPARE = "xacro"
# PyYAML first, through our import (its patterns compile on first use): xacro.substitution_args imports it too;
# xacro through ours (without its command-line module)
SPARE_PRELOAD = ("urdfcheck.core.yamlimport", "urdfcheck.load.xacro.xacroimport", "xacro.substitution_args",
                 "urdfcheck.load.xacro.expand", "urdfcheck.load.xacro.safeeval", "urdfcheck.load.xacro.yamlguard")
EXPAND = "urdfcheck.load.xacro.expand:expand_with"  # (path, options as a dict)
EXPAND_BATCH = "urdfcheck.load.xacro.expand:expand_batch"  # ([(path, options, limits), ...], also)
BATCH_GRACE = 5.0  # seconds the spare has past its expansions' own time-out to report them all


def batch_children(n: int) -> int:
    """How many of a batch's `n` expansions the spare forks a child for; it expands the others itself, one after
    another. A child per core the console and the spare leave idle: on two cores (a CI runner) the run is bound
    by CPU, and a child's fork, page copies and exit cost ~5% of a cold lint for no time gained (issue 38: the
    CPU of xacro then check_urdf per variant); with more cores the expansions run side by side. The console
    reads the same count for the spare's deadline (`loader.Batch.send`)."""
    import os

    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        cores = os.cpu_count() or 1
    return max(0, min(n - 1, cores - 2))
