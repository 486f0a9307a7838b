"""Load: path -> expanded XML with a source map (plain URDF or xacro) -> Model.

Every failure is a located Finding; nothing here raises on bad input except `load_model`, which raises
LoadError (carrying the findings) for callers that need a model or nothing.
"""
from __future__ import annotations

import os
import re
from pathlib import Path

from urdfcheck.core import bytescan, door, lazyre, paths, xmlfront
from urdfcheck.core.findings import Finding, Location, Severity
from urdfcheck.core.records import Record
from urdfcheck.core.safeio import UTF8_BOM, encoding_problem
from urdfcheck.core.suppress import Suppression
from urdfcheck.core.walk import real as realpath  # remembered for the run
from urdfcheck.load import budget, reuse
from urdfcheck.load.packages import Resolver
from urdfcheck.load.xacro import XACRO_MEMORY, XACRO_TIMEOUT, worker_limits

MAX_BYTES = xmlfront.MAX_BYTES

# Severity of load findings; the catalogue may override the names but these codes are fixed here
# because loading happens before any rule runs.
_LOAD_SEVERITY = {"X003": Severity.WARNING, "X005": Severity.WARNING, "X016": Severity.WARNING}


XACRO_NS = "http://www.ros.org/wiki/xacro"


_XACRO_PREFIX = lazyre.compile(rb"""xmlns:([A-Za-z_][\w.-]*)\s*=\s*["']""" + re.escape(XACRO_NS.encode())
                               + rb"""["']""")


def _no_xacro_elements(data: bytes) -> bool:
    """What `is_xacro(path, root)` would say of the parsed bytes, said of the bytes: no element in the xacro
    namespace. URDF exported with xacro keeps xmlns:xacro on <robot> and uses no xacro element. Sound because
    the bytes are UTF-8 with no character reference (`&#`), no DOCTYPE (so no entity) and no default namespace
    (the caller's `xmlfront.streamable`): an element in the namespace is spelled `<prefix:` with a prefix
    declared for its URI, literally."""
    if b"xacro" not in data:
        return True
    prefixes = set(_XACRO_PREFIX.findall(data))
    if prefixes and (b"${" in data or b"$(" in data):
        return False  # substitutions in a file that declares xacro: see is_xacro
    return not any(b"<" + p + b":" in data for p in prefixes)


def is_xacro(path: Path, root=None) -> bool:
    """A .xacro file, or a file whose parsed tree uses xacro elements (some packages name them .urdf), or one that
    declares the xacro namespace and writes ${...} or $(...) in its attributes: a .urdf its launch file runs
    through xacro (read raw, every such number would be U005). A URDF exported by xacro keeps the declaration but
    no substitution."""
    if path.name.endswith(".xacro"):
        return True
    if root is None:
        return False
    if next(root.iter("{" + XACRO_NS + "}*"), None) is not None:  # lxml filters in C
        return True
    if XACRO_NS not in root.nsmap.values():
        return False
    return bool(root.xpath('boolean(//@*[contains(., "${") or contains(., "$(")])'))  # in C, as iter above


class Expanded(Record):
    # entry: display path of the entry file
    # root: lxml root element of the (expanded) document
    # files: display paths, index = marker file index
    # text: expanded XML with markers (xacro only)
    _fields = ('entry', 'xacro', 'root', 'files', 'findings', 'suppressions', 'declared_args', 'args', 'text',
               'resolver', '_cache')

    def __init__(self, entry: str,
                 xacro: bool,
                 root: object | None = None,
                 files: list[str] | None = None,
                 findings: list[Finding] | None = None,
                 suppressions: list[Suppression] | None = None,
                 declared_args: dict | None = None,
                 args: dict | None = None,
                 text: str | None = None,
                 resolver: Resolver | None = None,
                 _cache: dict | None = None):
        self.entry = entry
        self.xacro = xacro
        self.root = root
        self.files = [] if files is None else files
        self.findings = [] if findings is None else findings
        self.suppressions = [] if suppressions is None else suppressions
        self.declared_args = {} if declared_args is None else declared_args
        self.args = {} if args is None else args
        self.text = text
        self.resolver = resolver
        self._cache = {} if _cache is None else _cache
        # a large plain document not parsed yet: read as its model is built (`build_model`), never whole
        self.stream: bytes | None = None

    @property
    def readable(self) -> bool:
        """Read and (for xacro) expanded; a document read as its model is built counts until it fails."""
        return self.root is not None or self.stream is not None

    def clean_text(self) -> str:
        """The expanded document exactly as stock xacro prints it (no source markers)."""
        from urdfcheck.load.xacro import STRIP_RE

        if self.text is not None:
            return STRIP_RE.sub("", self.text)
        return door.read_bytes(self.entry, limit=MAX_BYTES).decode("utf-8", "replace")

    def locator(self):
        """`locate` as the model builder calls it: for a plain URDF a function of the element alone (a 10,000-link
        URDF asks 180,000 times; a bound method and its branch cost a tenth of the build)."""
        if self.xacro:
            return self.locate

        def line(el, _new=_new_location, _loc=Location, _entry=self.entry):
            return _new(_loc, (_entry, el.sourceline, None, ()))
        return line

    def locate(self, el) -> Location:
        """Source location of an element of `root` (xacro markers or lxml line numbers)."""
        if not self.xacro:  # skip namedtuple's keyword handling
            return _new_location(Location, (self.entry, el.sourceline, None, ()))
        from urdfcheck.load.xacro import SRC_ATTR

        node = el
        while node is not None:
            m = node.get(SRC_ATTR) if isinstance(node.tag, str) else None
            if m:
                loc = self._cache.get(m)
                if loc is None:
                    loc = self._cache[m] = self._decode(m)
                return loc
            node = node.getparent()
        return Location(self.entry, None)

    def _decode(self, marker: str) -> Location:
        parts = []
        for item in marker.split(";"):
            if not item:
                continue
            i, _, line = item.partition(":")
            try:
                parts.append((self.files[int(i)], int(line)))
            except (ValueError, IndexError):
                continue
        if not parts:
            return Location(self.entry, None)
        via = tuple(Location(f, ln) for f, ln in parts[1:])
        return Location(parts[0][0], parts[0][1], via=via)


_new_location = tuple.__new__


def _finding(code: str, message: str, file: str, line: int | None = None, column: int | None = None,
             via=()) -> Finding:
    from urdfcheck.core.findings import clean_text

    return Finding(code=code, severity=_LOAD_SEVERITY.get(code, Severity.ERROR), message=clean_text(message),
                   location=Location(file, line, column, tuple(via)))


def expand(path: str | os.PathLike, args: dict | None = None, **kwargs) -> Expanded:
    """Read and (for xacro) expand one entry model. Problems are findings on the result."""
    return begin(path, args, **kwargs).result()


def begin(path: str | os.PathLike, args: dict | None = None, *, packages: dict | None = None,
          trusted: bool = False, allow_env=(), timeout: float = XACRO_TIMEOUT,
          memory: int = XACRO_MEMORY, environ: dict | None = None, max_elements: int | None = None,
          batch: Batch | None = None, stream: bool = False) -> Pending:
    """Start `expand`: a xacro file starts expanding in its worker now, and the caller works on meanwhile.
    With `batch`, a xacro file the console's spare can take waits for `batch.send()` (see `Batch`).
    `stream`: a large plain URDF is left unparsed for `build_model` to read as it builds (no `root`): for a
    caller that only wants the model."""
    p = Path(path)
    entry = paths.shown(p)
    escapes = not trusted and (_links_outside(p, packages) or door.leaves(p))
    resolver = None if escapes else Resolver(packages, near=p.resolve(), environ=environ)
    out = Expanded(entry=entry, xacro=False, files=[entry], args=dict(args or {}), resolver=resolver)
    if escapes:  # a symlink committed in a pull request must not read the runner's files
        out.findings.append(_finding("X014", "the model path is or goes through a symbolic link to outside the "
                                             "package roots or the working directory; not read", entry))
        return Pending(out)
    run = budget.current()
    spent = run.spent() if run is not None else None
    if spent is not None:  # what was not linted is a finding, located at the model
        out.findings.append(_finding("X017", f"not linted: {spent}", entry))
        _unrecordable()
        return Pending(out)
    cut = False
    if run is not None:
        timeout, cut = run.timeout(timeout)
    try:
        # a regular file only (a committed FIFO must not block the run), inside the run's roots unless trusted
        if trusted:
            with door.unconfined():
                data = door.read_bytes(p, limit=MAX_BYTES)
        else:
            data = door.read_bytes(p, limit=MAX_BYTES)
    except OSError as e:
        out.findings.append(_finding("X001", f"cannot read file: {e.strerror}", entry))
        return Pending(out)
    problem = encoding_problem(data)
    if problem is not None:  # UTF-16/32: urdfdom reads UTF-8 only; never silently skipped or read as garbage
        out.findings.append(_finding("X001", problem, entry, 1))
        return Pending(out)
    if data.startswith(UTF8_BOM):  # read on (urdfdom and xacro skip it), but say so
        out.findings.append(_finding("X003", "the file starts with a UTF-8 byte-order mark: urdfdom and xacro skip "
                                             "it, but a launch file that reads the text into robot_description "
                                             "passes U+FEFF on to every consumer; save it as UTF-8 without BOM",
                                     entry, 1))
    opts = (trusted, allow_env, timeout, memory, max_elements)
    if is_xacro(p):
        out.xacro = True
        known = reuse.key(str(p), _options(out, opts), out.resolver) if reuse.active() else None
        stored = reuse.take(known) if known is not None else None
        if stored is not None:  # the lint cache has this expansion, and every file it read is unchanged
            return Pending(out, job=_Reused(stored, known))
        if batch is not None and not cut and batch.takes(opts):
            job = batch.add(out, p, opts)
        else:
            job = _start_xacro(out, p, *opts, grace=0.0 if cut else None)
            job.budget_cut = cut
        job.reuse_key = known
        return Pending(out, job=job)
    too_big = _too_many_elements(data)
    if too_big is not None:
        out.findings.append(_finding("X017", too_big, entry, 1))
        return Pending(out)
    return Pending(out, later=lambda: _read_plain(out, p, data, opts, stream))


# Elements of one document that the main process builds a model from. The largest real robots have hundreds of
# links, the benchmark models 10 000; a million sibling links (23 MB, under the size cap) cost 12 s and 1.9 GB.
MAX_LINKS_JOINTS = 100_000
MAX_ELEMENTS = 2_000_000


_LINK_OR_JOINT = lazyre.compile(rb"<(?:link|joint)[\s>/]")


def _too_many_elements(data) -> str | None:
    """Counted on the bytes before parsing: a byte count instead of a libxml2 tree and a model."""
    if isinstance(data, str):
        data = data.encode("utf-8", "replace")
    if len(data) < 2_000_000:  # too small to hold that many elements
        return None
    parts = len(_LINK_OR_JOINT.findall(data))  # one regex pass: 3x faster than ten byte counts
    if parts > MAX_LINKS_JOINTS:
        return (f"not linted: the model has more than {MAX_LINKS_JOINTS} links and joints ({parts}); "
                "no robot description is that large")
    tags = data.count(b"<")  # an upper bound; the end tags are counted only when it is over
    if tags > MAX_ELEMENTS and (tags := tags - data.count(b"</")) > MAX_ELEMENTS:
        return f"not linted: the model has more than {MAX_ELEMENTS} elements ({tags})"
    return None


class _Reused:
    """An expansion the lint cache had (`load.reuse`), standing in for its worker job."""

    budget_cut = False

    def __init__(self, res: dict, known: str):
        self.res, self.reuse_key = res, known

    def result(self) -> dict:
        return self.res

    def cancel(self) -> None:
        pass


class Pending:
    """An expansion under way: `result()` gives the Expanded (waiting for the worker); `cancel()` drops it."""

    __slots__ = ("_out", "_job", "_later")

    def __init__(self, out: Expanded, job=None, later=None):
        self._out, self._job, self._later = out, job, later

    def result(self) -> Expanded:
        job, later = self._job, self._later
        self._job = self._later = None
        if job is not None:
            res = job.result()
            if getattr(job, "reuse_key", None) is not None:
                reuse.made(job.reuse_key, res)
            _finish_xacro(self._out, res, getattr(job, "budget_cut", False))
        elif later is not None:
            later()
        return self._out

    def cancel(self) -> None:
        if self._job is not None:
            self._job.cancel()
        self._job = self._later = None


class Batch:
    """Xacro models begun together (the run's first few) go to the console's spare as one job: each is expanded
    there or in a child forked from it (`xacro.batch_children`), where xacro is already imported. Without it,
    the second model of a run (a package's argument variant) made this process import xacro before forking its
    worker: 40 ms on the critical path and the import done twice. Models the spare cannot take (other limits, no
    spare) start alone."""

    def __init__(self):
        self.items: list[tuple[Expanded, Path, tuple]] = []
        self.shares: list[_Share] = []
        self.job = None
        # ("module:function", args) the spare runs too, while the expansions run (its value: `also_result`)
        self.also: tuple[str, tuple] | None = None

    def takes(self, opts: tuple) -> bool:
        from urdfcheck.core import worker
        from urdfcheck.load import xacro as xacro_pkg

        kept = worker.spare_limits(xacro_pkg.SPARE)
        return kept is not None and kept == worker_limits(*opts[:4])

    def add(self, out: Expanded, p: Path, opts: tuple) -> _Share:
        share = _Share(self, len(self.items))
        self.items.append((out, p, opts))
        self.shares.append(share)
        return share

    def send(self) -> None:
        """Hand the models to the spare: one alone as a lone expansion, several as a batch."""
        if not self.items:  # (a plain URDF run imports no worker machinery)
            return
        from urdfcheck.core import worker
        from urdfcheck.load import xacro as xacro_pkg

        lim = worker_limits(*self.items[0][2][:4])
        spare = worker.take_spare(xacro_pkg.SPARE, lim)
        if spare is None:  # gone meanwhile: each starts alone (`_Share.result`)
            return
        if len(self.items) == 1 and self.also is None:
            out, p, opts = self.items[0]
            spare.send(xacro_pkg.EXPAND, str(p), _options(out, opts))
        else:
            spare.send(xacro_pkg.EXPAND_BATCH, [(str(p), _options(out, opts), worker_limits(*opts[:4]))
                                                for out, p, opts in self.items], self.also)
            # the expansions' own time-outs come first, one after another for those the spare runs itself
            alone = len(self.items) - xacro_pkg.batch_children(len(self.items))
            spare.deadline += (alone - 1) * lim.timeout + xacro_pkg.BATCH_GRACE
        self.job = spare

    def _batch(self) -> dict | None:
        value = self.job.result() if self.job is not None else None
        if isinstance(value, dict) and isinstance(value.get("outcomes"), list) \
                and len(value["outcomes"]) == len(self.items):
            return value
        return None  # the spare itself failed (not an expansion: each of those has its outcome in the list)

    def outcome(self, index: int):
        """The outcome of model `index`, None when the spare did not deliver it (then it is expanded alone)."""
        if self.job is None:
            return None
        if len(self.items) == 1 and self.also is None:  # the spare expanded it itself: its outcome, whatever it is
            return self.job.result()
        got = self._batch()
        return got["outcomes"][index] if got is not None else None

    def also_result(self):
        """What `also` returned in the spare; None when it did not run or failed."""
        got = self._batch() if self.also is not None else None
        return got.get("also") if got is not None else None


class _Share:
    """One model's part of a `Batch`, standing in for its worker job in `Pending`."""

    budget_cut = False

    def __init__(self, batch: Batch, index: int):
        self.batch, self.index = batch, index

    def result(self):
        got = self.batch.outcome(self.index)
        if got is None:
            out, p, opts = self.batch.items[self.index]
            got = _start_xacro(out, p, *opts, grace=None, spare=False).result()
        return got

    def cancel(self) -> None:
        job, self.batch.job = self.batch.job, None
        if job is not None:
            job.cancel()


def _options(out: Expanded, opts: tuple) -> dict:
    trusted, allow_env, _, _, max_elements = opts
    return dict(mappings=out.args, trusted=trusted, allow_env=allow_env, resolver=out.resolver,
                max_evals=max_elements, root=paths.showing_root())


def _read_plain(out: Expanded, p: Path, data: bytes, opts: tuple, stream: bool = False) -> None:
    shown = out.entry
    # large files only (the byte checks are not run twice on every model), not xacro, nor suppression comments
    # (read from the whole tree)
    if stream and len(data) >= xmlfront.STREAM_BYTES and not bytescan.has(data, b"&#") and b"urdfcheck" not in data \
            and _no_xacro_elements(data):
        try:
            warnings, checked = xmlfront.precheck(data)
        except xmlfront.XmlRefused as r:
            out.findings.append(_finding(r.issue.code, r.issue.message, shown, r.issue.line, r.issue.column))
            return
        if xmlfront.streamable(checked):
            out.findings.extend(_finding(w.code, w.message, shown, w.line) for w in warnings)
            out.stream = checked
            return
    try:
        root, warnings = xmlfront.parse(data)
    except xmlfront.XmlRefused as r:
        out.findings.append(_finding(r.issue.code, r.issue.message, shown, r.issue.line, r.issue.column))
        return
    # the xacro namespace is in the bytes (the front end takes UTF-8 only and refuses entity declarations),
    # unless spelled with character references: without either, skip searching a large tree for it
    if (b"xacro" in data or b"&#" in data) and is_xacro(p, root):
        out.xacro = True
        _finish_xacro(out, _start_xacro(out, p, *opts).result())
        return
    for w in warnings:
        out.findings.append(_finding(w.code, w.message, shown, w.line))
    from urdfcheck.core.suppress import scan_comments

    if b"urdfcheck" in data:  # comments keep their bytes: no such word, no suppression (skips a tree walk)
        out.suppressions = [Suppression(shown, a, b, c, d) for a, b, c, d in scan_comments(root)]
    out.root = root


def _links_outside(p: Path, packages: dict | None) -> bool:
    """The entry file is a symlink whose target lies outside the workspace around the link itself, or the
    path leads out of the working directory through a linked folder."""
    from urdfcheck.load.packages import leaves_cwd, workspace_root

    lexical = Path(os.path.abspath(p))
    if leaves_cwd(lexical, (packages or {}).values()):
        return True
    if not os.path.islink(lexical):
        return False
    real = realpath(lexical)
    roots = [workspace_root(lexical.parent)] + [Path(v) for v in (packages or {}).values()]
    for r in roots:
        base = realpath(r)
        if real == base or real.startswith(base.rstrip(os.sep) + os.sep):
            return False
    return True


def _unrecordable() -> None:
    from urdfcheck.core import observe

    observe.taint()  # a run cut by its time budget is not stored by the lint cache


def _start_xacro(out: Expanded, p: Path, trusted, allow_env, timeout, memory, max_elements=None, grace=None,
                 spare: bool = True):
    from urdfcheck.core import worker
    from urdfcheck.load import xacro as xacro_pkg

    options = _options(out, (trusted, allow_env, timeout, memory, max_elements))
    if grace is None and spare:  # a child the console forked at start-up, with xacro imported meanwhile (cli.main)
        spare = worker.take_spare(xacro_pkg.SPARE, worker_limits(trusted, allow_env, timeout, memory))
        if spare is not None:  # the options go as a dict: this process need not import the expander
            spare.send(xacro_pkg.EXPAND, str(p), options)
            return spare
    from urdfcheck.load.xacro import expand as xexpand

    opts = xexpand.Options(**options)
    xexpand.preload()
    extra = {} if grace is None else {"grace": grace}  # cut by the run budget: no delivery grace past it
    return worker.start(xexpand.expand, str(p), opts, timeout=timeout, memory=memory,
                        env_keep=tuple(allow_env), scrub_env=not trusted, **extra)


def _finish_xacro(out: Expanded, res, budget_cut: bool = False) -> None:
    from urdfcheck.core import observe, worker

    if observe.active():  # the lint cache: what the worker read, or that it is unknown (cli/cache.py)
        if isinstance(res, dict):
            observe.add(res.get("observed"))
        else:
            observe.taint()
    if isinstance(res, worker.Failure):
        if res.kind == "timeout" and budget_cut:
            out.findings.append(_finding("X017", "not linted: the run's time budget ran out during its xacro "
                                                 "expansion", out.entry, 1))
            return
        what = {"timeout": "xacro expansion timed out", "memory": "xacro expansion ran out of memory",
                "output": "xacro expansion produced too much output"}.get(res.kind, "xacro expansion failed")
        code = "X012" if res.kind in ("timeout", "memory", "output") else "X010"
        out.findings.append(_finding(code, f"{what}: {res.message}", out.entry, 1))
        return
    out.files = [paths.shown(f) for f in res["files"]] or [out.entry]
    out.declared_args = dict(res.get("args", {}))
    for idx, first, last, codes, cline in res["suppressions"]:
        out.suppressions.append(Suppression(out.files[idx], first, last, codes, cline))
    for idx, code, message, line in res.get("xml_warnings", []):
        out.findings.append(_finding(code, message, out.files[idx], line))
    for kind, text, marker in res.get("warnings", []):
        if kind in ("warning", "error") and text.strip():
            loc = out._decode(marker) if marker else Location(out.entry, None)
            out.findings.append(Finding("X016", Severity.WARNING, f"xacro {kind}: " + _short(text), loc))
    err = res.get("error")
    if err is not None:
        loc = out._decode(err["marker"]) if err.get("marker") else Location(out.entry, None)
        out.findings.append(_finding(err["code"], err["message"], loc.file, loc.line, via=loc.via))
        return
    too_big = _too_many_elements(res["xml"])
    if too_big is not None:
        out.findings.append(_finding("X017", too_big, out.entry, 1))
        return
    out.text = res["xml"]
    try:
        root, _ = xmlfront.parse(out.text.encode("utf-8"))
    except xmlfront.XmlRefused as r:
        out.findings.append(_finding(r.issue.code, "expanded document: " + r.issue.message, out.entry))
        return
    out.root = root


def _short(text: str) -> str:
    from urdfcheck.core.findings import clean_text

    return clean_text(text.strip().splitlines()[0] if text.strip() else text)


class LoadError(Exception):
    def __init__(self, findings: list[Finding]):
        super().__init__("; ".join(f"{f.location}: {f.code} {f.message}" for f in findings) or "cannot load")
        self.findings = findings


def build_model(exp: Expanded):
    """Model for an expanded document, or None when there is no document. A document left unparsed (`begin`'s
    `stream`) is read as the model is built; where libxml2 stops on the way, it is read again whole, which
    reports what is wrong with it as a finding of `exp` (none of the half-built model's issues is kept)."""
    if exp.stream is not None:
        data, exp.stream = exp.stream, None
        from lxml import etree

        from urdfcheck.model.build import build_streamed

        try:
            return build_streamed(xmlfront.stream(data), exp.locator(), exp.entry)
        except etree.XMLSyntaxError:
            pass
        try:
            exp.root, warnings = xmlfront.parse(data)  # `data` passed `precheck`: only what libxml2 found
        except xmlfront.XmlRefused as r:
            exp.findings.append(_finding(r.issue.code, r.issue.message, exp.entry, r.issue.line, r.issue.column))
            return None
        exp.findings.extend(_finding(w.code, w.message, exp.entry, w.line) for w in warnings)
    if exp.root is None:
        return None
    from urdfcheck.model.build import build

    return build(exp.root, exp.locator(), exp.entry)


def load_model(path, args: dict | None = None, **kwargs):
    """Model or LoadError. For `tree`, `tf`, `publish`, `verify` and API users."""
    exp = expand(path, args, **kwargs)
    errors = [f for f in exp.findings if f.severity >= Severity.ERROR]
    if exp.root is None or errors:
        raise LoadError(errors or exp.findings)
    return build_model(exp)
