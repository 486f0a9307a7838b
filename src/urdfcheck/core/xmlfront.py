"""Hardened XML front end for untrusted model files.

lxml with entity resolution, DTD loading and network off. Constructs that parsers disagree on (a DOCTYPE,
entity declarations, processing instructions, trailing content) are refused as findings instead of being
"recovered" differently by each consumer.

Namespaces are read as urdfdom (TinyXML2, namespace-unaware) reads them: elements in a default namespace get
their local names, and an undeclared prefix (Drake's `drake:...`) is accepted, the name keeping its prefix;
each is an X005 warning where yourdfpy, urdf_parser_py or xacro read it differently.
"""
from __future__ import annotations

import re

from urdfcheck.core import bytescan, lazyre
from urdfcheck.core.lxmlimport import etree
from urdfcheck.core.records import TupleRecord

MAX_BYTES = 32 * 1024 * 1024
MAX_ELEMENTS = 2_000_000
# libxml2's own caps (no XML_PARSE_HUGE): nesting depth 256, a text or attribute value 10 MB
_LIMIT_ERRORS = ("Excessive depth", "too long", "Huge input lookup", "huge text node", "Resource limit exceeded")

_DECL = lazyre.compile(rb"^(\xef\xbb\xbf)?\s*<\?xml(\s[^?]*)?\?>")
_DECL_ATTR = lazyre.compile(rb"([A-Za-z_:][-\w.:]*)\s*=\s*[\"']([^\"']*)[\"']")
_SPACE = lazyre.compile(rb"\s*")
_DEFAULT_NS = lazyre.compile(rb"xmlns\s*=")  # a literal start: a fast scan of large files
_UNDECLARED = lazyre.compile(r"Namespace prefix (\S+) (?:for \S+ )?on \S+ is not defined\s*")
_NS_UNDEFINED = etree.ErrorTypes.NS_ERR_UNDEFINED_NAMESPACE
_NCNAME = lazyre.compile(r"[A-Za-z_][\w.-]*", re.ASCII)
_START_NAME = lazyre.compile(rb"<[^\s/>!?]+")
_DOCTYPE_MSG = ("DOCTYPE declarations are not allowed in robot descriptions "
                "(entities expand differently in each ROS parser)")


class XmlIssue(TupleRecord):
    code: str
    message: str
    line: int | None = None
    column: int | None = None


class XmlRefused(Exception):
    """The document cannot be used; `issue` says why and where."""

    def __init__(self, issue: XmlIssue):
        super().__init__(issue.message)
        self.issue = issue


def options(*, recover: bool = False, comments: bool = True, huge: bool = False) -> dict:
    """The one set-up of lxml's parsers for everything urdfcheck reads: no entity resolved, no DTD loaded, no
    network, no ids collected, libxml2's size limits kept. `comments=False` drops comments and processing
    instructions; `huge` lifts the size limits, only for XML a real consumer wrote from the model."""
    return dict(recover=recover, resolve_entities=False, no_network=True, load_dtd=False, dtd_validation=False,
                huge_tree=huge, remove_comments=not comments, remove_pis=not comments, collect_ids=False)


def parser(*, recover: bool = False, comments: bool = True, huge: bool = False) -> etree.XMLParser:
    return etree.XMLParser(**options(recover=recover, comments=comments, huge=huge))


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
        if j < 0 or end is None:
            return None
        i = j + len(end)
    return None


def precheck(data: bytes) -> tuple[list[XmlIssue], bytes]:
    """What `parse` checks on the bytes before libxml2 reads them (size, UTF-8, the declaration, a DOCTYPE):
    (warnings, the bytes to parse); raises XmlRefused."""
    if len(data) > MAX_BYTES:
        raise XmlRefused(XmlIssue("X004", f"file is {len(data)} bytes; the limit is {MAX_BYTES}"))
    try:
        if not data.isascii():  # ASCII is UTF-8; decoding megabytes only to drop the result is not free
            data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise XmlRefused(XmlIssue("X001", f"invalid UTF-8 ({e.reason})", _line_of(data, e.start))) from None
    warnings, data = check_declaration(data)
    at = _prolog_doctype(data) if bytescan.has(data, b"<!DOCTYPE", 1) else None
    if at is not None:  # refuse before libxml2 reads entity declarations (amplification, external ones)
        raise XmlRefused(XmlIssue("X002", _DOCTYPE_MSG, _line_of(data, at)))
    return warnings, data


def parse(data: bytes) -> tuple[etree._Element, list[XmlIssue]]:
    """Parse untrusted bytes. Returns (root, warnings); raises XmlRefused for unusable documents."""
    warnings, data = precheck(data)
    try:
        strict = parser()
        try:
            root = etree.fromstring(data, strict)
        except etree.XMLSyntaxError as e:
            root, ns_warnings = _undeclared_prefixes(data, e, strict.error_log)
            warnings = warnings + ns_warnings
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
    if _DEFAULT_NS.search(data):
        warnings = warnings + _drop_default_namespace(root)
    return root, warnings


# --- large documents, read as they are parsed -------------------------------------------------------------------
# libxml2's tree of a URDF takes about 13 KiB per link (some 630 bytes an element), twice what the model takes:
# a large model is built from the document's top-level elements as the parser completes them, each dropped
# once read, so the whole tree never exists. Only where that reads the same as `parse`: nothing `parse` would
# refuse, warn about or rewrite after libxml2 is done may be in the bytes; any error of libxml2's on the way
# is the caller's cue to read the document whole with `parse`, which reports it as usual.
STREAM_BYTES = 2_000_000  # about 2,000 links: below, the tree costs little and `parse` is faster


def streamable(data: bytes) -> bool:
    """Whether `stream` reads `data` as `parse` would (the caller has passed it through `precheck`)."""
    if len(data) < STREAM_BYTES or bytescan.has(data, b"<!DOCTYPE", 1) or _DEFAULT_NS.search(data):
        return False
    decl = _DECL.match(data)
    if bytescan.find(data, b"<?", decl.end() if decl else 0, 1) >= 0:  # a processing instruction: `parse` refuses it
        return False
    return data.count(b"<") <= MAX_ELEMENTS


# the root's children a model is built from: lxml tests tags in C, so only these cost a Python object each
_PARTS = ("link", "joint", "material", "transmission", "gazebo", "ros2_control")


def stream(data: bytes):
    """The root element (its attributes read; its children still coming), then each child of the root, in
    document order, once it is whole; a child is removed when the next one is asked for. Raises
    etree.XMLSyntaxError."""
    pull = etree.XMLPullParser(events=("end",), tag=_PARTS, **options())
    root = None
    whole: list = []  # the root once the parser is closed
    for el in _ends(pull, data, whole):
        parent = el.getparent()
        if root is None:
            root = _top(el)
            yield root
        if parent is not root:  # nested (a <joint> of a <transmission>), or the root itself
            continue
        yield from _drain(root, el)  # children of other names before it (U002's), then it
    if root is None:
        root = whole[0]
        yield root
    yield from _drain(root, None)


# libxml2's push parser is fed this much at a time: iterparse reading the same bytes takes about a third longer,
# and much larger pieces are slower again (libxml2 scans a piece for the end of a tag from its start)
_PIECE = 32768


def _ends(pull, data: bytes, whole: list):
    for i in range(0, len(data), _PIECE):
        pull.feed(data[i:i + _PIECE])
        for _, el in pull.read_events():
            yield el
    whole.append(pull.close())
    for _, el in pull.read_events():
        yield el


def _top(el):
    while True:
        parent = el.getparent()
        if parent is None:
            return el
        el = parent


def _drain(root, last):
    """Hand out and remove the root's children up to `last` (all of them with None)."""
    while len(root):
        first = root[0]
        yield first
        del root[0]
        if first is last:
            return


def _undeclared_prefixes(data: bytes, err: etree.XMLSyntaxError, log) -> tuple[etree._Element, list[XmlIssue]]:
    """Read a document whose only fault is an undeclared namespace prefix (`<drake:joint_lower_limit>`,
    `drake:foo="..."` with no xmlns:drake) as the namespace-unaware consumers do: urdfdom and MuJoCo (TinyXML2)
    and Drake read `drake:foo` as a plain name. libxml2 reports these in its NAMESPACE domain and builds the
    tree anyway (the document stays well-formed), but lxml raises. Re-raises `err` for anything else.

    Only NS_ERR_UNDEFINED_NAMESPACE is accepted, and not on its word: after a namespace error libxml2 leaves
    some fatal errors unlogged (content after the root element), so the document is first parsed again, strictly
    and with the same hardening, with the prefixes declared on its root element (inserted on the same line:
    line numbers unchanged); any error there is reported as usual. The tree returned is libxml2's recovered one,
    whose names keep their prefix ("drake:foo") as TinyXML2 reads them."""
    prefixes: dict[str, int | None] = {}
    at = _root_name_end(data)
    for _ in range(8):  # libxml2 logs at most 100 errors: a prefix first used later shows up in the next pass
        _add_undeclared(prefixes, log, err)
        if at is None:
            raise err
        decl = "".join(f' xmlns:{p}="urn:urdfcheck:undeclared:{p}"' for p in prefixes).encode("ascii")
        strict = parser()
        try:
            etree.fromstring(data[:at] + decl + data[at:], strict)  # raises what a strict parser finds besides
            break
        except etree.XMLSyntaxError as e:
            err, log = e, strict.error_log
    else:
        raise err
    tolerant = parser(recover=True)
    root = etree.fromstring(data, tolerant)
    if root is None or any(e.type != _NS_UNDEFINED for e in tolerant.error_log):
        raise err
    return root, [XmlIssue("X005", f"namespace prefix {p!r} is used but never declared (no xmlns:{p}=\"...\"): "
                                   "urdfdom, MuJoCo and Drake read it as part of the name, but xacro, urdf_parser_py "
                                   "and other standards-conforming XML parsers reject the file", line)
                  for p, line in prefixes.items()]


def _add_undeclared(prefixes: dict, log, err: etree.XMLSyntaxError) -> None:
    """Prefixes named by undeclared-prefix errors in `log` (the first line of each); raises for any other error."""
    for entry in log:
        if entry.domain != etree.ErrorDomains.NAMESPACE:  # the first real error is the one to report
            raise etree.XMLSyntaxError(entry.message, entry.type, entry.line, entry.column) from None
        m = _UNDECLARED.fullmatch(entry.message or "") if entry.type == _NS_UNDEFINED else None
        if m is None or not _NCNAME.fullmatch(m.group(1)) or m.group(1) in ("xml", "xmlns"):
            raise err
        prefixes.setdefault(m.group(1), entry.line or None)
    if not log:
        raise err


def _root_name_end(data: bytes, max_items: int = 1000) -> int | None:
    """Offset just after the root element's name in its start tag: past a BOM, spaces, comments and PIs (the
    XML declaration is one; a DOCTYPE was refused before)."""
    i = 3 if data.startswith(b"\xef\xbb\xbf") else 0
    for _ in range(max_items):
        i = _SPACE.match(data, i).end()
        end = b"?>" if data.startswith(b"<?", i) else b"-->" if data.startswith(b"<!--", i) else None
        if end is None:
            m = _START_NAME.match(data, i)
            return m.end() if m else None
        j = data.find(end, i + 2)
        if j < 0:
            return None
        i = j + len(end)
    return None


def _drop_default_namespace(root: etree._Element) -> list[XmlIssue]:
    """Give elements in a default namespace (`<robot xmlns="http://...">`) their local names, as urdfdom and
    MuJoCo (TinyXML2, namespace-unaware) see them, so the model is checked like those consumers read it.
    yourdfpy and urdf_parser_py match elements by qualified tag: a namespaced <robot> reads as a robot with no
    links or joints, a namespaced <link> is skipped (a warning). Inside <gazebo>, <transmission> and
    <ros2_control> blocks their readers (TinyXML2 again) ignore namespaces: no warning."""
    out, seen = [], set()
    for el in root.iter():
        tag = el.tag
        if not (isinstance(tag, str) and tag[:1] == "{" and el.prefix is None):
            continue
        uri, _, local = tag[1:].partition("}")
        el.tag = local
        if uri in seen or _in_block(el):
            continue
        seen.add(uri)
        if el is root:
            what = "yourdfpy and urdf_parser_py then find no links or joints"
        else:
            what = f"yourdfpy and urdf_parser_py skip this <{local}>"
        out.append(XmlIssue("X005", f"<{local}> is in the XML namespace {uri!r} (xmlns=\"...\"): urdfdom, "
                                    f"Pinocchio and MuJoCo ignore namespaces, but {what}; remove the xmlns "
                                    "attribute", el.sourceline))
    etree.cleanup_namespaces(root)
    return out


def _in_block(el: etree._Element) -> bool:
    return any(a.tag in _BLOCKS for a in el.iterancestors()) or el.tag in _BLOCKS


_BLOCKS = frozenset(("gazebo", "transmission", "ros2_control"))


def _check_shape(root: etree._Element, data: bytes) -> None:
    # Depth and attribute length are already capped by libxml2 without XML_PARSE_HUGE (depth 256, text
    # 10 MB; see _LIMIT_ERRORS); entity references need no check because without a DOCTYPE (refused above)
    # an undeclared entity is a syntax error. For the same reason every element and processing instruction
    # is written with its own "<" in the (UTF-8) bytes: counting bytes rules most documents out before any
    # walk of the tree, which costs a tenth of the parse on a large model.
    if data.count(b"<") > MAX_ELEMENTS and int(root.xpath("count(//*)")) > MAX_ELEMENTS:
        raise XmlRefused(XmlIssue("X004", f"more than {MAX_ELEMENTS} XML elements"))
    decl = _DECL.match(data)
    if bytescan.find(data, b"<?", decl.end() if decl else 0, 1) < 0:
        return
    for pi in root.iter(etree.ProcessingInstruction):
        raise XmlRefused(XmlIssue("X002", f"processing instruction <?{pi.target}?> inside the document",
                                  pi.sourceline))
