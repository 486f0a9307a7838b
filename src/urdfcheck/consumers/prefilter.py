"""Which parameter files found beside a model are worth parsing: a look at their bytes, before PyYAML.

In a package with several models, zero-config discovery (`consumers.consumers.discover_consumers`) keeps a parameter
file for a model only when one of its values names a joint of that model (`_names_a_joint`); a file that fails
to parse is dropped there without a word. So a file whose bytes hold none of the model's joint names cannot be
kept, and is not parsed: example-robot-data's 69 models share one package whose YAML files name none of the
UR5's joints, and linting the UR5 imported PyYAML and parsed them for nothing.

What the bytes cannot rule out passes: an escape sequence (`"shoulder\\x5fpan_joint"` is a joint name), a NUL
byte or a UTF-16/32 byte-order mark (text in another encoding), an empty name, a name with a space or a quote (YAML
can write it folded or doubled), a file that cannot be read or is over the
readers' cap. A file that passes is parsed and judged exactly as before. A package with one model keeps every
parameter file and reports the ones it cannot read (C007), so there every file is parsed as before.

tests/consumers/test_prefilter.py runs this against every YAML file of the corpus and the examples: for each string
value a file holds (each joint name that would keep it), the file passes.
"""
from __future__ import annotations

_UNSURE = (b"\\", b"\x00")
_WIDE_BOMS = (b"\xff\xfe", b"\xfe\xff", b"\x00\x00\xfe\xff")
LIMIT = 2 * 1024 * 1024  # consumers.yamlsrc.MAX_BYTES (not imported: it imports PyYAML)


def may_name(data: bytes, names) -> bool:
    """False only when no value of a YAML file with these bytes can equal one of `names`."""
    if data.startswith(_WIDE_BOMS) or any(u in data for u in _UNSURE):
        return True
    for n in names:
        if not n or any(c.isspace() or c in "'\"" for c in n):  # "", folded lines, '' in quotes: not in bytes
            return True
        if n.encode("utf-8", "surrogateescape") in data:
            return True
    return False


def worth_parsing(path, names) -> bool:
    """`may_name` for a file; True when it cannot be read or is over the cap (its reader says why)."""
    from urdfcheck.core import door

    try:
        data = door.read_bytes(path, limit=LIMIT)
    except OSError:
        return True
    return len(data) > LIMIT or may_name(data, names)
