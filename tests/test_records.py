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
