"""Hardened XML front end for untrusted model files.

lxml with entity resolution, DTD loading and network off. Constructs that parsers disagree on (a DOCTYPE,
entity declarations, processing instructions, trailing content) are refused as findings instead of being
"recovered" differently by each consumer.
"""
from __future__ import annotations

import re
from typing import NamedTuple

from lxml import etree

MAX_BYTES = 32 * 1024 * 1024
MAX_ELEMENTS = 2_000_000
# libxml2's own caps (no XML_PARSE_HUGE): nesting depth 256, a text or attribute value 10 MB
_LIMIT_ERRORS = ("Excessive depth", "too long", "Huge input lookup", "huge text node", "Resource limit exceeded")

_DECL = re.compile(rb"^(\xef\xbb\xbf)?\s*<\?xml(\s[^?]*)?\?>")
_DECL_ATTR = re.compile(rb"([A-Za-z_:][-\w.:]*)\s*=\s*[\"']([^\"']*)[\"']")
_SPACE = re.compile(rb"\s*")
_DOCTYPE_MSG = ("DOCTYPE declarations are not allowed in robot descriptions "
                "(entities expand differently in each ROS parser)")


class XmlIssue(NamedTuple):
    code: str
    message: str
    line: int | None = None
    column: int | None = None


class XmlRefused(Exception):
    """The document cannot be used; `issue` says why and where."""

    def __init__(self, issue: XmlIssue):
        super().__init__(issue.message)
        self.issue = issue


def _parser() -> etree.XMLParser:
    return etree.XMLParser(
        resolve_entities=False,
        no_network=True,
        load_dtd=False,
        dtd_validation=False,
        huge_tree=False,
        remove_comments=False,
        remove_pis=False,
        collect_ids=False,
    )


def _line_of(data: bytes, offset: int) -> int:
    return data.count(b"\n", 0, offset) + 1


def check_declaration(data: bytes) -> tuple[list[XmlIssue], bytes]:
    """Issues with the <?xml ...?> declaration, and the data to parse.

    TinyXML (urdfdom) accepts a malformed declaration such as `<?xml verison="1.0"?>` and so does the
    robot; we report it and parse the document with the declaration blanked out (lines unchanged).
    """
    m = _DECL.match(data)
    if not m:
        return [], data
    out = []
    body = m.group(2) or b""
    pairs = _DECL_ATTR.findall(body)
    attrs = {k.decode("latin-1"): v.decode("latin-1") for k, v in pairs}
    leftover = _DECL_ATTR.sub(b"", body).strip()
    odd = [k for k in attrs if k not in ("version", "encoding", "standalone")]
    start = m.start(0) + len(m.group(1) or b"")
    lead = data[start:m.end(0)].index(b"<?xml")
    line = _line_of(data, start + lead)
    if odd or leftover or "version" not in attrs:
        what = f"unknown attribute {odd[0]!r}" if odd else ("no version" if "version" not in attrs
                                                             else "stray text")
        out.append(XmlIssue("X003", f"malformed XML declaration ({what}); strict XML parsers reject the file", line))
    elif attrs["version"] != "1.0":
        out.append(XmlIssue("X003", f"XML declaration says version {attrs['version']!r}; ROS parsers expect 1.0",
                            line))
    if lead:  # urdfdom (TinyXML) reads on; libxml2, expat and so xacro stop at once
        out.append(XmlIssue("X003", f"the XML declaration is not at the start of the file ({lead} blank "
                                    "characters before it); urdfdom accepts this, but xacro and other strict XML "
                                    "parsers reject the file", line))
    enc = attrs.get("encoding")
    if enc is not None and enc.lower().replace("_", "-") not in ("utf-8", "utf8", "ascii", "us-ascii"):
        out.append(XmlIssue("X003", f"XML declaration says encoding {enc!r}; ROS tools read URDF as UTF-8", line))
    if not out:
        return out, data
    # parse what ROS parses: the bytes as UTF-8, whatever the declaration claims
    blank = bytes(b if b in b"\r\n" else 32 for b in data[start:m.end(0)])
    return out, data[:start] + blank + data[m.end(0):]


def _prolog_doctype(data: bytes, max_items: int = 1000) -> int | None:
    """Offset of a <!DOCTYPE in the prolog (after BOM, spaces, comments, PIs). A linear scan, not a regular
    expression (a lazy `<!--.*?-->` backtracks exponentially); None also when the prolog is too long to scan
    (libxml2 and the docinfo check below still refuse the DOCTYPE)."""
    i = 3 if data.startswith(b"\xef\xbb\xbf") else 0
    for _ in range(max_items):
        i = _SPACE.match(data, i).end()
        if data.startswith(b"<!DOCTYPE", i):
            return i
        end = b"?>" if data.startswith(b"<?", i) else b"-->" if data.startswith(b"<!--", i) else None
        j = data.find(end, i + 2) if end is not None else -1
        if j < 0:
            return None
        i = j + len(end)
    return None


def parse(data: bytes) -> tuple[etree._Element, list[XmlIssue]]:
    """Parse untrusted bytes. Returns (root, warnings); raises XmlRefused for unusable documents."""
    if len(data) > MAX_BYTES:
        raise XmlRefused(XmlIssue("X004", f"file is {len(data)} bytes; the limit is {MAX_BYTES}"))
    try:
        if not data.isascii():  # ASCII is UTF-8; decoding megabytes only to drop the result is not free
            data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise XmlRefused(XmlIssue("X001", f"invalid UTF-8 ({e.reason})", _line_of(data, e.start))) from None
    warnings, data = check_declaration(data)
    at = _prolog_doctype(data) if b"<!DOCTYPE" in data else None
    if at is not None:  # refuse before libxml2 reads entity declarations (amplification, external ones)
        raise XmlRefused(XmlIssue("X002", _DOCTYPE_MSG, _line_of(data, at)))
    try:
        root = etree.fromstring(data, _parser())
    except etree.XMLSyntaxError as e:
        line, col = (e.position if e.position else (e.lineno, None))
        msg = str(e.msg if hasattr(e, "msg") and e.msg else e)
        msg = re.sub(r",? line \d+, column \d+.*$", "", msg).strip()
        code = "X002" if "Extra content" in msg else "X001"
        if any(k in msg for k in _LIMIT_ERRORS):
            code = "X004"
        if code == "X002":
            msg = "content after the root element (a second root or trailing text)"
        raise XmlRefused(XmlIssue(code, f"malformed XML: {msg}", line or None, col or None)) from None
    except ValueError as e:  # e.g. unicode strings with an encoding declaration
        raise XmlRefused(XmlIssue("X001", f"malformed XML: {e}")) from None
    tree = root.getroottree()
    info = tree.docinfo
    if info.doctype or info.internalDTD is not None:
        raise XmlRefused(XmlIssue("X002", _DOCTYPE_MSG, 1))
    for sib in root.itersiblings(preceding=True):
        if isinstance(sib, etree._ProcessingInstruction):
            raise XmlRefused(XmlIssue("X002", f"processing instruction <?{sib.target}?> before the root element",
                                      sib.sourceline))
    for sib in root.itersiblings():
        if isinstance(sib, etree._ProcessingInstruction):
            raise XmlRefused(XmlIssue("X002", f"processing instruction <?{sib.target}?> after the root element",
                                      sib.sourceline))
    _check_shape(root, data)
    return root, warnings


def _check_shape(root: etree._Element, data: bytes) -> None:
    # Depth and attribute length are already capped by libxml2 without XML_PARSE_HUGE (depth 256, text
    # 10 MB; see _LIMIT_ERRORS); entity references need no check because without a DOCTYPE (refused above)
    # an undeclared entity is a syntax error. For the same reason every element and processing instruction
    # is written with its own "<" in the (UTF-8) bytes: counting bytes rules most documents out before any
    # walk of the tree, which costs a tenth of the parse on a large model.
    if data.count(b"<") > MAX_ELEMENTS and int(root.xpath("count(//*)")) > MAX_ELEMENTS:
        raise XmlRefused(XmlIssue("X004", f"more than {MAX_ELEMENTS} XML elements"))
    decl = _DECL.match(data)
    if data.find(b"<?", decl.end() if decl else 0) < 0:
        return
    for pi in root.iter(etree.ProcessingInstruction):
        raise XmlRefused(XmlIssue("X002", f"processing instruction <?{pi.target}?> inside the document",
                                  pi.sourceline))
