"""xacro's module state, saved once and put back after each in-process expansion (the fuzz harnesses expand
thousands of inputs in one process, where the real tool forks a fresh worker for each)."""
from __future__ import annotations


def snapshot():
    """Save xacro's pristine module state now; returns a function that restores it."""
    import xacro
    import xacro.substitution_args as subst

    saved_x, saved_s = dict(vars(xacro)), dict(vars(subst))
    saved_sym = dict(xacro._global_symbols)
    saved_ns = {k: dict(v) for k, v in xacro._global_symbols.items() if isinstance(v, dict)}
    units = getattr(xacro, "ConstructUnits", None)
    saved_units = units.__dict__.get("constructor") if units is not None else None

    def restore() -> None:
        vars(xacro).update(saved_x)
        vars(subst).update(saved_s)
        xacro._global_symbols.clear()
        xacro._global_symbols.update(saved_sym)
        for k, v in saved_ns.items():
            dict.clear(xacro._global_symbols[k])
            dict.update(xacro._global_symbols[k], v)
        if saved_units is not None:
            units.constructor = saved_units

    return restore
