"""`load.packages.leaves_cwd`: a path written below the working directory that really lies outside it (through a
link of the file or of a folder on the way) must be caught, also when a caller shares its cache of folders'
real paths across many files (discover does, one realpath per folder)."""
import os

from urdfcheck.load.packages import leaves_cwd


def test_links_of_files_and_of_folders_are_caught_with_and_without_a_shared_cache(tmp_path, monkeypatch):
    outside = tmp_path / "outside"
    (outside / "sub").mkdir(parents=True)
    (outside / "secret.urdf").write_text("x")
    (outside / "sub" / "deep.urdf").write_text("x")
    ws = tmp_path / "ws"
    (ws / "pkg" / "urdf").mkdir(parents=True)
    (ws / "pkg" / "urdf" / "ok.urdf").write_text("x")
    os.symlink(outside / "secret.urdf", ws / "pkg" / "urdf" / "file_link.urdf")
    os.symlink(outside, ws / "pkg" / "dir_link")
    os.symlink(ws / "pkg" / "urdf" / "ok.urdf", ws / "pkg" / "urdf" / "inner_link.urdf")  # stays inside
    monkeypatch.chdir(ws)
    cases = {"pkg/urdf/ok.urdf": False, "pkg/urdf/file_link.urdf": True, "pkg/dir_link/secret.urdf": True,
             "pkg/dir_link/sub/deep.urdf": True, "pkg/urdf/inner_link.urdf": False}
    cache: dict = {}
    for path, expected in cases.items():
        assert leaves_cwd(path) is expected, path
        assert leaves_cwd(path, cache=cache) is expected, path
    assert leaves_cwd(outside / "secret.urdf") is False  # not written below the working directory at all
