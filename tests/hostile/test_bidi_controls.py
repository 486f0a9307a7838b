"""Attack ("Trojan Source"): Unicode bidirectional controls (U+202E RIGHT-TO-LEFT OVERRIDE, isolates, marks) in a link
name, a file name or a xacro message make a report show text in another order than it has: in a terminal, a PR
annotation, a code-scanning page. Every report format shows them as the visible escape `\\u202e`, and the strings a
JSON or SARIF consumer parses hold no control either."""
import json

from hostile_arena import arena, formats  # noqa: F401 (fixture)

BIDI = ["\u202e", "\u202a", "\u202b", "\u202c", "\u202d", "\u2066", "\u2067", "\u2068", "\u2069", "\u200e", "\u200f",
        "\u061c"]
NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def _strings(node):
    if isinstance(node, str):
        yield node
    elif isinstance(node, dict):
        for k, v in node.items():
            yield k
            yield from _strings(v)
    elif isinstance(node, list):
        for v in node:
            yield from _strings(v)


def test_bidi_controls_are_escaped_in_every_format(arena):
    hidden = "".join(BIDI)
    urdf = arena.write(f"urdf/plain{BIDI[0]}.urdf", f'<robot name="r{hidden}">\n  <link name="a{hidden}b"/>\n'
                                                    f'  <link name="c"/>\n</robot>\n')
    xacro = arena.write(f"urdf/x{BIDI[5]}.urdf.xacro",
                        f'<robot name="v" {NS}>\n  <link name="a"/>\n'
                        f'  <link name="${{xacro.fatal(\'evil{hidden}\')}}"/>\n</robot>\n')
    for fmt in formats():
        r = arena.lint(urdf, xacro, fmt=fmt)
        for c in BIDI:
            assert c not in r.out and c not in r.err, (fmt, hex(ord(c)))
        assert "\\u202e" in r.out, fmt  # shown, escaped: the reader sees that something is there
        if fmt in ("json", "sarif"):
            for s in _strings(json.loads(r.out)):
                assert not any(c in s for c in BIDI), (fmt, s)
