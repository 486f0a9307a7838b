"""Run the PyPI xacro package as a library, with source markers and (by default) the sandbox.

This module patches xacro's module globals, so it only runs inside a worker process (see core/worker.py): the
parent never executes xacro code. Each expansion puts xacro's module state back when it ends and starts from
fresh global symbols, so nothing leaks from one file to the next when the spare expands several in turn.

Source map: every element read from a file gets an attribute `__ucsrc="F:L"` (file index, line).
When an element is first evaluated, the macro call sites active at that moment are appended
("F:L;F2:L2;..." innermost call first). The markers survive macro cloning because they are plain
attributes; they are stripped from the output for `urdfcheck expand`.
"""
from __future__ import annotations

import glob
import io
import os
import sys
import xml.dom.minidom
from xml.dom import expatbuilder

from urdfcheck.core import door, lazyre, xmlfront
from urdfcheck.core.paths import showing, shown
from urdfcheck.core.safeio import encoding_problem
from urdfcheck.load.xacro import SRC_ATTR, STRIP_RE  # noqa: F401 - the markers, shared with the loader

BUILTINS = {"include", "property", "macro", "arg", "element", "attribute", "if", "unless",
            "insert_block", "call"}
MAX_INCLUDES = 5000
MAX_FILE_BYTES = 16 * 1024 * 1024
# Elements evaluated. The largest corpus model (PR2) evaluates ~2 800; a 1.2 KB macro bomb reaches 10 000 in
# about a second, where 400 000 took minutes (xacro's cost per element grows with the document). Trusted
# (own) files keep a larger budget.
MAX_EVALS = 20_000  # ~1 s of expansion; PR2, the largest corpus model, evaluates 2,786 elements
MAX_EVALS_TRUSTED = 400_000
# Budgets for one expansion, far above what real models use (corpus maxima: 868 items iterated by all
# ${...}, one value of 768 characters, 153 000 characters of values in all), low enough that the worst
# input stays within about a second.
MAX_EXPR_ITER = 500_000  # items iterated by all ${...} together
MAX_VALUE = 1_000_000  # characters/items of one value
MAX_TEXT = 8 * 1024 * 1024  # characters of evaluated attribute and text values in all (macro-cloned bulk)


_GLOB_MAGIC = lazyre.compile(r"[*?\[]")  # what xacro's get_include_files treats as a pattern


class Refusal(Exception):
    """A construct the sandbox will not run. `code` is the finding code."""

    def __init__(self, code: str, message: str):
        super().__init__(message)
        self.code = code
        self.message = message


class Options:
    def __init__(self, mappings=None, trusted=False, allow_env=(), resolver=None, max_evals=None, root=None):
        self.root = root  # messages show paths relative to it (core.paths.showing); None: the working directory
        self.mappings = dict(mappings or {})
        self.trusted = trusted
        self.allow_env = set(allow_env)
        self.resolver = resolver
        self.max_evals = max_evals or (MAX_EVALS_TRUSTED if trusted else MAX_EVALS)


class _State:
    def __init__(self):
        self.files: list[str] = []
        self.file_index: dict[str, int] = {}
        self.calls: list[str] = []  # active macro call sites (markers), outermost first
        self.frames: list[list] = []  # [element marker, builtin marker] per eval_all level
        self.evals = 0
        self.text = 0
        self.suppressions: list[tuple] = []
        self.warnings: list[tuple[str, str | None]] = []
        self.declared_args: dict[str, str] = {}
        self.xml_warnings: list[tuple] = []

    def index(self, path: str) -> int:
        if path not in self.file_index:
            self.file_index[path] = len(self.files)
            self.files.append(path)
        return self.file_index[path]


def _line_builder(state: _State, idx: int):
    class LineBuilder(expatbuilder.ExpatBuilderNS):
        def start_element_handler(self, name, attributes):
            # the marker as one more attribute from the parser (set last, as setAttribute would, without its
            # node-by-node path; a marker written in the file is replaced, as setAttribute replaces it)
            super().start_element_handler(name, attributes + [SRC_ATTR, f"{idx}:{self._parser.CurrentLineNumber}"])

    return LineBuilder()


def _collect_suppressions(state: _State, idx: int, root) -> None:
    from urdfcheck.core.suppress import scan_comments

    state.suppressions.extend((idx,) + s for s in scan_comments(root))


def preload() -> None:
    """Import what `expand` needs, in the calling process.

    Called before forking the worker: each child then inherits the modules instead of importing them
    again (a package with argument variants forks once per variant), and PyYAML, which xacro imports,
    is already there for the contract readers. Importing runs no user input.
    """
    import importlib

    from urdfcheck.load.xacro import SPARE_PRELOAD

    for name in SPARE_PRELOAD:  # the spare's list, in its order (PyYAML through our import before xacro)
        importlib.import_module(name)


def expand_with(path: str, options: dict) -> dict:
    """`expand` with the options as a dict (a job sent to a prepared worker: its sender has not imported this
    module)."""
    return expand(path, Options(**options))


def expand_batch(jobs: list, also=None) -> dict:
    """In the console's spare, where xacro is imported: each (path, options, limits) expanded under the limits the
    loader gives a lone expansion, the first `batch_children` each in a child of its own forked now (before
    this process runs any xacro code), the others here, one after another (each with its own wall clock and
    xacro's module state put back after it: `expand`); "outcomes": theirs (a result dict or a `Failure`) in
    order. This process is under the same limits as a child (`Batch.takes`: the spare's are the jobs'); if it
    dies or overruns, the loader expands each model alone.

    `also`: ("module:function", args) run here meanwhile (the package's parameter files, parsed where PyYAML is
    imported); "also": its value, None when it failed."""
    from urdfcheck.core import worker
    from urdfcheck.load.xacro import batch_children

    forked = batch_children(len(jobs))
    started = [worker.start(expand_with, path, options, timeout=lim.timeout, memory=lim.memory,
                            env_keep=lim.env_keep, scrub_env=lim.scrub_env) for path, options, lim in jobs[:forked]]
    here = [_expand_here(*job) for job in jobs[forked:]]
    extra = None
    if also is not None:
        try:
            extra = worker._by_name(also[0], *also[1])
        except Exception:  # noqa: BLE001 - the console does it itself
            extra = None
    worker.wait(started)
    return {"outcomes": [j.value for j in started] + here, "also": extra}


def _expand_here(path: str, options: dict, lim):
    """`expand_with` in this process, its outcome as a child's would come back (`core.worker.start`): the result,
    or a `Failure` for what the child would have reported, with the child's wall clock (`lim.timeout`). What it
    reads is its own record for the lint cache (as a child's is): afterwards this process's record is as before."""
    import gc
    import signal

    from urdfcheck.core import observe
    from urdfcheck.core.worker import Failure

    def overrun(signum, frame):
        raise _Overrun()

    before = observe.snapshot()
    gc.enable()  # as in a child: an expansion makes cyclic garbage (DOM trees)
    old = signal.signal(signal.SIGALRM, overrun)
    signal.setitimer(signal.ITIMER_REAL, lim.timeout)
    try:
        return expand_with(path, options)
    except _Overrun:
        return Failure("timeout", f"did not finish within {lim.timeout:g} s")
    except MemoryError:
        return Failure("memory", "out of memory")
    except RecursionError:
        return Failure("error", "recursion too deep")
    except Exception as e:  # noqa: BLE001 - reported, as a child reports it
        return Failure("error", f"{type(e).__name__}: {e}")
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)
        observe.restore(before)


class _Overrun(BaseException):
    """The wall clock of an expansion run in the worker itself (a BaseException: xacro's handlers let it by)."""


def expand(path: str, opts: Options) -> dict:
    """Expand `path`. Returns a dict (picklable): xml (marked), files, suppressions, warnings, args.

    Errors are returned, not raised: {"error": {"code", "message", "marker"}}.
    """
    import contextlib

    from xacro import substitution_args as subst

    from urdfcheck.load.xacro.xacroimport import xacro

    kept = _stock(xacro, subst)
    try:
        # `--trusted`: the runner lowered the guard; the door still refuses FIFOs and caps, but confines nothing
        with showing(opts.root), (door.unconfined() if opts.trusted else contextlib.nullcontext()):
            return _expand(path, opts)
    finally:
        _put_back(kept)


# what an expansion replaces in xacro's modules (its hooks, the sandbox) and in this process (stderr)
_PATCHED = ("get_include_files", "eval_all", "handle_macro_call", "check_attrs", "parse", "eval_extension",
            "eval_text", "warning", "message", "error", "safe_eval", "_global_symbols")
_PATCHED_SUBST = ("_eval_env", "_eval_optenv", "_eval_find", "_eval")


def _stock(xacro, subst) -> list:
    """xacro's module state as it is before an expansion (stock: each expansion puts it back), and fresh global
    symbols for this one: what one expansion did to them (the sandbox's functions, anything a model reached)
    never reaches the next one the spare runs (`expand_batch`). Returns what `_put_back` restores."""
    kept = [(mod, name, getattr(mod, name)) for mod, names in ((xacro, _PATCHED), (subst, _PATCHED_SUBST))
            for name in names if hasattr(mod, name)]
    units = getattr(xacro, "ConstructUnits", None)
    if units is not None and hasattr(units, "constructor"):
        kept.append((units, "constructor", units.constructor))
    kept.append((sys, "stderr", sys.stderr))
    if hasattr(xacro, "create_global_symbols"):
        xacro._global_symbols = xacro.create_global_symbols()
    return kept


def _put_back(kept: list) -> None:
    for mod, name, value in kept:
        setattr(mod, name, value)


def _expand(path: str, opts: Options) -> dict:
    from xacro import substitution_args as subst

    from urdfcheck.load.xacro.xacroimport import xacro

    state = _State()
    resolver = opts.resolver
    out: dict = {"files": state.files, "suppressions": state.suppressions, "warnings": state.warnings,
                 "args": state.declared_args, "xml_warnings": state.xml_warnings}

    observe = sys.modules.get("urdfcheck.core.observe")
    if observe is not None and observe.active():
        # the lint cache stores what this expansion read (load/reuse.py): the walks and package folders the
        # console remembered before forking would answer without a read, so they are looked at again here
        from urdfcheck.core import walk
        from urdfcheck.load import packages

        walk.forget()
        packages.forget()

    # --- fresh module state: nothing survives from an earlier run -------------------------
    xacro.all_includes = []
    xacro.substitution_args_context = {}
    xacro.root_dir = os.curdir
    xacro.verbosity = 1
    xacro.filestack = None
    xacro.macrostack = None

    orig_eval_all = xacro.eval_all
    orig_handle_macro_call = xacro.handle_macro_call
    orig_check_attrs = xacro.check_attrs
    orig_eval_extension = xacro.eval_extension
    orig_eval_text = xacro.eval_text

    def marker_of(node):
        if node.nodeType == node.ELEMENT_NODE and node.hasAttribute(SRC_ATTR):
            return node.getAttribute(SRC_ATTR)
        return None

    def annotate(node):
        m = marker_of(node)
        if m is not None and ";" not in m:
            node.setAttribute(SRC_ATTR, m + ";" + ";".join(reversed(state.calls)))

    def eval_all(node, macros, symbols):
        state.evals += 1
        if state.evals > opts.max_evals:
            raise Refusal("X012", f"expansion evaluated more than {opts.max_evals} elements "
                                  "(a macro that multiplies itself?)")
        annotate(node)
        state.frames.append([marker_of(node) or (state.frames[-1][0] if state.frames else None), None])
        try:
            orig_eval_all(node, macros, symbols)
        except BaseException as e:
            if getattr(e, "_uc_marker", None) is None:
                frame = state.frames[-1]
                try:
                    e._uc_marker = frame[1] or frame[0]
                except AttributeError:
                    pass
            raise
        finally:
            state.frames.pop()

    def handle_macro_call(node, macros, symbols):
        if not node.tagName.startswith("xacro:"):
            return False
        site = node.getAttribute(SRC_ATTR) if node.hasAttribute(SRC_ATTR) else None
        if site is not None:
            node.removeAttribute(SRC_ATTR)
            site = site.split(";")[0]
        # block arguments were written at the call site: give them the outer call chain first
        for child in node.getElementsByTagName("*"):
            annotate(child)
        if site is not None:
            state.calls.append(site)
        try:
            return orig_handle_macro_call(node, macros, symbols)
        except BaseException as e:
            if getattr(e, "_uc_marker", None) is None and site is not None:
                try:
                    e._uc_marker = ";".join([site] + list(reversed(state.calls[:-1])))
                except AttributeError:
                    pass
            raise
        finally:
            if site is not None:
                state.calls.pop()

    def check_attrs(tag, required, optional):
        if tag.hasAttribute(SRC_ATTR):
            m = tag.getAttribute(SRC_ATTR).split(";")[0]
            tag.removeAttribute(SRC_ATTR)
            if state.frames:
                state.frames[-1][1] = ";".join([m] + list(reversed(state.calls)))
        result = orig_check_attrs(tag, required, optional)
        if tag.tagName == "xacro:arg" and result and result[0] is not None:
            state.declared_args.setdefault(result[0], result[1] if len(result) > 1 else None)
        return result

    shown = _shown

    def get_include_files(filename_spec, symbols):
        # stock globs the pattern as written: '/*/*/*.xacro' or '../../*' walks the runner's file system, and
        # the refusal of the first match named a file outside the package. Here the folder the pattern
        # starts from must lie inside the package roots, and every match too; messages name the pattern only.
        written = str(xacro.eval_text(filename_spec, symbols))
        full = os.path.normpath(os.path.join(xacro.root_dir, xacro.abs_filename_spec(written)))
        confine = not opts.trusted and resolver is not None
        if _GLOB_MAGIC.search(full):
            parts = full.split(os.sep)
            first = next(i for i, part in enumerate(parts) if _GLOB_MAGIC.search(part))
            base = os.sep.join(parts[:first]) or os.sep
            if confine and not resolver.allowed(base):
                raise Refusal("X014", f"refusing the include pattern {shown(written)}: it searches outside the "
                                      "package roots")
            filenames = []
            for match in glob.iglob(full):
                if len(filenames) + len(state.files) >= MAX_INCLUDES:
                    raise Refusal("X012", f"more than {MAX_INCLUDES} files included")
                if confine and not resolver.allowed(match):
                    raise Refusal("X014", f"refusing the include pattern {shown(written)}: a file it matches is "
                                          "outside the package roots")
                filenames.append(match)
            filenames.sort()
            if not filenames:
                xacro.warning(xacro.include_no_matches_msg.format(shown(written, quote=False)))
        else:
            if confine and not resolver.allowed(full):
                raise Refusal("X014", f"refusing to read {shown(written)}: it is outside the package roots")
            filenames = [xacro.abs_filename_spec(written)]
        for filename in filenames:
            xacro.all_includes.append(filename)
            yield filename

    def parse(inp, filename=None):
        if inp is not None:
            return xml.dom.minidom.parseString(inp) if isinstance(inp, str) else inp
        full = os.path.join(xacro.root_dir, filename)
        # never stat a path outside the package roots (source_layout only maps paths inside them anyway)
        if resolver is not None and resolver.allowed(full) and not os.path.exists(full):
            full = str(resolver.source_layout(full) or full)
        if len(state.files) >= MAX_INCLUDES:
            raise Refusal("X012", f"more than {MAX_INCLUDES} files included")
        if not opts.trusted and resolver is not None and not resolver.allowed(full):
            raise Refusal("X014", f"refusing to read {shown(filename)}: it is outside the package roots")
        try:
            data = door.read_bytes(full, limit=MAX_FILE_BYTES)
        except OSError as e:
            xacro.filestack.pop()  # as stock xacro does: the missing file is not "the current file"
            # not `exc=e`: xacro would append the OSError's text, which holds the absolute path
            raise xacro.XacroException(f"{e.strerror}: {shown(filename, quote=False)}{_package_hint(filename)}") \
                from e
        if len(data) > MAX_FILE_BYTES:
            raise Refusal("X012", f"{shown(filename)} is larger than {MAX_FILE_BYTES} bytes")
        idx = state.index(os.path.normpath(full))
        problem = encoding_problem(data)
        if problem is not None:  # an included UTF-16 file: say so, not "invalid UTF-8"
            err = Refusal("X001", problem)
            err._uc_marker = f"{idx}:1"
            raise err
        try:
            root, warnings = xmlfront.parse(data)
        except xmlfront.XmlRefused as r:
            err = Refusal(r.issue.code, r.issue.message)
            err._uc_marker = f"{idx}:{r.issue.line or 1}"
            raise err from None
        for w in warnings:
            state.xml_warnings.append((idx, w.code, w.message, w.line))
        if b"urdfcheck" in data:  # comments keep their bytes: no such word, no suppression (as the loader decides)
            _collect_suppressions(state, idx, root)
        builder = _line_builder(state, idx)
        return builder.parseString(data)

    def eval_text(text, symbols):
        # stock lexes every attribute and text, and a text without "$" is one TEXT token returned as it is: most
        # values, and every source marker, skip the lexer (about a sixth of an expansion)
        result = text if type(text) is str and "$" not in text else orig_eval_text(text, symbols)
        if isinstance(result, str):
            state.text += len(result)
            if state.text > MAX_TEXT:
                raise Refusal("X012", f"expansion produced more than {MAX_TEXT} characters of values "
                                      "(a large value multiplied by macros?)")
        return result

    def eval_extension(s):
        if s == "$(cwd)" and not opts.trusted:
            raise Refusal("X015", "$(cwd) is refused in the sandbox (it copies the runner's path into the model)")
        return orig_eval_extension(s)

    def eval_env(name):
        if not opts.trusted and name not in opts.allow_env:
            raise Refusal("X015", f"$(env {name}) is refused: the variable is not allow-listed in the config")
        return os.environ[name]

    def eval_optenv(name, default=""):
        # sandbox: the default (or ""), never the runner's environment, unless the variable is allow-listed
        if not opts.trusted and name not in opts.allow_env:
            return default
        return os.environ.get(name, default)

    def eval_find(pkg):
        hit = resolver.find(pkg) if resolver is not None else None
        if hit is None:
            raise Refusal("X013", f"package {pkg!r} not found (pass --package {pkg}=PATH)")
        return str(hit)

    def collect(kind):
        def note(*args, **kwargs):
            kwargs.pop("print_location", None)
            text = " ".join(str(a) for a in args)
            frame = state.frames[-1] if state.frames else [None, None]
            state.warnings.append((kind, text, frame[1] or frame[0]))
        return note

    units = getattr(xacro, "ConstructUnits", None)
    orig_unit_constructor = getattr(units, "constructor", None)

    def unit_constructor(unit, loader, node):
        # a YAML tag such as !degrees evaluates its scalar: locate a failure at that YAML line
        try:
            return orig_unit_constructor(unit, loader, node)
        except Exception as e:
            if getattr(e, "_uc_marker", None) is None and getattr(node.start_mark, "name", None):
                frame = state.frames[-1] if state.frames else [None, None]
                where = f"{state.index(os.path.normpath(node.start_mark.name))}:{node.start_mark.line + 1}"
                try:
                    e._uc_marker = ";".join(m for m in (where, frame[1] or frame[0]) if m)
                except AttributeError:
                    pass
            raise

    def sandbox_unit_constructor(unit, loader, node):
        # stock: float(eval(scalar)); a failure echoed the evaluated text ("could not convert string to float:
        # '<whatever the expression computed>'"). Here the scalar goes through the sandbox evaluator (the same
        # guards as ${...}) and a non-number is reported by its type, never by its text.
        value = loader.construct_scalar(node)
        try:
            result = xacro.safe_eval(value, xacro._global_symbols)
        except SyntaxError:
            raise xacro.XacroException(f"invalid expression after {unit.value.tag}") from None
        if not isinstance(result, (int, float)):
            raise xacro.XacroException(f"the value after {unit.value.tag} is not a number "
                                       f"(it evaluates to a {type(result).__name__})")
        return float(result) * unit.value.conversion_constant

    if orig_unit_constructor is not None:
        if not opts.trusted:
            orig_unit_constructor = sandbox_unit_constructor
        units.constructor = unit_constructor
    if not opts.trusted:
        xacro.get_include_files = get_include_files
    xacro.eval_all = eval_all
    xacro.handle_macro_call = handle_macro_call
    xacro.check_attrs = check_attrs
    xacro.parse = parse
    xacro.eval_extension = eval_extension
    xacro.eval_text = eval_text
    xacro.warning = collect("warning")
    xacro.message = collect("message")
    xacro.error = collect("error")
    subst._eval_env = eval_env
    subst._eval_optenv = eval_optenv
    subst._eval_find = eval_find

    if not opts.trusted:
        _install_sandbox(xacro, subst, resolver, {"env": eval_env, "optenv": eval_optenv, "find": eval_find})

    sys.stderr = io.StringIO()  # print_location and friends write here; never to the user's terminal
    try:
        doc = xacro.process_file(path, mappings=dict(opts.mappings))
        text = doc.toprettyxml(indent="  ")
    except RecursionError:
        out["error"] = {"code": "X012", "message": "expansion nested too deeply (recursive macro?)", "marker": None}
        return out
    except Refusal as e:
        out["error"] = {"code": e.code, "message": e.message, "marker": getattr(e, "_uc_marker", None)}
        return out
    except Exception as e:
        out["error"] = _describe(e, xacro)
        return out
    finally:
        seen = sys.modules.get("urdfcheck.core.observe")
        if seen is not None and seen.active():  # what this expansion read and ran, for the lint cache
            out["observed"] = sorted(set(seen.take()) | set(seen.installed_modules()))
    out["xml"] = text
    out["deps"] = sorted(set(xacro.all_includes))
    return out


def _describe(e: BaseException, xacro) -> dict:
    """Turn a xacro failure into {code, message, marker}, looking through wrapped exceptions."""
    marker = getattr(e, "_uc_marker", None)
    inner = e
    seen = 0
    located = None  # the innermost exception's own location (a !degrees failure: its YAML line)
    while inner is not None and seen < 10:
        seen += 1
        if inner is not e and getattr(inner, "_uc_marker", None):
            located = inner._uc_marker
        if isinstance(inner, Refusal):
            return {"code": inner.code, "message": inner.message, "marker": marker}
        if _is_refused(inner):
            expr = getattr(inner, "expr", "")
            reason = getattr(inner, "reason", str(inner))
            return {"code": "X011", "message": f"refused expression {expr!r}: {reason}",
                    "marker": getattr(inner, "_uc_marker", None) or marker}  # e.g. the YAML line of a !degrees
        nxt = getattr(inner, "exc", None) or inner.__cause__ or inner.__context__
        inner = nxt if nxt is not inner else None
    msg = _text(e)
    if type(e).__name__ == "ExpatError":
        msg = f"XML parsing error: {msg}"
    elif "No such file or directory" in msg and "package:/" in msg and _PACKAGE_HINT not in msg:
        msg += _PACKAGE_HINT
    elif msg.startswith("Undefined substitution argument "):
        # xacro's words name the argument without quotes ("... argument name"): say what is missing and who sets it
        arg = msg[len("Undefined substitution argument "):].strip()
        msg = (f"xacro argument '{arg}' has no default and nothing sets it (no launch file found that runs this "
               f"model with it): set it with --arg {arg}:=... or in the model's args: in urdfcheck.yaml")
    macros = [m.body.getAttribute("name") for m in reversed(xacro.macrostack or []) if m.body is not None]
    if macros:
        msg += " (in macro " + " <- ".join(macros) + ")"
    # a library's own words may quote a path it built (an OSError's text): shown as reports show paths
    msg = _QUOTED_PATH.sub(lambda m: _shown(m.group(2)), msg)
    return {"code": "X010", "message": msg.strip(), "marker": located or marker}


_QUOTED_PATH = lazyre.compile(r"""(['"])(/[^'"\n]*)\1""")
# stock xacro joins "package://pkg/x.xacro" to the including file's folder like any relative name
_PACKAGE_HINT = " (xacro does not resolve package:// URLs in <xacro:include> or load_yaml: write $(find pkg)/...)"


def _package_hint(path) -> str:
    return _PACKAGE_HINT if "package:/" in str(path) else ""


def _text(e: BaseException, limit: int = 4000) -> str:
    """An exception's message, bounded; str() itself may fail (a KeyError of a 100 000-digit integer)."""
    try:
        msg = str(e) or repr(e)
    except Exception:  # noqa: BLE001 - any failure to describe is described by the type
        msg = type(e).__name__
    return msg if len(msg) <= limit else msg[:limit - 3] + "..."


def _shown(path, quote=True) -> str:
    """A path for a message, as reports show paths (core.paths), never the runner's absolute path."""
    text = str(path)
    if os.path.isabs(text):
        text = shown(os.path.normpath(text))
        if os.path.isabs(text):
            return "a file outside the working directory"
    return repr(text) if quote else text


class _NamedText(io.StringIO):
    """YAML text with the file's name: PyYAML's marks (the !degrees error locations) carry it."""

    def __init__(self, text: str, name: str):
        super().__init__(text)
        self.name = name


def _is_refused(e) -> bool:
    return type(e).__name__ == "Refused" and type(e).__module__.endswith("safeeval")


# stock xacro's create_global_symbols: the bare helpers (load_yaml, abs_filename, dotify) warn with this text
DEPRECATED_BARE = "Using {name}() directly is deprecated. Use {ns}.{name}() instead."


def _deprecated_as_stock(xacro, symbols, name: str, confined):
    """`confined` under the bare name, warning as stock's bare name does (issue 15: replacing stock's wrapper
    lost the warning). Only where this xacro deprecates the bare name, i.e. it is not the xacro.NAME helper."""
    ns = symbols.get("xacro")
    stock = symbols.get(name)
    if stock is None or not isinstance(ns, dict) or stock is dict.get(ns, name):
        return confined
    message = DEPRECATED_BARE.format(name=name, ns="xacro")

    def deprecated(*args, **kwargs):
        xacro.warning(message)  # collected at the element being evaluated, like every xacro warning
        return confined(*args, **kwargs)

    deprecated.__name__ = deprecated.__qualname__ = name
    return deprecated


def _install_sandbox(xacro, subst, resolver, confined: dict) -> None:
    import functools

    from urdfcheck.core.yamlimport import yaml
    from urdfcheck.load.xacro import safeeval, yamlguard

    def confined_load_yaml(filename):
        # stock load_yaml, reading the file once: a regular file only (a committed FIFO would block), capped,
        # checked for alias bombs and nesting before PyYAML builds it
        full = xacro.abs_filename_spec(filename)
        if resolver is not None and not resolver.allowed(full):
            raise Refusal("X014", f"refusing to load YAML {_shown(filename)}: it is outside the package roots")
        try:
            data = door.read_bytes(full, limit=yamlguard.MAX_BYTES)
        except OSError as e:  # not `exc=e`: xacro would append the OSError's text, which holds the absolute path
            raise xacro.XacroException(f"{e.strerror}: {_shown(filename, quote=False)}{_package_hint(full)}") \
                from None
        try:
            text = data.decode("utf-8")
            yamlguard.check_yaml_text(text, _shown(filename))
        except UnicodeDecodeError:
            raise xacro.XacroException(f"{_shown(filename)} is not UTF-8 text") from None
        except yamlguard.YamlRefused as e:  # an alias bomb is an expansion limit (X012), not a xacro error
            raise Refusal(e.code, e.message) from None
        for unit in xacro.ConstructUnits:
            yaml.SafeLoader.add_constructor(unit.value.tag, unit.constructor)
        xacro.filestack.append(full)
        try:
            return xacro.YamlListWrapper.wrap(yaml.safe_load(_NamedText(text, full)))
        finally:
            xacro.filestack.pop()
            xacro.all_includes.append(full)

    def confined_abs_filename(filename_spec):
        # stock prepends the current file's folder: the runner's absolute path, copied into the model. Every
        # xacro use of a relative name (include, load_yaml) resolves it against that same folder, so the name
        # is returned as written.
        if not isinstance(filename_spec, str):
            raise TypeError(f"expected a file name, not {type(filename_spec).__name__}")
        return filename_spec

    symbols = xacro._global_symbols
    symbols["load_yaml"] = _deprecated_as_stock(xacro, symbols, "load_yaml", confined_load_yaml)
    symbols["abs_filename"] = _deprecated_as_stock(xacro, symbols, "abs_filename", confined_abs_filename)
    if "xacro" in symbols:
        dict.__setitem__(symbols["xacro"], "load_yaml", confined_load_yaml)
        dict.__setitem__(symbols["xacro"], "abs_filename", confined_abs_filename)
    # one budget for all expressions of the expansion: a cheap-looking loop repeated by macros adds up
    evaluator = safeeval.default_evaluator(symbols, safeeval.Limits(
        max_len=MAX_VALUE, max_alloc=5 * MAX_VALUE, max_total_iter=MAX_EXPR_ITER))

    def safe_eval(expr, globals, locals=None):
        return evaluator.evaluate(expr, globals)

    xacro.safe_eval = safe_eval
    # $(eval) sees env/optenv/find too (stock binds them at import time): give it the confined ones
    functions = {**safeeval.default_substitution_functions(), **confined}
    subst._eval = functools.partial(safeeval.evaluate_substitution, functions=functions, evaluator=evaluator)
