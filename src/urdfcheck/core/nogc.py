"""Run the steps that build a large model, or index it, without the cyclic garbage collector.

A 10,000-link model is some 400,000 small tuples with not one reference cycle among them. Left to the
collector, they would be traced again on every promotion from generation to generation while they are
built, and then by the collections that follow: about a third of the lint time of such a model, all of
it for nothing.
"""
from __future__ import annotations

import gc


def call(fn, *args, long_lived: bool = False):
    """`fn(*args)` with the collector paused. `long_lived`: what it leaves behind stays (a model), so it is
    filed with the oldest generation at once: freeze, then unfreeze, moves every tracked object there
    without tracing any, where otherwise the next collections would trace it on its way up."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        return fn(*args)
    finally:
        if enabled:
            gc.enable()
        if long_lived and gc.get_freeze_count() == 0:  # not when the program keeps objects frozen itself
            gc.freeze()
            gc.unfreeze()
