"""A fast yes/no on whether a document satisfies a JSON schema, before paying for jsonschema.

Importing jsonschema takes ~60 ms, as long as the rest of a small lint run; the config is read on every
run and is almost always valid. `verdict` evaluates the few keywords our config schema uses and answers
True (valid), False (invalid) or None (a keyword or value it does not know). Only True is acted upon:
anything else goes to jsonschema, which also writes the error message. tests/core/test_schemagate.py checks
that every True or False agrees with jsonschema's Draft 2020-12 validator.
"""
from __future__ import annotations

import re

# annotations that never affect validity
_ANNOTATIONS = frozenset({"$schema", "$id", "$defs", "title", "description", "$comment", "examples", "default"})
_TYPES = {
    "object": lambda v: isinstance(v, dict),
    "array": lambda v: isinstance(v, list),
    "string": lambda v: isinstance(v, str),
    "boolean": lambda v: isinstance(v, bool),
    "null": lambda v: v is None,
    "number": lambda v: isinstance(v, (int, float)) and not isinstance(v, bool),
    "integer": lambda v: (isinstance(v, int) and not isinstance(v, bool))
    or (isinstance(v, float) and v.is_integer()),
}


_JSON = (dict, list, str, bool, int, float, type(None))


class _Unknown(Exception):
    pass


def verdict(instance, schema: dict) -> bool | None:
    try:
        return _valid(instance, schema, schema)
    except (_Unknown, re.error, RecursionError):
        return None


def _valid(inst, schema, root) -> bool:
    if schema is True:
        return True
    if schema is False:
        return False
    if not isinstance(schema, dict):
        raise _Unknown
    ok = True
    for key, value in schema.items():
        if key in _ANNOTATIONS:
            continue
        check = _KEYWORDS.get(key)
        if check is None:
            raise _Unknown
        # evaluate every keyword: one that is unknown further on must still make the answer None
        ok = check(inst, value, schema, root) and ok
    return ok


def _type(inst, value, schema, root) -> bool:
    names = [value] if isinstance(value, str) else value
    if not all(n in _TYPES for n in names) or not isinstance(inst, _JSON):
        raise _Unknown  # e.g. a TOML date, or a Decimal that jsonschema counts as a number
    return any(_TYPES[n](inst) for n in names)


def _properties(inst, value, schema, root) -> bool:
    if not isinstance(inst, dict):
        return True
    return all([_valid(inst[k], sub, root) for k, sub in value.items() if k in inst])


def _additional(inst, value, schema, root) -> bool:
    if not isinstance(inst, dict):
        return True
    known = schema.get("properties", {})
    if "patternProperties" in schema:
        raise _Unknown
    return all([_valid(v, value, root) for k, v in inst.items() if k not in known])


def _required(inst, value, schema, root) -> bool:
    return not isinstance(inst, dict) or all(k in inst for k in value)


def _property_names(inst, value, schema, root) -> bool:
    return not isinstance(inst, dict) or all([_valid(k, value, root) for k in inst])


def _items(inst, value, schema, root) -> bool:
    if not isinstance(value, dict) and not isinstance(value, bool):
        raise _Unknown  # the array form belongs to older drafts
    return not isinstance(inst, list) or all([_valid(v, value, root) for v in inst])


def _pattern(inst, value, schema, root) -> bool:
    return not isinstance(inst, str) or re.search(value, inst) is not None


def _min_length(inst, value, schema, root) -> bool:
    return not isinstance(inst, str) or len(inst) >= value


def _minimum(inst, value, schema, root) -> bool:
    if not isinstance(value, (int, float)) or isinstance(value, bool):
        raise _Unknown
    return not isinstance(inst, (int, float)) or isinstance(inst, bool) or inst >= value


def _enum(inst, value, schema, root) -> bool:
    # jsonschema compares with `==` whenever a string is involved, but tells 1 from True: answer only for
    # all-string enums, where a non-string instance simply matches nothing
    if not all(isinstance(x, str) for x in value):
        raise _Unknown
    return isinstance(inst, str) and inst in value


def _const(inst, value, schema, root) -> bool:
    return _enum(inst, [value], schema, root)


def _one_of(inst, value, schema, root) -> bool:
    return [_valid(inst, sub, root) for sub in value].count(True) == 1


def _ref(inst, value, schema, root) -> bool:
    if not isinstance(value, str) or not value.startswith("#/") or "~" in value or "%" in value:
        raise _Unknown
    target = root
    for part in value[2:].split("/"):
        if not isinstance(target, dict) or part not in target:
            raise _Unknown
        target = target[part]
    return _valid(inst, target, root)


_KEYWORDS = {
    "type": _type, "properties": _properties, "additionalProperties": _additional, "required": _required,
    "propertyNames": _property_names, "items": _items, "pattern": _pattern, "minLength": _min_length,
    "minimum": _minimum, "enum": _enum, "const": _const, "oneOf": _one_of, "$ref": _ref,
}
