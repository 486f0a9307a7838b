"""The argparse side of the command line: help formatters, the option types, and every command's options from the
one table (cli/options.py). Imported only to build a parser: a plain `urdfcheck lint [flags] PATH...` is read
without argparse (`cli.options.plain_lint`), whose import with gettext and locale and the lint parser's set-up cost
~4 ms of every lint."""
from __future__ import annotations

import argparse
import os
import sys


class Formatter(argparse.HelpFormatter):
    """argparse's help formatter, with the terminal width read the way shutil.get_terminal_size reads it but
    without importing shutil: argparse builds a formatter for every add_argument, and that import (with bz2,
    lzma, fnmatch) is 1.7 ms of every start-up."""

    def __init__(self, prog, indent_increment=2, max_help_position=24, width=None):
        super().__init__(prog, indent_increment, max_help_position, _columns() - 2 if width is None else width)


class RawFormatter(argparse.RawDescriptionHelpFormatter, Formatter):
    """The same, with descriptions and epilogs printed as written."""


def _columns() -> int:
    try:
        return int(os.environ["COLUMNS"])
    except (KeyError, ValueError):
        pass
    try:
        return os.get_terminal_size(sys.__stdout__.fileno()).columns
    except (AttributeError, ValueError, OSError):
        return 80


def kv(sep: str, what: str):
    """argparse type for NAME<sep>VALUE."""

    def parse(text: str):
        if sep not in text:
            raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}")
        k, v = text.split(sep, 1)
        if not k:
            raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}")
        return k, v

    return parse


def codes(text: str) -> list[str]:
    """argparse type: rule codes or prefixes, comma-separated."""
    out = [c.strip().upper() for c in text.split(",") if c.strip()]
    for c in out:
        if not (c == "ALL" or (c[0].isalpha() and (c[1:] == "" or c[1:].isdigit()))):
            raise argparse.ArgumentTypeError(f"{c!r} is not a rule code or prefix (e.g. S001, J, ALL)")
    return out


def severity(text: str):
    """argparse type: error, warning or info."""
    from urdfcheck.core.findings import Severity

    try:
        return Severity.parse(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


class _Choices:
    """A named list of choices (cli/options.py), imported when argparse first looks into it: a lint command line
    that does not name a target does not import the URDF grammar while parsing."""

    def __init__(self, name: str):
        self.name, self._items = name, None

    def _get(self):
        if self._items is None:
            from urdfcheck.cli.options import choices

            self._items = choices(self.name)
        return self._items

    def __contains__(self, item) -> bool:
        return item in self._get()

    def __iter__(self):
        return iter(self._get())


_TYPES = {"codes": codes, "severity": severity, "kv:=": kv(":=", "NAME:=VALUE"), "kv=": None, "float": float,
          "int": int}


def add_options(p: argparse.ArgumentParser, command: str, only=None) -> None:
    """`command`'s options from the one table (cli/options.py); `only`: the dests to add (a group of them)."""
    from urdfcheck.cli.options import for_command

    for o in for_command(command):
        if only is not None and o.dest not in only:
            continue
        kw: dict = {"dest": o.dest, "help": o.help}
        if o.value == "flag":
            kw.update(action="store_true", default=o.unset)
        else:
            kw.update(default=o.unset, metavar=o.metavar)
            if o.value == "append":
                kw["action"] = "append"
            if o.type == "kv=":
                kw["type"] = kv("=", o.metavar)
            elif o.type is not None:
                kw["type"] = _TYPES[o.type]
            if o.choices is not None:
                kw["choices"] = _Choices(o.choices)
                if o.choices == "targets":  # argparse would list them in the usage line: the grammar's import
                    kw["metavar"] = "DISTRO"
        p.add_argument(*o.flags, **kw)
