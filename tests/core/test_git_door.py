"""git only where the runner put it (issue 36): the repository is found by urdfcheck, nothing but git runs,
blobs are read once each within the budget, odd names are notes."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
AGV = ROOT / "examples" / "agv"
SRC = str(ROOT / "src")
MISSING = "0123456789abcdef0123456789abcdef01234567"

pytestmark = pytest.mark.skipif(shutil.which("git") is None, reason="git not installed")


def cli(*args, cwd=None, env=None):
    e = {**os.environ, "PYTHONPATH": SRC + os.pathsep + os.environ.get("PYTHONPATH", ""), **(env or {})}
    return subprocess.run([sys.executable, "-m", "urdfcheck", *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, env=e, timeout=180)


def git(*args, cwd, data=None):
    env = {**{k: v for k, v in os.environ.items() if not k.startswith("GIT_")}, "GIT_AUTHOR_NAME": "t",
           "GIT_AUTHOR_EMAIL": "t@t", "GIT_COMMITTER_NAME": "t", "GIT_COMMITTER_EMAIL": "t@t",
           "GIT_CONFIG_NOSYSTEM": "1"}
    return subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True, env=env, input=data).stdout


def repo_with_agv(tmp_path) -> Path:
    repo = tmp_path / "repo"
    shutil.copytree(AGV, repo / "agv_description")
    git("init", "-q", cwd=repo)
    git("add", "-A", cwd=repo)
    git("commit", "-qm", "init", cwd=repo)
    return repo


def test_a_committed_bare_repository_is_never_taken_for_one(tmp_path):
    """A folder holding HEAD, objects/, refs/ and config as plain files (what a pull request can commit): git's
    own discovery takes it for a bare repository and obeys its config; urdfcheck looks for .git only."""
    evil = tmp_path / "evil"
    evil.mkdir()
    shutil.copy(AGV / "urdf/agv.urdf", evil / "robot.urdf")
    marker = tmp_path / "MARKER"
    (evil / "HEAD").write_text("ref: refs/heads/main\n")
    (evil / "objects").mkdir()
    (evil / "refs" / "heads").mkdir(parents=True)
    (evil / "config").write_text(
        "[core]\n\trepositoryformatversion = 1\n\tbare = false\n\tworktree = .\n"
        "[extensions]\n\tpartialClone = origin\n"
        f'[remote "origin"]\n\turl = "ext::sh -c touch% {marker}"\n\tpromisor = true\n'
        "[protocol]\n\tallow = always\n")
    res = cli("diff", "--git", MISSING, cwd=evil)
    assert not marker.exists()
    assert res.returncode == 2 and "no git repository" in res.stderr
    assert not marker.exists()
    res = cli("diff", "--git", MISSING, evil, cwd=tmp_path)
    assert res.returncode == 2 and not marker.exists()


def _promisor(repo: Path, url: str, **extra) -> None:
    git("config", "core.repositoryformatversion", "1", cwd=repo)
    git("config", "extensions.partialClone", "origin", cwd=repo)
    git("config", "remote.origin.url", url, cwd=repo)
    git("config", "remote.origin.promisor", "true", cwd=repo)
    git("config", "protocol.allow", "always", cwd=repo)
    for k, v in extra.items():
        git("config", k.replace("_", "."), v, cwd=repo)


def test_no_lazy_fetch_runs_a_promisor_remote_ext_url(tmp_path):
    repo = repo_with_agv(tmp_path)
    marker = tmp_path / "MARKER"
    _promisor(repo, f"ext::sh -c touch% {marker}", protocol_ext_allow="always")
    res = cli("diff", "--git", MISSING, cwd=repo)
    assert res.returncode == 2, res.stderr
    assert not marker.exists()
    assert "Traceback" not in res.stderr


def test_no_lazy_fetch_runs_an_upload_pack_command(tmp_path):
    repo = repo_with_agv(tmp_path)
    other = tmp_path / "other"
    git("init", "-q", "--bare", str(other), cwd=tmp_path)
    marker = tmp_path / "MARKER"
    _promisor(repo, str(other), remote_origin_uploadpack=f"touch {marker}; git-upload-pack",
              protocol_file_allow="always")
    res = cli("diff", "--git", MISSING, cwd=repo)
    assert res.returncode == 2, res.stderr
    assert not marker.exists()


def test_git_dir_from_the_environment_is_not_used(tmp_path):
    repo = repo_with_agv(tmp_path)
    other = tmp_path / "other"
    other.mkdir()
    git("init", "-q", cwd=other)
    (other / "x").write_text("x")
    git("add", "x", cwd=other)
    git("commit", "-qm", "o", cwd=other)
    f = repo / "agv_description/urdf/agv.urdf.xacro"
    f.write_text(f.read_text().replace('xyz="0.25 0 0.15"', 'xyz="0.26 0 0.15"'))
    res = cli("diff", "--git", "HEAD", "--format", "json", cwd=repo, env={"GIT_DIR": str(other / ".git")})
    data = json.loads(res.stdout)
    assert {m["status"] for m in data["models"]} >= {"changed"}  # compared with repo's HEAD, not other's


def test_a_worktree_is_found_through_its_git_file(tmp_path):
    repo = repo_with_agv(tmp_path)
    wt = tmp_path / "wt"
    git("worktree", "add", "-q", str(wt), cwd=repo)
    assert (wt / ".git").is_file()
    f = wt / "agv_description/urdf/agv.urdf.xacro"
    f.write_text(f.read_text().replace('xyz="0.25 0 0.15"', 'xyz="0.26 0 0.15"'))
    data = json.loads(cli("diff", "--git", "HEAD", "--format", "json", cwd=wt / "agv_description").stdout)
    changed = [m for m in data["models"] if m["status"] == "changed"]
    assert changed and all([x["frame"] for x in m["moved"]] == ["laser_link"] for m in changed)


def test_copies_of_one_blob_are_read_once_within_the_budget(tmp_path):
    from urdfcheck.core import door
    from urdfcheck.core import git as gitdoor

    repo = tmp_path / "repo"
    (repo / "copies").mkdir(parents=True)
    blob = os.urandom(256 * 1024)
    for i in range(120):
        (repo / "copies" / f"c{i}.stl").write_bytes(blob)
    (repo / "a.txt").write_text("a\n")
    git("init", "-q", cwd=repo)
    git("add", "-A", cwd=repo)
    git("commit", "-qm", "copies", cwd=repo)
    found = gitdoor.find(repo / "copies")
    assert found is not None and os.path.samefile(found.work_tree, repo)
    budget = door.RunBytes(3 * len(blob))  # room for the blob three times, not 120
    with gitdoor.export(found, "HEAD", budget=budget) as tree:
        assert budget.used == len(blob) + 2
        assert tree.written == len(blob) + 2
        files = sorted(Path(tree.root, "copies").iterdir())
        assert len(files) == 120
        assert len({f.stat().st_ino for f in files}) == 1  # hard links: one copy on disk
        assert files[0].read_bytes() == blob
        root = tree.root
    assert not os.path.exists(root)  # removed afterwards
    import tempfile

    private = tmp_path / "private-tmp"
    private.mkdir()
    tempfile.tempdir, before = str(private), tempfile.tempdir
    try:
        with pytest.raises(gitdoor.GitError, match="budget"):
            gitdoor.export(found, "HEAD", budget=door.RunBytes(len(blob) // 2))
    finally:
        tempfile.tempdir = before
    assert os.listdir(private) == []  # what was written before the budget ran out is removed


def test_odd_names_are_notes_not_crashes(tmp_path):
    repo = repo_with_agv(tmp_path)
    oid = git("hash-object", "-w", "--stdin", cwd=repo, data=b"<robot name='x'/>\n").decode().strip()
    names = [b"agv_description/" + b"n" * 300 + b".urdf", b"agv_description/caf\xe9.urdf",
             b"agv_description/bad\x1b]52;c;x\x07.urdf", b"agv_description/\xe2\x80\xaeevil.urdf"]
    for name in names:
        git("update-index", "--add", "--cacheinfo", f"100644,{oid},{os.fsdecode(name)}", cwd=repo)
    git("commit", "-qm", "odd", cwd=repo)
    for fmt in ("text", "json", "markdown"):
        res = cli("diff", "--git", "HEAD", "--format", fmt, cwd=repo)
        assert res.returncode == 0, res.stderr
        out = res.stdout + res.stderr
        assert "Traceback" not in out and "urdfcheck-rev-" not in out and str(tmp_path) not in out
        assert "\x1b" not in out and "\u202e" not in out
        assert out.count("not read") >= 4, out


def test_no_temp_folder_in_messages_of_an_old_side_that_does_not_load(tmp_path):
    repo = repo_with_agv(tmp_path)
    f = repo / "agv_description/urdf/agv.urdf"
    good = f.read_text()
    f.write_text(good.replace("</robot>", ""))
    git("commit", "-qam", "broken", cwd=repo)
    f.write_text(good)
    for fmt in ("text", "json"):
        res = cli("diff", "--git", "HEAD", "--format", fmt, cwd=repo)
        assert res.returncode == 1
        assert "urdfcheck-rev-" not in res.stdout and "/tmp" not in res.stdout and str(repo) not in res.stdout
        assert "does not load" in res.stdout or '"unloadable"' in res.stdout


def test_a_listing_past_the_file_cap_is_stopped(tmp_path, monkeypatch):
    from urdfcheck.core import git as gitdoor

    repo = tmp_path / "repo"
    repo.mkdir()
    for i in range(30):
        (repo / f"f{i}.txt").write_text(str(i))
    git("init", "-q", cwd=repo)
    git("add", "-A", cwd=repo)
    git("commit", "-qm", "many", cwd=repo)
    found = gitdoor.find(repo)
    monkeypatch.setattr(gitdoor, "MAX_FILES", 10)
    with pytest.raises(gitdoor.GitError, match="more than 10 files"):
        gitdoor.export(found, "HEAD")


def test_any_revision_tree_is_written_or_noted(tmp_path):
    """Property (bounded): whatever names and contents a revision holds, `export` writes each file inside its
    folder with its contents, or notes it with a printable name; it raises nothing but GitError."""
    pytest.importorskip("hypothesis")
    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st

    from urdfcheck.core import door
    from urdfcheck.core import git as gitdoor

    part = st.binary(min_size=1, max_size=300).filter(lambda b: b"/" not in b and b"\0" not in b
                                                      and b not in (b".", b".."))
    name = st.lists(part, min_size=1, max_size=3).map(lambda ps: b"/".join(ps))
    entries = st.lists(st.tuples(name, st.sampled_from([b"", b"x", b"<robot name='r'/>", b"\xff\xfe" * 40])),
                       min_size=1, max_size=6, unique_by=lambda e: e[0].split(b"/")[0])
    counter = iter(range(10**6))

    @settings(max_examples=25, deadline=None, suppress_health_check=list(HealthCheck))
    @given(entries)
    def check(files):
        repo = tmp_path / f"r{next(counter)}"
        repo.mkdir()
        git("init", "-q", cwd=repo)
        for n, data in files:
            oid = git("hash-object", "-w", "--stdin", cwd=repo, data=data).decode().strip()
            r = subprocess.run(["git", "update-index", "--add", "--cacheinfo", f"100644,{oid},{os.fsdecode(n)}"],
                               cwd=repo, capture_output=True)
            if r.returncode:  # git itself refuses the name (.git, ./, a file under a file): nothing to read
                files = [f for f in files if f[0] != n]
        if not files:
            return
        git("commit", "-qm", "x", "--allow-empty", cwd=repo)
        try:
            tree = gitdoor.export(gitdoor.find(repo), "HEAD", budget=door.RunBytes(1 << 20))
        except gitdoor.GitError:
            return
        with tree:
            root = os.path.realpath(tree.root)
            for note in tree.notes:
                assert note.isprintable(), note
            noted = "\n".join(tree.notes)
            for n, data in files:
                dest = os.path.join(os.fsencode(root), n)
                if os.path.isfile(dest):
                    assert os.path.realpath(dest).startswith(os.fsencode(root))
                    with open(dest, "rb") as f:
                        assert f.read() == data
                else:
                    assert gitdoor.shown_name(n) in noted, (n, tree.notes)

    check()


def test_git_is_run_through_the_one_door_only():
    import re

    pattern = re.compile(r"""[\[(]\s*["']git["']\s*,""")
    src = ROOT / "src" / "urdfcheck"
    offenders = [str(p.relative_to(src)) for p in src.rglob("*.py")
                 if p != src / "core" / "git.py" and pattern.search(p.read_text(encoding="utf-8"))]
    assert offenders == []


def test_a_blob_over_the_cap_is_written_empty_and_noted(tmp_path):
    from urdfcheck.core import door
    from urdfcheck.core import git as gitdoor

    repo = tmp_path / "repo"
    repo.mkdir()
    (repo / "big.stl").write_bytes(b"x" * 5000)
    (repo / "small.urdf").write_text("<robot name='r'/>")
    git("init", "-q", cwd=repo)
    git("add", "-A", cwd=repo)
    git("commit", "-qm", "big", cwd=repo)
    budget = door.RunBytes(1 << 20)
    with gitdoor.export(gitdoor.find(repo), "HEAD", max_file=1000, budget=budget) as tree:
        assert Path(tree.root, "big.stl").read_bytes() == b""
        assert Path(tree.root, "small.urdf").read_text() == "<robot name='r'/>"
        assert [n for n in tree.notes if "big.stl" in n and "written empty" in n]
        assert budget.used == len("<robot name='r'/>")  # the big blob was never read
