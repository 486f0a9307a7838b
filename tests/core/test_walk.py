"""The one folder walk (core/walk.py) that discovery, the planner and the package scans share."""
import os

from hypothesis import given, settings
from hypothesis import strategies as st

from urdfcheck.core.walk import files, folders


def _tree(tmp_path):
    for d in ("b/y", "a/x", "a/build/z", ".hidden/q", "c"):
        (tmp_path / d).mkdir(parents=True)
    for f in ("a/x/f.urdf", "b/g.xacro", "c/h.txt", "top.txt", "a/build/COLCON_IGNORE"):
        (tmp_path / f).write_text("x")
    os.symlink(tmp_path / "b", tmp_path / "c" / "link_to_b")
    return tmp_path


def test_same_order_as_a_sorted_os_walk_without_hidden_ignored_or_linked_folders(tmp_path):
    root = _tree(tmp_path)
    want = []
    for here, dirs, names in os.walk(root):
        dirs[:] = sorted(d for d in dirs if not d.startswith(".")
                         and not os.path.exists(os.path.join(here, d, "COLCON_IGNORE")))
        want.append((here, sorted(names)))
    got = [(here, files(entries)) for here, entries in folders(root)]
    assert got == want
    assert not any("link_to_b" in here for here, _ in got)  # a link to a folder is listed, never entered


def test_limits(tmp_path):
    root = _tree(tmp_path)
    assert [h for h, _ in folders(root, max_depth=0)] == [str(root)]
    assert len(list(folders(root, max_dirs=2))) == 2
    assert list(folders(root / "missing")) == []


def _listings(monkeypatch):
    from urdfcheck.core import walk

    calls = []
    real = walk.os.scandir
    monkeypatch.setattr(walk.os, "scandir", lambda p: calls.append(p) or real(p))
    return calls


def test_a_run_lists_each_folder_once(tmp_path, monkeypatch):
    """Inside a run (`remembered`), a second walk over the same folders lists none of them again and yields the
    same entries; outside, every walk lists afresh (an edit between two API calls is seen)."""
    from urdfcheck.core.walk import remembered

    root = _tree(tmp_path)
    calls = _listings(monkeypatch)
    first = [(h, files(e)) for h, e in folders(root)]
    listed = len(calls)  # the folders walked, and a/build, listed to find its COLCON_IGNORE
    assert listed == len(first) + 1
    with remembered():
        inside = [(h, files(e)) for h, e in folders(root)]
        again = [(h, files(e)) for h, e in folders(root / "a")]  # a walk of a part of what was walked
        assert inside == first and again == [x for x in first if x[0].startswith(str(root / "a"))]
        assert len(calls) == 2 * listed
        (root / "a" / "new.urdf").write_text("x")  # within a run, files do not change: the listing is kept
        assert "new.urdf" not in files(dict(folders(root))[str(root / "a")])
    assert "new.urdf" in files(dict(folders(root))[str(root / "a")])


def test_the_memo_is_bounded(tmp_path, monkeypatch):
    from urdfcheck.core import walk

    root = _tree(tmp_path)
    monkeypatch.setattr(walk, "MEMO_ENTRIES", 3)
    calls = _listings(monkeypatch)
    with walk.remembered():
        n = len(list(folders(root)))
        list(folders(root))
    assert n < len(calls) < 2 * n  # the first folders fit, the rest is listed again


# --- core.paths.shown: remembered per (path, root, working directory); the same as computing it each time ---------
def _shown_reference(text, root, run_root):
    if not text or text.startswith("<"):
        return text
    p = os.path.abspath(text)
    base = os.path.abspath(root or run_root or os.getcwd())
    rel = os.path.relpath(p, base)
    if rel != ".." and not rel.startswith(".." + os.sep):
        return rel
    top = p.split(os.sep)[1:2]
    return rel if top and top == base.split(os.sep)[1:2] and top != [""] else p


_PARTS = st.sampled_from(["a", "b", "..", ".", "", "work", "opt"])
_PATHS = st.builds(lambda lead, parts: lead + "/".join(parts), st.sampled_from(["", "/", "./", "../"]),
                   st.lists(_PARTS, max_size=4))


@given(text=_PATHS, root=st.none() | _PATHS, run_root=st.none() | _PATHS,
       cwd=st.sampled_from(["/", "/tmp", "/usr/lib"]))
@settings(max_examples=300, deadline=None)
def test_shown_paths_match_the_plain_computation(text, root, run_root, cwd):
    from urdfcheck.core import paths

    old = os.getcwd()
    try:
        os.chdir(cwd)
        with paths.showing(run_root):
            expected = _shown_reference(text, root, paths.showing_root())
            assert paths.shown(text, root) == expected
            assert paths.shown(text, root) == expected  # remembered
    finally:
        os.chdir(old)


def test_skipped_by_the_marker_files_ros_tools_read_never_by_name(tmp_path):
    """Issue 36: colcon builds a package under a plain folder named build, log, install, venv (it skips by the
    COLCON_IGNORE it writes into its own bases); a venv is skipped by its pyvenv.cfg, a catkin space by .catkin,
    and a marker beside a package.xml other than *_IGNORE does not hide the package."""
    plain = ["build/p", "log/p", "install/p", "venv/p", "devel/p", "node_modules/p", "__pycache__/p"]
    marked = {"ws/build": "COLCON_IGNORE", "ws/install": "COLCON_IGNORE", "ws/log": "COLCON_IGNORE",
              "amen": "AMENT_IGNORE", "cat": "CATKIN_IGNORE", "env": "pyvenv.cfg", "ws/devel": ".catkin",
              "web/node_modules": ".package-lock.json"}
    for d in plain + [f"{m}/p" for m in marked]:
        (tmp_path / d).mkdir(parents=True)
        (tmp_path / d / "package.xml").write_text("<package/>")
    for d, marker in marked.items():
        (tmp_path / d / marker).write_text("")
    (tmp_path / "pkgvenv").mkdir()
    for f in ("package.xml", "pyvenv.cfg"):  # a package beside a venv marker: colcon builds it
        (tmp_path / "pkgvenv" / f).write_text("")
    got = {os.path.relpath(h, tmp_path) for h, e in folders(tmp_path) if "package.xml" in files(e)}
    assert got == set(plain) | {"pkgvenv"}
    assert [h for h, _ in folders(tmp_path / "amen")][:2] == [str(tmp_path / "amen"), str(tmp_path / "amen" / "p")]
