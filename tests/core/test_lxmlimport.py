"""core.lxmlimport: lxml.etree loads without inspect, and nothing that asks for inspect later notices."""
import subprocess
import sys

_CHECK = r"""
import sys
from urdfcheck.core import xmlfront
assert "inspect" not in sys.modules, "inspect was imported with lxml"

class Target:  # a parser target is what lxml's getfullargspec is for
    def __init__(self): self.seen = []
    def start(self, tag, attrib): self.seen.append(tag)
    def end(self, tag): pass
    def close(self): return self.seen

parser = xmlfront.etree.XMLParser(target=Target())
assert xmlfront.etree.fromstring(b"<robot><link/></robot>", parser) == ["robot", "link"]
import inspect
assert sys.modules["inspect"] is inspect and hasattr(inspect, "signature") and inspect.__file__
assert type(inspect).__name__ == "module"
print("ok")
"""


def _run(code: str) -> str:
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout


def test_lxml_loads_without_inspect_and_parser_targets_still_work():
    assert _run(_CHECK).strip() == "ok"


def test_inspect_imported_first_is_left_alone():
    code = ("import inspect, sys\nfrom urdfcheck.core.lxmlimport import etree\n"
            "assert sys.modules['inspect'] is inspect\nprint(etree.fromstring(b'<a/>').tag)")
    assert _run(code).strip() == "a"


def test_the_stand_in_answers_any_name():
    code = ("import sys\nfrom urdfcheck.core import lxmlimport\n"
            "later = lxmlimport._Later('inspect')\nsys.modules['inspect'] = later\n"
            "assert later.isfunction(len) is False and later.isbuiltin(len)\n"
            "assert sys.modules['inspect'] is not later\nprint('ok')")
    assert _run(code).strip() == "ok"
