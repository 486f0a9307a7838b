"""Extract the real-history fixtures of tests/diff/test_diff_history.py from local clones of the upstream repositories.

    python tools/history_fixtures.py MIRRORS    # MIRRORS/<owner+name>/repo is a clone holding the commits below

For each commit named below, the files a test needs (models, launch and parameter files, package manifests: no
meshes, images, docs, C++ or tests) are taken at the commit's parent ("old") and at the commit ("new"). They are
stored once per content, named by their upstream git blob id, in tests/fixtures/history/<repo>/files.tar.xz
(the many near-identical versions of a file compress to a tenth of their size), and
<repo>/<commit>.txt lists `old <TAB> blob <TAB> path` for every file of the parent, then `new` for each file the
commit adds or changes and `gone <TAB> - <TAB> path` for each it deletes. Files keep no name of their own in the
fixture tree so that nothing here is a package, a launch file or a Python module to colcon, pytest, ruff or
urdfcheck itself; the test rebuilds the two revisions as a throwaway git repository. Only repositories whose
licence permits redistribution are listed; each keeps its LICENSE and a SOURCES.md naming the upstream repository
and commits.
"""
from __future__ import annotations

import fnmatch
import io
import subprocess
import sys
import tarfile
from pathlib import Path

OUT = Path(__file__).resolve().parents[1] / "tests" / "fixtures" / "history"
SKIP = ("*.stl", "*.STL", "*.dae", "*.obj", "*.png", "*.jpg", "*.gif", "*.pgm", "*.svg", "*.pdf", "*.rviz",
        "*.world", "*.md", "*.rst", "*.cpp", "*.hpp", "*.h", "*.drawio", "*/test/*", "test/*", "*/doc/*",
        "doc/*", "docker/*", ".*")

REPOS = {
    "linorobot2": {
        "mirror": "linorobot+linorobot2", "url": "https://github.com/linorobot/linorobot2", "license": "Apache-2.0",
        "note": "Every package.xml declares `<license>Apache 2.0</license>` from the first commit (65ea1a1, "
                "2021-08-04) on; the LICENSE file at the root came on 2021-09-23 (95063e8), after some of the "
                "commits below.",
        "include": ["*/package.xml", "linorobot2_description/*", "linorobot2_bringup/launch/*",
                    "linorobot2_gazebo/launch/*", "linorobot2_base/config/*"],
        "commits": ["1ac1d5c", "46347df", "b5480cf", "06a0362", "1d4dd82", "a6d9e72", "c25f22e", "84ae70e",
                    "185ad8f", "9e8be8e", "b934e9f", "91ca638", "63fe5ae", "550153d", "e4fef1d", "cecce05", "dcc558b",
                    "0a7eb82"],
    },
    "ros2_control_demos": {
        "mirror": "ros-controls+ros2_control_demos", "url": "https://github.com/ros-controls/ros2_control_demos",
        "license": "Apache-2.0",
        "include": ["*/package.xml"],
        "commits": {
            "8240fa0e": ["example_11/*", "ros2_control_demo_description/carlikebot/*"],
            "7eeeae45": ["example_11/*", "ros2_control_demo_description/carlikebot/*"],
            "618d8e61": ["example_7/*", "ros2_control_demo_description/r6bot/*"],
            "c141f0e5": ["example_2/*", "ros2_control_demo_description/diffbot/*"],
        },
    },
    "Universal_Robots_ROS2_Description": {
        "mirror": "UniversalRobots+Universal_Robots_ROS2_Description",
        "url": "https://github.com/UniversalRobots/Universal_Robots_ROS2_Description", "license": "BSD-3-Clause",
        "include": ["package.xml", "urdf/*", "config/*", "launch/*"],
        "commits": ["42e44a2", "7299dcb", "dcb7db0", "60e6974"],
    },
}


def git(repo: Path, *args: str) -> bytes:
    return subprocess.run(["git", "-C", str(repo), *args], check=True, capture_output=True).stdout


def tree(repo: Path, rev: str, include: list[str]) -> dict[str, str]:
    """path -> blob id of the files a test needs at `rev`."""
    out = {}
    for line in git(repo, "ls-tree", "-r", rev).decode().splitlines():
        meta, path = line.split("\t", 1)
        mode, kind, blob = meta.split()
        if kind != "blob" or mode == "120000":
            continue
        if any(fnmatch.fnmatch(path, p) for p in SKIP) or not any(fnmatch.fnmatch(path, p) for p in include):
            continue
        out[path] = blob
    return out


def main(mirrors: Path) -> None:
    for name, spec in REPOS.items():
        repo = mirrors / spec["mirror"] / "repo"
        dest = OUT / name
        dest.mkdir(parents=True, exist_ok=True)
        blobs: dict[str, bytes] = {}
        commits = spec["commits"]
        rows = []
        for commit in commits:
            include = spec["include"] + (commits[commit] if isinstance(commits, dict) else [])
            full = git(repo, "rev-parse", commit).decode().strip()
            subject = git(repo, "log", "-1", "--format=%ad %s", "--date=short", commit).decode().strip()
            old, new = tree(repo, f"{full}~1", include), tree(repo, full, include)
            lines = [f"old\t{blob}\t{path}\n" for path, blob in sorted(old.items())]
            lines += [f"new\t{blob}\t{path}\n" for path, blob in sorted(new.items()) if old.get(path) != blob]
            lines += [f"gone\t-\t{path}\n" for path in sorted(set(old) - set(new))]
            for blob in {*old.values(), *new.values()} - set(blobs):
                blobs[blob] = git(repo, "cat-file", "blob", blob)
            (dest / f"{commit}.txt").write_text("".join(lines))
            rows.append(f"| {commit} | {full} | {subject.replace('|', '/')} |\n")
        with tarfile.open(dest / "files.tar.xz", "w:xz") as tar:
            for blob in sorted(blobs):  # fixed order, times and owners: the same input gives the same archive
                info = tarfile.TarInfo(blob)
                info.size, info.mode = len(blobs[blob]), 0o644
                tar.addfile(info, io.BytesIO(blobs[blob]))
        lic = git(repo, "show", f"{git(repo, 'rev-parse', 'HEAD').decode().strip()}:LICENSE")
        (dest / "LICENSE").write_bytes(lic)
        (dest / "SOURCES.md").write_text(
            f"# {name}\n\nFiles of {spec['url']} (licence {spec['license']}, copied in LICENSE), unchanged, at the "
            "commits below and their parents, for tests/diff/test_diff_history.py. `files.tar.xz` holds each file "
            "once, named by its upstream git blob id (the test checks each name against the content); `<commit>.txt` "
            "lists the parent's files (`old`, blob, upstream path), then "
            "what the commit adds or changes (`new`) and deletes (`gone`). Made by tools/history_fixtures.py.\n\n"
            + (f"{spec['note']}\n\n" if spec.get("note") else "")
            + "| commit | full id | date and subject |\n| --- | --- | --- |\n" + "".join(rows))


if __name__ == "__main__":
    main(Path(sys.argv[1]))
