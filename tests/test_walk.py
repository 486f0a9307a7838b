"""The one folder walk (core/walk.py) that discovery, the planner and the package scans share."""
import os

from hypothesis import given, settings
from hypothesis import strategies as st

from urdfcheck.core.walk import files, folders


def _tree(tmp_path):
    for d in ("b/y", "a/x", "a/build/z", ".hidden/q", "c"):
        (tmp_path / d).mkdir(parents=True)
    for f in ("a/x/f.urdf", "b/g.xacro", "c/h.txt", "top.txt"):
        (tmp_path / f).write_text("x")
    os.symlink(tmp_path / "b", tmp_path / "c" / "link_to_b")
    return tmp_path


def test_same_order_as_a_sorted_os_walk_without_hidden_build_or_linked_folders(tmp_path):
    root = _tree(tmp_path)
    want = []
    for here, dirs, names in os.walk(root):
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d != "build")
        want.append((here, sorted(names)))
    got = [(here, files(entries)) for here, entries in folders(root)]
    assert got == want
    assert not any("link_to_b" in here for here, _ in got)  # a link to a folder is listed, never entered


def test_limits(tmp_path):
    root = _tree(tmp_path)
    assert [h for h, _ in folders(root, max_depth=0)] == [str(root)]
    assert len(list(folders(root, max_dirs=2))) == 2
    assert list(folders(root / "missing")) == []


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
