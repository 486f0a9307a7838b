"""Records declare their fields once: a FrozenRecord without `__init__` gets one from `_fields`/`_defaults`."""
import pytest

from urdfcheck.core.records import FrozenRecord


class Pair(FrozenRecord):
    _fields = ("a", "b", "c")
    _defaults = {"c": 3}


def test_generated_init_takes_positions_keywords_and_defaults():
    assert Pair(1, 2) == Pair(a=1, b=2, c=3) == Pair(1, b=2)
    assert Pair(1, 2, 4).c == 4 and hash(Pair(1, 2)) == hash(Pair(1, 2, 3))
    with pytest.raises(TypeError):
        Pair(1)
    with pytest.raises(TypeError):
        Pair(1, 2, d=4)
    with pytest.raises(TypeError):
        Pair(1, 2, a=1)
    with pytest.raises(AttributeError):
        Pair(1, 2).a = 5
    assert repr(Pair(1, 2)) == "Pair(a=1, b=2, c=3)"


# --- TupleRecord: typing.NamedTuple's behaviour without evaluating annotations -------------------------------
from urdfcheck.core.records import TupleRecord  # noqa: E402


class _Part(TupleRecord):
    """A part."""

    name: str
    size: "UndefinedName" = 1.0  # noqa: F821 - a string annotation is never evaluated (typing would compile it)
    tags: tuple = ()

    @property
    def big(self) -> bool:
        return self.size > 10

    def renamed(self, name: str) -> "_Part":
        return self._replace(name=name)


def test_a_tuple_record_is_a_namedtuple_with_defaults_methods_and_properties():
    import pickle

    p = _Part("arm")
    assert p == ("arm", 1.0, ()) and isinstance(p, tuple) and p._fields == ("name", "size", "tags")
    assert _Part("a", 20).big and not p.big and p.renamed("b").name == "b"
    assert _Part(name="x", tags=(1,)).tags == (1,) and _Part.__doc__ == "A part."
    assert pickle.loads(pickle.dumps(p)) == p and _Part.__module__ == __name__
    with pytest.raises(AttributeError):
        p.name = "other"


def test_a_tuple_record_refuses_what_namedtuple_would_break():
    with pytest.raises(TypeError):
        class _Bad(TupleRecord):
            a: int = 0
            b: int

    with pytest.raises(AttributeError):
        class _Worse(TupleRecord):
            a: int

            def _replace(self):
                return self


def test_a_frozen_record_reads_its_values_once_and_pickles_as_before():
    """The values a FrozenRecord hashes and compares are read once (the sandbox hashes its limits for each
    expression); a pickled record equals and hashes like the original in a process with another hash seed."""
    import os
    import pickle
    import subprocess
    import sys

    from urdfcheck.load.xacro.safeeval import Limits

    reads = []

    class Counted(FrozenRecord):
        _fields = ("a", "b")

        def __getattribute__(self, name):
            if name in ("a", "b"):
                reads.append(name)
            return super().__getattribute__(name)

    x = Counted(1, (2, 3))
    for _ in range(5):
        hash(x)
        assert x == Counted(1, (2, 3)) and x != Counted(1, (2, 4))
    assert reads.count("a") == 1 + 5 + 5  # x once; each fresh record compared with it once
    assert repr(x) == "Counted(a=1, b=(2, 3))"
    limits = Limits(max_depth=50)
    assert {limits: 1}[Limits(max_depth=50)] == 1
    data = pickle.dumps(limits)
    code = ("import pickle, sys; from urdfcheck.load.xacro.safeeval import Limits; "
            f"got = pickle.loads({data!r}); print(got == Limits(max_depth=50), {{Limits(max_depth=50): 1}}.get(got))")
    env = dict(os.environ, PYTHONHASHSEED="12345")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=60)
    assert out.stdout.split() == ["True", "1"], out.stderr
