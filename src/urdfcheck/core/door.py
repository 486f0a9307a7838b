"""The one door: every file a reader of urdfcheck opens comes in here (issue 36).

In CI on a pull request every file of the checkout is the attacker's: a model, a YAML, a launch file, a recording
or a folder inside one can be a symlink out of the checkout, a FIFO, a device, or a file made to be huge. Each
reader that opened its own files was one more place to forget a guard. So:

- `read_bytes` / `read_text`: a whole file, capped (readers of models, YAML, launch, `.lua`, joint-state files);
- `open_stream`: a file object for a container library (MCAP, ROS 1 bags) that reads pieces itself; every read
  counts against the run's byte budget;
- `admit`: the real path of a file a library must open by name (sqlite3), after the same checks.

What is checked, in every case:
1. **Confinement.** The real path (links followed) must lie under one of the run's roots: the checkout, the roots
   of the packages the run resolved, and what the person running the tool named (`runner=True`, for paths typed
   on the command line: a path typed outside the checkout is the runner's choice; a path typed *inside* it whose
   real path leads out is a link the pull request planted, and is refused).
2. **Regular files only**, opened non-blocking (core.safeio): never a FIFO, device, socket or folder.
3. **Bytes capped per file and counted per run** (`RunBytes`): a reader asks for what it may need, the door
   refuses more than the run has left.

Refusals are `Refused` (an OSError whose text never holds the runner's absolute path), so readers that already
report an OSError as a located finding keep doing so. Outside a run (`guarded` not entered) only the per-file
checks and caps apply: the API and tests that read a file by hand keep working, confined to nothing but what
they name.
"""
from __future__ import annotations

import _thread  # threading's lock and thread-local state, without importing threading (start-up)
import contextlib
import errno
import os

from urdfcheck.core import safeio
from urdfcheck.core.walk import real as realpath  # remembered for the run

DEFAULT_RUN_BYTES = 2 * 1024**3  # what one run may read in all, every reader together, unless the runner raises it
DEFAULT_FILE_BYTES = 64 * 1024**2  # one file read whole, unless the reader asks for a smaller or larger cap


class Refused(OSError):
    """The door refused a path: outside the roots, not a regular file, or over a cap. `why` is safe to print."""

    def __init__(self, shown: str, why: str):
        super().__init__(errno.EACCES, why, shown)
        self.why = why
        self.shown = shown

    def __str__(self) -> str:
        return f"{self.shown}: {self.why}"


class RunBytes:
    """Bytes one run may still read through the door."""

    def __init__(self, total: int = DEFAULT_RUN_BYTES):
        self.total = total
        self.used = 0
        self._lock = _thread.allocate_lock()

    def take(self, n: int, shown) -> None:
        """`shown`: the file as a message names it, or a path to name so (`_shown`, only for the refusal: a run
        reads hundreds of files)."""
        with self._lock:
            if self.used + n > self.total:
                raise Refused(shown if isinstance(shown, str) else _shown(shown),
                              f"the run's read budget ({self.total // 2**20} MiB) is used up")
            self.used += n


class _Run:
    def __init__(self, roots, budget: RunBytes):
        self.roots: list[str] = []
        self.budget = budget
        self.unconfined = False  # the runner lowered the guard (`unconfined`)
        for r in roots:
            self.add_root(r)

    def add_root(self, root) -> None:
        real = realpath(os.fspath(root))
        if real not in self.roots:
            self.roots.append(real)


_state = _thread._local()


def _current() -> _Run | None:
    return getattr(_state, "run", None)


@contextlib.contextmanager
def guarded(roots, total_bytes: int | None = None):
    """Enter a run: from here every read is confined to `roots` (and what is added with `add_root`) and counted."""
    prev = _current()
    _state.run = _Run(roots, RunBytes(DEFAULT_RUN_BYTES if total_bytes is None else total_bytes))
    try:
        yield _state.run
    finally:
        _state.run = prev


def add_root(root) -> None:
    """A folder the run may read below: a package root the resolver found, a folder the runner named."""
    run = _current()
    if run is not None:
        run.add_root(root)


def _shown(path) -> str:
    from urdfcheck.core.paths import shown

    p = os.fspath(path)
    return shown(p, None) if os.path.isabs(p) else p


def _under(real: str, root: str) -> bool:
    return real == root or real.startswith(root.rstrip(os.sep) + os.sep)


def confine(path, *, runner: bool = False) -> str:
    """The real path of `path`, or Refused when it leaves the run's roots.

    `runner`: the path was typed by the person running the tool. Typed outside every root, it is theirs to name
    (it becomes a root of its own); typed inside a root, its real path must stay inside one."""
    p = os.path.abspath(os.fspath(path))
    real = realpath(p)
    run = _current()
    if run is None or not run.roots or run.unconfined:
        return real
    if any(_under(real, r) for r in run.roots):
        return real
    if runner and not any(_under(p, r) for r in run.roots):
        return real
    raise Refused(_shown(path), "refused: its real path lies outside the checkout and the packages of this run "
                                "(a link out of the checkout)")


def admit(path, *, limit: int = DEFAULT_FILE_BYTES, runner: bool = False) -> str:
    """The real path of a regular file a library must open by name (sqlite3), confined and within `limit`; its
    size is counted in the run's budget."""
    real = confine(path, runner=runner)
    try:
        st = safeio.check_regular(real)
    except OSError as e:
        raise Refused(_shown(path), e.strerror or "cannot be read") from None
    if st.st_size > limit:
        raise Refused(_shown(path), f"larger than {limit // 2**20} MiB")
    run = _current()
    if run is not None:
        run.budget.take(st.st_size, _shown(path))
    return real


overlaid = safeio.overlaid  # the unsaved text of an editor's open documents (`urdfcheck server`)


def read_bytes(path, *, limit: int = DEFAULT_FILE_BYTES, runner: bool = False) -> bytes:
    """At most `limit + 1` bytes of a confined regular file (a caller tells "too large" by the extra byte)."""
    real = confine(path, runner=runner)
    try:
        data = safeio.read_file(real, limit)
    except safeio.NotRegularFile as e:
        raise Refused(_shown(path), e.strerror or "not a regular file") from None
    run = _current()
    if run is not None:
        run.budget.take(len(data), _Path(path))
    return data


class _Path:
    """A path the budget names only if it refuses the read."""

    __slots__ = ("path",)

    def __init__(self, path):
        self.path = path

    def __fspath__(self):
        return os.fspath(self.path)


def read_text(path, *, limit: int = DEFAULT_FILE_BYTES, runner: bool = False, errors: str = "replace") -> str:
    """`read_bytes` decoded as UTF-8."""
    return read_bytes(path, limit=limit, runner=runner).decode("utf-8", errors)


class _Counted:
    """A binary file object whose reads are capped at `limit` bytes and counted in the run's budget."""

    def __init__(self, fd: int, shown: str, limit: int, run: _Run | None):
        self._f = os.fdopen(fd, "rb", buffering=0)
        self._shown, self._left, self._run = shown, limit, run

    def _count(self, n: int) -> None:
        self._left -= n
        if self._left < 0:
            raise Refused(self._shown, "read past the size cap for this file")
        if self._run is not None:
            self._run.budget.take(n, self._shown)

    def read(self, n: int = -1) -> bytes:
        data = self._f.read() if n is None or n < 0 else self._f.read(n)
        self._count(len(data))
        return data

    def readinto(self, buf) -> int:
        n = self._f.readinto(buf)
        self._count(n or 0)
        return n

    def seek(self, *a) -> int:
        return self._f.seek(*a)

    def tell(self) -> int:
        return self._f.tell()

    def seekable(self) -> bool:
        return True

    def readable(self) -> bool:
        return True

    def close(self) -> None:
        self._f.close()

    @property
    def closed(self) -> bool:
        return self._f.closed

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def open_stream(path, *, limit: int = DEFAULT_FILE_BYTES, runner: bool = False) -> _Counted:
    """A confined regular file opened for reading in pieces; at most `limit` bytes may be read from it."""
    real = confine(path, runner=runner)
    try:
        safeio.check_regular(real)
        fd = os.open(real, safeio._FLAGS)
    except safeio.NotRegularFile as e:
        raise Refused(_shown(path), e.strerror or "not a regular file") from None
    st = os.fstat(fd)
    if not _regular(st.st_mode):
        os.close(fd)
        raise Refused(_shown(path), "not a regular file")
    return _Counted(fd, _shown(path), limit, _current())


def _regular(mode: int) -> bool:
    import stat

    return stat.S_ISREG(mode)


def active() -> bool:
    """A run is guarded (`guarded` entered): a caller that may be inside one enters its own only when not."""
    return _current() is not None


def guarding(typed=()):
    """`guarded` around the checkout of the working directory and the paths the runner `typed`
    (core.checkout.run_roots), unless a run is guarded already: then its roots and budget go on, and the roots of
    what is typed are added to it."""
    from urdfcheck.core.checkout import run_roots

    roots = run_roots([p for p in typed if p])
    run = _current()
    if run is None:
        return guarded(roots)
    for r in roots:  # an inner run (the base revision's tree of --diff-base): what it was typed is the runner's
        if not any(_under(realpath(r), x) for x in run.roots):
            run.add_root(r)
    return contextlib.nullcontext()


@contextlib.contextmanager
def unconfined():
    """The runner lowered the guard (`--trusted`): reads keep their per-file checks and caps and still count in
    the run's budget, but are not confined to the roots."""
    run = _current()
    if run is None or run.unconfined:
        yield
        return
    run.unconfined = True
    try:
        yield
    finally:
        run.unconfined = False


def runner_folder(path) -> str:
    """The real path of a folder the runner typed (a recording folder): confined as `runner=True`; when it lies
    outside every root it becomes one, so the files inside it are the runner's too. A folder typed inside the
    checkout stays the checkout's: its files must stay inside the roots (appended for urdfcheck.bag)."""
    real = confine(path, runner=True)
    run = _current()
    if run is not None and run.roots and not any(_under(real, r) for r in run.roots):
        run.add_root(real)
    return real


def budget() -> RunBytes | None:
    """The byte budget of the run in progress (None outside `guarded`): for readers that count bytes they do not
    read from a file, such as git blobs streamed from `git cat-file`."""
    run = _current()
    return run.budget if run is not None else None


def leaves(path) -> bool:
    """Whether the door would refuse `path` for leaving the run's roots (a committed link out of the checkout):
    discovery lists such a model so that the loader names it (X014) rather than it dropping out of the run."""
    try:
        confine(path)
    except Refused:
        return True
    return False


def roots() -> tuple[str, ...]:
    """The roots of the run in progress (empty outside one): what a plan made in one guarded block hands to the
    run that lints it later (the pytest plugin plans at collection and lints at the first item)."""
    run = _current()
    return tuple(run.roots) if run is not None else ()


def carried() -> tuple | None:
    """The guard of the run in progress as plain data (roots, unconfined, bytes left), for a child forked before
    the run was guarded (a spare worker, core.worker): it enters it with `enter_carried`. None outside a run."""
    run = _current()
    if run is None:
        return None
    return tuple(run.roots), bool(run.unconfined), max(0, run.budget.total - run.budget.used)


def enter_carried(state) -> None:
    """In a child forked before the run was guarded: from here on, every read is guarded as in the parent (its
    roots, whether the runner lowered the guard, the bytes the run had left when the job was sent)."""
    roots, unconfined, left = state
    run = _Run(roots, RunBytes(left))
    run.unconfined = bool(unconfined)
    _state.run = run
