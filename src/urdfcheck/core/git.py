"""The one door to git: the repository the runner put there, read without running anything else (issue 36).

On a pull request every file of the checkout is the attacker's. A folder the pull request committed with `HEAD`,
`objects/`, `refs/` and `config` as plain files is, to git's own discovery, a bare repository, and git then obeys
that config: a promisor remote whose lazy fetch runs a shell command, hooks, an fsmonitor. So:

- **The repository is found here, never by git**: walking up from the folder the runner named (or the working
  directory) to the nearest `.git` folder, or `.git` file of a worktree / submodule ("gitdir: ..."). Git forbids
  committing a path named `.git`, so what is found is what the runner's checkout made. git is then always called
  with an explicit `--git-dir` and `--work-tree`, and `safe.bareRepository=explicit` for anything below.
- **Nothing runs but git itself**: no hooks, no fsmonitor, no pager, no prompt, no system config, no `GIT_*`
  variable from the environment; no transport at all (`GIT_ALLOW_PROTOCOL` with no protocol in it outranks any
  `protocol.<name>.allow` a config may set, so a lazy fetch of a missing object by a promisor remote -- `ext::`
  URL, a local URL with `remote.<name>.uploadpack` -- fails instead of running its command; `GIT_NO_LAZY_FETCH`
  says the same to git >= 2.44). Only plumbing that applies no filter or textconv is used (rev-parse, ls-tree,
  cat-file).
- **Blobs are streamed, once each**: a revision's tree is listed, blobs are asked for by object id once (120 tree
  entries naming one blob cost one read; the copies are hard links), each capped, every byte counted in the run's
  read budget (`core.door`), written into a private temporary folder outside the user's tree.
- **Odd names are notes, not crashes**: a name git holds but a file system or a report cannot (a component over
  255 bytes, bytes that are not UTF-8, control characters, `..`) is not written; a note names it, escaped.
  No message holds the temporary folder's path.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import tempfile
import threading

from urdfcheck.core import door, lazyre

# a blob above the door's cap for one file is written empty (and noted): the working tree's copy is not read either
MAX_FILE = door.DEFAULT_FILE_BYTES
MAX_FILES = 50_000
NAME_MAX = 255
TIMEOUT = 120
CHUNK = 1 << 20
# config given on the command line outranks the repository's; each entry closes one way to run a command
_CONFIG = (
    "safe.bareRepository=explicit", "core.fsmonitor=false", "core.hooksPath=/dev/null", "core.pager=cat",
    "protocol.allow=never", "core.sshCommand=false", "core.askPass=false", "credential.helper=",
    "fetch.recurseSubmodules=false", "submodule.recurse=false", "core.untrackedCache=false",
    "log.showSignature=false", "gc.auto=0", "maintenance.auto=false",
)
_ODD = lazyre.compile(r"[\x00-\x1f\x7f-\x9f\u061c\u200e\u200f\u202a-\u202e\u2066-\u2069]")


class GitError(ValueError):
    """git could not do what was asked (no repository, unknown revision, a budget used up). Safe to print."""


class Repo:
    """A repository found by `find`: its git folder and its work tree (both real paths)."""

    def __init__(self, git_dir: str, work_tree: str):
        self.git_dir, self.work_tree = git_dir, work_tree

    def __repr__(self) -> str:
        return f"Repo({self.work_tree!r})"

    # --- running git ---------------------------------------------------------------------------------------------
    def argv(self, *args: str) -> list[str]:
        cfg = [x for c in _CONFIG for x in ("-c", c)]
        return ["git", "--no-pager", "--no-replace-objects", f"--git-dir={self.git_dir}",
                f"--work-tree={self.work_tree}", *cfg, *args]

    def run(self, *args: str, data: bytes | None = None) -> bytes:
        try:
            p = subprocess.run(self.argv(*args), input=data, capture_output=True, env=env(), timeout=TIMEOUT,
                               cwd=self.work_tree, stdin=None if data is not None else subprocess.DEVNULL)
        except FileNotFoundError:
            raise GitError("git is not installed") from None
        except subprocess.TimeoutExpired:
            raise GitError(f"git {args[0]} took longer than {TIMEOUT} s") from None
        if p.returncode != 0:
            raise GitError(self._said(p.stderr) or f"git {args[0]} failed")
        return p.stdout

    def _said(self, stderr: bytes) -> str:
        lines = stderr.decode("utf-8", "replace").strip().splitlines()
        msg = lines[-1] if lines else ""
        for p in (self.git_dir, self.work_tree):
            msg = msg.replace(p, "<repository>" if p == self.work_tree else "<repository>/.git")
        if "promisor remote" in msg or "lazy fetch" in msg:
            msg += " (a partial clone: urdfcheck never fetches; fetch the revision's files first)"
        return _escape(msg)

    # --- revisions -------------------------------------------------------------------------------------------------
    def commit(self, rev: str) -> str:
        """The commit id `rev` names; GitError when it names none (never an option: `-x` is refused)."""
        if not rev or rev.startswith("-") or _ODD.search(rev) or len(rev) > 1024:
            raise GitError(f"{_escape(rev)!s} is not a revision")
        out = self.run("rev-parse", "--verify", "--quiet", "--end-of-options", f"{rev}^{{commit}}")
        sha = out.decode("ascii", "replace").strip()
        if not re.fullmatch(r"[0-9a-f]{40}|[0-9a-f]{64}", sha):
            raise GitError(f"{_escape(rev)} is not a revision")
        return sha

    def tree(self, commit: str, path: str | None = None) -> list[tuple[bytes, str, str]]:
        """(path as bytes, mode, object id) of every blob, link and submodule of `commit` (below `path`)."""
        args = ["ls-tree", "-r", "-z", "--full-tree", commit]
        if path:
            args += ["--", path]
        out = []
        for rec in self._records(args):
            meta, _, name = rec.partition(b"\t")
            parts = meta.split()
            if len(parts) != 3:
                continue
            mode, kind, oid = (x.decode("ascii", "replace") for x in parts)
            out.append((name, mode if kind != "commit" else "160000", oid))
            if len(out) > MAX_FILES:
                raise GitError(f"more than {MAX_FILES} files in the revision")
        return out

    def _records(self, args):
        """The NUL-separated records git prints, read as they come: a listing of millions of entries is stopped
        at MAX_FILES, never held whole."""
        try:
            proc = subprocess.Popen(self.argv(*args), stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                    stderr=subprocess.PIPE, env=env(), cwd=self.work_tree)
        except FileNotFoundError:
            raise GitError("git is not installed") from None
        timer = threading.Timer(TIMEOUT, proc.kill)
        timer.start()
        try:
            rest = b""
            while True:
                piece = proc.stdout.read(CHUNK)
                if not piece:
                    break
                *done, rest = (rest + piece).split(b"\0")
                yield from (r for r in done if r)
            if rest:
                yield rest
            err = proc.stderr.read(65536)
            if proc.wait() != 0:
                raise GitError(self._said(err) or f"git {args[0]} failed")
        finally:
            timer.cancel()
            if proc.poll() is None:
                proc.kill()
                proc.wait()
            proc.stdout.close()
            proc.stderr.close()

    def sizes(self, oids) -> dict[str, int]:
        oids = list(dict.fromkeys(oids))
        if not oids:
            return {}
        out = self.run("cat-file", "--batch-check=%(objectname) %(objecttype) %(objectsize)",
                       data="".join(f"{o}\n" for o in oids).encode())
        sizes = {}
        for line in out.decode("ascii", "replace").splitlines():
            parts = line.split()
            if len(parts) == 3 and parts[1] == "blob" and parts[2].isdigit():
                sizes[parts[0]] = int(parts[2])
        return sizes

    def blobs(self, oids, budget: door.RunBytes, shown: str = "git"):
        """Yield (object id, chunks) for each object id, once, in order: `chunks` must be consumed before the next.
        Every byte is counted in `budget` (Refused when it runs out)."""
        oids = list(dict.fromkeys(oids))
        if not oids:
            return
        try:
            proc = subprocess.Popen(self.argv("cat-file", "--batch"), stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                    stderr=subprocess.DEVNULL, env=env(), cwd=self.work_tree)
        except FileNotFoundError:
            raise GitError("git is not installed") from None
        assert proc.stdout is not None  # stdout=PIPE

        def feed():  # a thread: cat-file stops reading while its output is not read
            try:
                for o in oids:
                    proc.stdin.write(f"{o}\n".encode())
                proc.stdin.close()
            except (OSError, ValueError):
                pass

        writer = threading.Thread(target=feed, daemon=True)
        writer.start()
        timer = threading.Timer(TIMEOUT, proc.kill)
        timer.start()
        try:
            for want in oids:
                head = proc.stdout.readline().decode("ascii", "replace").split()
                if len(head) != 3 or head[0] != want or not head[2].isdigit():
                    raise GitError("git cat-file: object missing or unreadable")
                size = int(head[2])

                def chunks(left=size):
                    while left > 0:
                        piece = proc.stdout.read(min(CHUNK, left))
                        if not piece:
                            raise GitError("git cat-file: the object ended early")
                        budget.take(len(piece), shown)
                        left -= len(piece)
                        yield piece
                    proc.stdout.read(1)  # the newline after the contents

                it = chunks()
                yield want, it
                for _ in it:  # a caller that stopped early: skip the rest (still counted: it was read)
                    pass
        finally:
            timer.cancel()
            proc.kill()
            proc.wait()
            proc.stdout.close()
            writer.join(timeout=5)

    def read(self, commit: str, path: str, limit: int, budget: door.RunBytes | None = None) -> bytes | None:
        """The contents of the blob at `path` in `commit` (None when there is none, or it is a link or submodule);
        GitError when it is larger than `limit` bytes."""
        entries = [e for e in self.tree(commit, path) if e[0] == path.encode("utf-8", "surrogateescape")]
        if not entries or entries[0][1] not in ("100644", "100755"):
            return None
        oid = entries[0][2]
        size = self.sizes([oid]).get(oid)
        if size is None:
            return None
        if size > limit:
            raise GitError(f"{_escape(path)} is larger than {limit // 1024} KiB in the revision")
        out = b""
        for _, chunks in self.blobs([oid], budget or _budget(), shown=path):
            out = b"".join(chunks)
        return out


def env() -> dict:
    """The environment git runs in: the runner's, less every GIT_ variable; no system config, no prompt, no
    transport, no lazy fetch."""
    out = {k: v for k, v in os.environ.items() if not k.startswith("GIT_")}
    out.update(GIT_CONFIG_NOSYSTEM="1", GIT_TERMINAL_PROMPT="0", GIT_OPTIONAL_LOCKS="0", GIT_NO_LAZY_FETCH="1",
               GIT_ALLOW_PROTOCOL="urdfcheck-none", GIT_PROTOCOL_FROM_USER="0", GIT_ASKPASS="false",
               SSH_ASKPASS="false", GIT_PAGER="cat", PAGER="cat", GIT_ATTR_NOSYSTEM="1", LC_ALL="C")
    return out


def find(start) -> Repo | None:
    """The repository around `start` (a file or folder): the nearest folder above holding `.git` as a folder, or
    as a file naming a git folder ("gitdir: PATH"). Never a folder that merely looks like a bare repository."""
    d = os.path.realpath(os.path.abspath(os.fspath(start)))
    if not os.path.isdir(d):
        d = os.path.dirname(d)
    while True:
        dot = os.path.join(d, ".git")
        git_dir = None
        if os.path.isdir(dot) and not os.path.islink(dot):
            git_dir = dot
        elif os.path.isfile(dot) and not os.path.islink(dot):
            git_dir = _gitfile(dot, d)
        if git_dir is not None and os.path.isfile(os.path.join(git_dir, "HEAD")):
            return Repo(os.path.realpath(git_dir), d)
        up = os.path.dirname(d)
        if up == d:
            return None
        d = up


def _gitfile(dot: str, d: str) -> str | None:
    try:  # a .git file of a worktree or submodule: one short line, written by git
        line = door.read_bytes(dot, limit=4096, runner=True).split(b"\n", 1)[0].decode("utf-8", "strict")
    except (OSError, UnicodeDecodeError):
        return None
    if not line.startswith("gitdir:"):
        return None
    target = os.path.join(d, line[len("gitdir:"):].strip())
    return target if os.path.isdir(target) else None


def _budget() -> door.RunBytes:
    current = door.budget()
    return current if current is not None else door.RunBytes()


def _escape(s: str) -> str:
    """`s` with every character a terminal or report would not show as itself (control, bidi and other format
    characters, unassigned code points, undecodable bytes) written as an escape."""
    s = s.encode("utf-8", "surrogateescape").decode("utf-8", "backslashreplace")
    return "".join(ch if ch.isprintable() else ch.encode("unicode_escape").decode("ascii") for ch in s)


def shown_name(name: bytes) -> str:
    """A path git holds, as a report may show it."""
    return _escape(name.decode("utf-8", "surrogateescape"))


def odd(name: bytes) -> str | None:
    """Why a path git holds is not written (None: it is written)."""
    try:
        text = name.decode("utf-8")
    except UnicodeDecodeError:
        return "its name is not UTF-8"
    if _ODD.search(text) or not text.isprintable():
        return "its name holds control, bidi or unassigned characters"
    parts = name.split(b"/")
    if name.startswith(b"/") or any(p in (b"", b".", b"..") or p.lower() == b".git" for p in parts):
        return "its name is not a plain relative path"
    if any(len(p) > NAME_MAX for p in parts):
        return f"a part of its name is longer than {NAME_MAX} bytes"
    if len(name) > 3000:
        return "its name is too long"
    return None


class Export:
    """A revision's files in a private temporary folder (`root`), removed by `cleanup` (or as a context manager).
    `notes`: what was not written, and why (names escaped, relative to the repository)."""

    def __init__(self, root: str, rev: str, commit: str):
        self.root, self.rev, self.commit = root, rev, commit
        self.notes: list[str] = []
        self.written = 0  # bytes written (each blob once)

    def cleanup(self) -> None:
        shutil.rmtree(self.root, ignore_errors=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.cleanup()


def export(repo: Repo, rev: str, *, max_file: int = MAX_FILE, budget: door.RunBytes | None = None) -> Export:
    """The files of `rev` (the whole repository: a model includes its sibling packages) in a new temporary folder
    outside the work tree. Links and submodules are not written (a link could point anywhere on the machine);
    blobs above `max_file` are written empty; each blob is read once, its other copies are hard links."""
    commit = repo.commit(rev)
    entries = repo.tree(commit)
    budget = budget or _budget()
    root = tempfile.mkdtemp(prefix="urdfcheck-rev-")
    out = Export(root, rev, commit)
    try:
        real = os.path.realpath(root)
        wt = repo.work_tree.rstrip(os.sep) + os.sep
        if real.startswith(wt):
            raise GitError("the temporary folder lies inside the repository (set TMPDIR elsewhere)")
        by_oid: dict[str, list[bytes]] = {}
        for name, mode, oid in entries:
            if mode not in ("100644", "100755"):
                continue  # links, submodules
            why = odd(name)
            if why is not None:
                out.notes.append(f"{rev}:{shown_name(name)}: not read ({why})")
                continue
            by_oid.setdefault(oid, []).append(name)
        sizes = repo.sizes(by_oid)
        broot = os.fsencode(root)
        wanted = []
        for oid, names in by_oid.items():
            if oid not in sizes:  # not in the local repository (and never fetched): said, not guessed
                out.notes.extend(f"{rev}:{shown_name(n)}: not read (its contents are not in the local repository)"
                                 for n in names)
                continue
            if sizes[oid] > max_file:
                for n in names:
                    if _place(broot, n, None, out) is not None:
                        out.notes.append(f"{rev}:{shown_name(n)}: written empty (larger than "
                                         f"{max_file // 2**20} MiB)")
            else:
                wanted.append(oid)
        for oid, chunks in repo.blobs(wanted, budget, shown=f"{rev} (git)"):
            first, *copies = by_oid[oid]
            dest = _place(broot, first, chunks, out)
            for n in copies:
                if dest is None:
                    out.notes.append(f"{rev}:{shown_name(n)}: not read (a copy of a file that could not be written)")
                else:
                    _place(broot, n, None, out, link=dest)
    except door.Refused as e:
        out.cleanup()
        raise GitError(f"reading {_escape(rev)}: {e.why}") from None
    except BaseException:
        out.cleanup()
        raise
    return out


def _place(broot: bytes, name: bytes, chunks, out: Export, link: bytes | None = None) -> bytes | None:
    """Write one file of the revision (contents, empty, or a hard link to `link`); a note when it cannot be."""
    dest = os.path.join(broot, name)
    try:
        os.makedirs(os.path.dirname(dest), exist_ok=True)
        if link is not None:
            os.link(link, dest)
            return dest
        fd = os.open(dest, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0), 0o600)
        with os.fdopen(fd, "wb") as f:
            for piece in chunks or ():
                f.write(piece)
                out.written += len(piece)
        return dest
    except door.Refused:
        raise
    except OSError as e:
        out.notes.append(f"{out.rev}:{shown_name(name)}: not read ({e.strerror or 'cannot be written'})")
        for _ in chunks or ():  # the stream moves on to the next object
            pass
        return None
