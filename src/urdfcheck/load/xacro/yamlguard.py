"""Refuse YAML files that would blow up when xacro loads them (size, alias bombs)."""
from __future__ import annotations

from urdfcheck.core.yamlimport import yaml

MAX_BYTES = 8 * 1024 * 1024
MAX_NODES = 1_000_000
MAX_DEPTH = 256


class YamlRefused(Exception):
    def __init__(self, message: str):
        super().__init__(message)
        self.code = "X012"
        self.message = message


def expanded_size(node, memo=None) -> int:
    """Number of nodes the document has once aliases are expanded (aliases share node objects)."""
    memo = {} if memo is None else memo
    key = id(node)
    if key in memo:
        return memo[key]
    memo[key] = 1  # cycles count once
    if isinstance(node, yaml.SequenceNode):
        total = 1 + sum(expanded_size(n, memo) for n in node.value)
    elif isinstance(node, yaml.MappingNode):
        total = 1 + sum(expanded_size(k, memo) + expanded_size(v, memo) for k, v in node.value)
    else:
        total = 1
    memo[key] = min(total, MAX_NODES + 1)
    return memo[key]


def check_yaml_text(text: str, name: str = "YAML") -> None:
    if len(text) > MAX_BYTES:
        raise YamlRefused(f"{name} is larger than {MAX_BYTES} bytes")
    loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
    # nesting first, on the event stream (libyaml's parser is iterative; its composer recurses in C and a
    # 120 KB `? ? ? ... x` overflows the stack; PyYAML's own scanner is quadratic in the depth)
    depth = 0
    try:
        for ev in yaml.parse(text, Loader=loader):
            if isinstance(ev, (yaml.SequenceStartEvent, yaml.MappingStartEvent)):
                depth += 1
                if depth > MAX_DEPTH:
                    raise YamlRefused(f"{name} nests deeper than {MAX_DEPTH} levels")
            elif isinstance(ev, (yaml.SequenceEndEvent, yaml.MappingEndEvent)):
                depth -= 1
    except yaml.YAMLError as e:
        # libyaml >= 0.2.6 stops at its own depth limit with a scanner error; PyYAML's pure-Python loader, which
        # xacro uses, has no such limit and would recurse until RecursionError
        if "nesting depth" in str(e):
            raise YamlRefused(f"{name} nests deeper than {MAX_DEPTH} levels") from None
        return  # a syntax error: xacro's loader reports it
    if "&" not in text:
        return
    node = yaml.compose(text, Loader=loader)
    if node is not None and expanded_size(node) > MAX_NODES:
        raise YamlRefused(f"{name} expands to more than {MAX_NODES} nodes through aliases (a YAML bomb)")
