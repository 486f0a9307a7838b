"""core.yamlimport: PyYAML's own patterns compile when first used, and every document reads as with stock PyYAML."""
import subprocess
import sys

# scalars of every implicit type of the core schema, a merge key, the "=" value, and a non-printable character
_DOCS = [
    "a: yes\nb: No\nc: ~\nd: null\ne: 0x1F\nf: 0o17\ng: 017\nh: 1_000\ni: -1.5e+3\nj: .inf\nk: .NaN\n",
    "t: 2001-12-14t21:59:43.10-05:00\nd: 2002-12-14\ns: '2002-12-14'\nv: =\n",
    "base: &b {x: 1, y: [1, 2]}\nderived:\n  <<: *b\n  y: 3\n",
    "joints: [left_wheel_joint, right_wheel_joint]\nwheel_radius: 0.1\nrate: 50\n",
    "bad: \"bell\x07\"\n",
]

_READ = r"""
import sys
{imp}
for text in {docs!r}:
    for loader in (yaml.SafeLoader, getattr(yaml, "CSafeLoader", yaml.SafeLoader)):
        try:
            print(repr(yaml.load(text, Loader=loader)))
        except yaml.YAMLError as e:
            print(type(e).__name__)
"""


def _run(code: str) -> str:
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout


def test_documents_read_as_with_stock_pyyaml():
    stock = _run(_READ.format(imp="import yaml", docs=_DOCS))
    ours = _run(_READ.format(imp="from urdfcheck.core.yamlimport import yaml", docs=_DOCS))
    assert ours == stock
    assert "ReaderError" in stock  # the pure-Python reader's non-printable check ran, and ran the same


def test_the_readers_pattern_is_compiled_only_when_used_and_others_as_usual():
    code = r"""
import re
real = re.compile
from urdfcheck.core.yamlimport import yaml
from urdfcheck.core import lazyre
assert re.compile is real
pattern = yaml.reader.Reader.NON_PRINTABLE
assert isinstance(pattern, lazyre.Pattern) and "search" not in vars(pattern)
yaml.load("a: 1", Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))
if hasattr(yaml, "CSafeLoader"):
    assert "search" not in vars(pattern)  # libyaml's reader: never compiled
yaml.safe_load("a: 1")
assert "search" in vars(pattern)  # the pure-Python reader used it
import base64, datetime
print("ok")
"""
    assert _run(code).strip() == "ok"


def test_yaml_imported_first_is_left_alone():
    code = ("import re, yaml\nfrom urdfcheck.core.yamlimport import yaml as ours\n"
            "assert ours is yaml and isinstance(yaml.reader.Reader.NON_PRINTABLE, re.Pattern)\nprint('ok')")
    assert _run(code).strip() == "ok"


def test_the_xacro_workers_preload_imports_pyyaml_through_ours():
    """xacro.substitution_args imports PyYAML: the worker's preload must reach it through our import first, or the
    patterns compile at import in the one process that always imports PyYAML (the xacro worker: ~10 ms)."""
    code = r"""
import importlib
from urdfcheck.load.xacro import SPARE_PRELOAD
from urdfcheck.load.xacro import expand
for name in SPARE_PRELOAD:
    importlib.import_module(name)
import yaml
from urdfcheck.core import lazyre
assert isinstance(yaml.reader.Reader.NON_PRINTABLE, lazyre.Pattern), "stock PyYAML import in the worker"
print("ok")
"""
    assert _run(code).strip() == "ok"
    preload = r"""
from urdfcheck.load.xacro import expand
expand.preload()
import yaml
from urdfcheck.core import lazyre
assert isinstance(yaml.reader.Reader.NON_PRINTABLE, lazyre.Pattern)
print("ok")
"""
    assert _run(preload).strip() == "ok"


def test_no_module_imports_pyyaml_around_ours():
    """`from yaml.x import y` loads the `yaml` package first, stock: every import of PyYAML goes through ours."""
    import ast
    from pathlib import Path

    import urdfcheck

    src = Path(urdfcheck.__file__).parent
    direct = []
    for path in sorted(src.rglob("*.py")):
        if path.name == "yamlimport.py":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
                [node.module or ""] if isinstance(node, ast.ImportFrom) and not node.level else []
            if any(n == "yaml" or n.startswith("yaml.") for n in names):
                direct.append(f"{path.relative_to(src)}:{node.lineno}")
    assert direct == []
