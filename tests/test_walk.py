"""The one folder walk (core/walk.py) that discovery, the planner and the package scans share."""
import os

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
