"""The lint cache (cli/cache.py, core/observe.py): a hit replays the run byte for byte, anything the run looked at
that changed is a miss, a corrupt or foreign entry is never used, the checked tree is never written.

Every run here is the real console entry (`python -m urdfcheck`) in a subprocess, with its own cache folder."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
from conftest import CORPUS, REPO

from urdfcheck.cli import cache

AGV = REPO / "examples" / "agv"


def environ(cache_dir, **more) -> dict:
    e = {**os.environ, "PYTHONPATH": str(REPO / "src") + os.pathsep + os.environ.get("PYTHONPATH", ""),
         "URDFCHECK_CACHE_DIR": str(cache_dir), "URDFCHECK_CACHE_TRACE": "1"}
    e.pop("URDFCHECK_NO_CACHE", None)
    e.update(more)
    return e


def cli(args, cwd, cache_dir, *, env=None, timeout=300, flags=(), raw=False):
    proc = subprocess.run([sys.executable, *flags, "-m", "urdfcheck", *map(str, args)], cwd=cwd,
                          env=environ(cache_dir, **(env or {})),
                          capture_output=True, text=True, timeout=timeout)
    lines = proc.stderr.splitlines()
    said = [ln for ln in lines if ln.startswith("urdfcheck: cache ")]
    rest = "".join(ln + "\n" for ln in lines if not ln.startswith("urdfcheck: cache "))
    if not raw:  # what the expansions did is for the tests of `load.reuse`
        said = [ln.split(" (xacro expansions:")[0] for ln in said]
    return proc.returncode, proc.stdout, rest, said


@pytest.fixture
def pkg(tmp_path):
    dst = tmp_path / "agv"
    shutil.copytree(AGV, dst)
    return dst


def entries(folder: Path) -> list[Path]:
    """The stored reports (the expansions are stored beside them, in folders named x<key>: `expansions`)."""
    return sorted(p for p in (folder / f"v{cache.SCHEMA}").glob("*/*.json") if not p.parent.name.startswith("x"))


def expansions(folder: Path) -> list[Path]:
    return sorted(p for p in (folder / f"v{cache.SCHEMA}").glob("x*/*.json"))


def tree(folder: Path) -> dict:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def test_hit_replays_the_run(pkg, tmp_path):
    c = tmp_path / "cache"
    before = tree(pkg)
    first = cli(["lint", "--format", "json", "urdf/agv.urdf.xacro"], pkg, c)
    assert first[3] == ["urdfcheck: cache miss", "urdfcheck: cache stored"]
    second = cli(["lint", "--format", "json", "urdf/agv.urdf.xacro"], pkg, c)
    assert second[3] == ["urdfcheck: cache hit"]
    assert second[:3] == first[:3]
    assert json.loads(second[1])["findings"] == json.loads(first[1])["findings"]
    assert tree(pkg) == before  # nothing written into the checked tree
    assert len(entries(c)) == 1


def test_hit_imports_no_pipeline(pkg, tmp_path):
    c = tmp_path / "cache"
    cli(["lint", "urdf/agv.urdf.xacro"], pkg, c)
    proc = subprocess.run([sys.executable, "-X", "importtime", "-m", "urdfcheck", "lint", "urdf/agv.urdf.xacro"],
                          cwd=pkg, env=environ(c), capture_output=True, text=True, timeout=120)
    assert "urdfcheck: cache hit" in proc.stderr
    imported = [ln.rsplit("|", 1)[-1].strip() for ln in proc.stderr.splitlines() if ln.startswith("import time:")]
    assert "urdfcheck.cli.cache" in imported
    # (`urdfcheck.load` itself is the empty package that is also the API function `urdfcheck.load()`)
    heavy = [m for m in imported if m.startswith(("urdfcheck.run", "urdfcheck.plan", "urdfcheck.load.",
                                                   "urdfcheck.model", "urdfcheck.consumers", "urdfcheck.rules",
                                                   "urdfcheck.finish", "urdfcheck.report", "urdfcheck.request",
                                                   "urdfcheck.cli.main", "urdfcheck.cli.common", "lxml", "yaml",
                                                   "argparse"))]
    assert heavy == []


def test_any_change_the_run_saw_is_a_miss(pkg, tmp_path):
    c = tmp_path / "cache"
    args = ["lint", "--format", "json", "urdf/agv.urdf.xacro"]
    clean = cli(args, pkg, c)
    assert clean[0] == 0
    xacro = pkg / "urdf" / "agv.urdf.xacro"
    text = xacro.read_text()
    xacro.write_text(text.replace('<joint name="left_wheel_joint"', '<joint name="left_wheel_joint2"', 1))
    edited = cli(args, pkg, c)
    assert edited[3][0].startswith("urdfcheck: cache miss (")
    assert edited[1] != clean[1]
    assert edited[:3] == cli(args, pkg, c, env={"URDFCHECK_NO_CACHE": "1"})[:3]
    xacro.write_text(text)  # back as it was: the first entry is valid again (content, not mtime)
    again = cli(args, pkg, c)
    assert again[3] == ["urdfcheck: cache hit"] and again[:3] == clean[:3]
    # zero-config: a new file in a folder that discovery listed is a miss too
    zero = ["lint", "--no-config", "urdf/agv.urdf.xacro"]
    assert cli(zero, pkg, c)[3][-1] == "urdfcheck: cache stored"
    assert cli(zero, pkg, c)[3] == ["urdfcheck: cache hit"]
    (pkg / "launch" / "extra.launch.xml").write_text("<launch/>")
    assert cli(zero, pkg, c)[3][0].startswith("urdfcheck: cache miss (")


def test_settings_are_part_of_the_key(pkg, tmp_path):
    c = tmp_path / "cache"
    cli(["lint", "urdf/agv.urdf.xacro"], pkg, c)
    assert cli(["lint", "--ignore", "G", "urdf/agv.urdf.xacro"], pkg, c)[3][0] == "urdfcheck: cache miss"
    assert cli(["lint", "urdf/agv.urdf.xacro"], pkg, c, env={"ROS_PACKAGE_PATH": "/x"})[3][0] == \
        "urdfcheck: cache miss"
    assert cli(["lint", "urdf/agv.urdf.xacro"], pkg, c)[3] == ["urdfcheck: cache hit"]


@pytest.mark.parametrize("damage", ["garbage", "truncated", "other key", "checksum", "extra field", "bad kind"])
def test_corrupt_or_foreign_entry_is_ignored(pkg, tmp_path, damage):
    c = tmp_path / "cache"
    args = ["lint", "--format", "json", "urdf/agv.urdf.xacro"]
    good = cli(args, pkg, c)
    (path,) = entries(c)
    raw = path.read_text()
    entry = json.loads(raw)
    if damage == "garbage":
        path.write_bytes(b"\x00\xff not json")
    elif damage == "truncated":
        path.write_text(raw[: len(raw) // 2])
    elif damage == "other key":
        entry["key"] = "0" * 32
        entry["sum"] = cache._checksum(entry)
        path.write_text(json.dumps(entry))
    elif damage == "checksum":
        entry["stdout"] = '{"findings": []}'
        path.write_text(json.dumps(entry))
    elif damage == "extra field":
        entry["pickle"] = "x"
        path.write_text(json.dumps(entry))
    else:
        entry["observed"][0][0] = "z"
        entry["sum"] = cache._checksum(entry)
        path.write_text(json.dumps(entry))
    again = cli(args, pkg, c)
    assert again[3] == ["urdfcheck: cache miss", "urdfcheck: cache stored"]
    assert again[:3] == good[:3]
    assert cli(args, pkg, c)[3] == ["urdfcheck: cache hit"]


def test_a_damaged_miss_is_not_read_for_its_expansions(pkg, tmp_path):
    """A miss is told from the first changed file, before its entry is validated; the entry the miss then reads
    (which expansions it made, so whether to fork a xacro worker) must still pass its checksum."""
    c = tmp_path / "cache"
    args = ["lint", "urdf/agv.urdf.xacro"]
    cli(args, pkg, c)
    (path,) = entries(c)
    entry = json.loads(path.read_text())
    assert entry["expansions"] and entry["made"] == len(entry["expansions"])
    entry["made"] = 7  # not refreshing the checksum
    path.write_text(json.dumps(entry))
    params = pkg / "config" / "agv_controllers.yaml"
    params.write_text(params.read_text() + "# tuned\n")
    assert cli(args, pkg, c)[3] == ["urdfcheck: cache miss", "urdfcheck: cache stored"]
    params.write_text(params.read_text() + "# again\n")
    said = cli(args, pkg, c)[3]  # the entry just stored is sound: read for its expansions
    assert said[0].startswith("urdfcheck: cache miss (") and said[0].endswith("no xacro worker"), said


def test_first_change_answers_any_record_without_raising(tmp_path):
    from urdfcheck.core.cachefile import digest
    from urdfcheck.core.observe import MALFORMED, fingerprint, first_change

    a, b = tmp_path / "a.xacro", tmp_path / "b.yaml"
    a.write_text("<robot/>")
    b.write_text("x: 1")
    good = [["m", str(tmp_path), "0:0"], ["r", str(b), fingerprint("r", str(b), digest)],
            ["r", str(a), fingerprint("r", str(a), digest)]]
    assert first_change(good[1:], {}, digest) is None
    assert first_change(good, {}, digest) == str(tmp_path)  # the module's stamp differs: looked at last
    b.write_text("x: 2")
    looks: dict = {}
    assert first_change(good, looks, digest) == str(b)  # a file read before the module stamp
    assert ("m", str(tmp_path)) not in looks  # the installed module was never looked at
    same = [["r", str(b), fingerprint("r", str(b), digest)]]  # unchanged: what follows it is looked at
    for bad in (None, {}, "r", [None], [["r", str(a)]], [[["r"], str(a), "x"]], [["r", "relative", "x"]],
                same + [["z", str(a), "x"]], same + [[1, 2, 3]], same + [["r", str(a), None]]):
        assert first_change(bad, {}, digest) == MALFORMED, bad


def test_the_edited_file_of_a_big_record_is_looked_at_first(tmp_path):
    """A workspace's record reads thousands of files: the miss after one edit must not digest them all first."""
    from urdfcheck.core.cachefile import digest
    from urdfcheck.core.observe import fingerprint, first_change

    files = [tmp_path / f"f{i:03}.yaml" for i in range(200)]
    for i, f in enumerate(files):
        f.write_text(f"x: {i}")
        os.utime(f, ns=(10**18, 10**18 + i))
    record = [["r", str(f), fingerprint("r", str(f), digest)] for f in files]
    files[57].write_text("x: edited")
    os.utime(files[57], ns=(2 * 10**18, 2 * 10**18))
    looks: dict = {}
    assert first_change(record, looks, digest) == str(files[57])
    assert len(looks) == 1
    files[57].unlink()  # a file gone is a change too, and is found as soon
    looks.clear()
    assert first_change(record, looks, digest) == str(files[57]) and len(looks) == 1


def test_no_cache_and_not_stored_runs(pkg, tmp_path):
    c = tmp_path / "cache"
    assert cli(["lint", "--no-cache", "urdf/agv.urdf.xacro"], pkg, c)[3] == []
    assert cli(["lint", "urdf/agv.urdf.xacro"], pkg, c, env={"URDFCHECK_NO_CACHE": "1"})[3] == []
    assert cli(["lint", "--list", "urdf/agv.urdf.xacro"], pkg, c)[3] == []
    assert cli(["lint", "-o", str(tmp_path / "r.txt"), "urdf/agv.urdf.xacro"], pkg, c)[3] == []
    assert not entries(c)
    # a run cut by its time budget (or whose worker crashed or timed out) read an unknown set of files
    code, out, _, said = cli(["lint", "--no-config", "--budget", "0.000001", "urdf/agv.urdf.xacro"], pkg, c)
    assert "X017" in out and said[-1].startswith("urdfcheck: cache not stored"), said
    assert not entries(c)


def test_default_folder_is_the_users_cache(pkg, tmp_path):
    xdg = tmp_path / "xdg"
    env = {"XDG_CACHE_HOME": str(xdg), "HOME": str(tmp_path / "home")}
    e = environ("", **env)
    del e["URDFCHECK_CACHE_DIR"]
    before = tree(pkg)
    for _ in range(2):
        subprocess.run([sys.executable, "-m", "urdfcheck", "lint", "urdf/agv.urdf.xacro"], cwd=pkg, env=e,
                       capture_output=True, timeout=120)
    assert len(entries(xdg / "urdfcheck")) == 1
    assert (xdg / "urdfcheck" / "CACHEDIR.TAG").is_file()
    assert tree(pkg) == before
    assert cache.user_cache_dir().endswith("urdfcheck")


def test_cache_dir_flag_and_config_cannot_set_it(pkg, tmp_path):
    mine = tmp_path / "mine"
    assert cli(["lint", "--cache-dir", mine, "urdf/agv.urdf.xacro"], pkg, tmp_path / "env")[3][-1] == \
        "urdfcheck: cache stored"
    assert len(entries(mine)) == 1 and not entries(tmp_path / "env")
    # a config of the checked tree has no say where the cache goes (every file of a pull request is its author's)
    cfg = pkg / "urdfcheck.yaml"
    cfg.write_text(cfg.read_text() + "\ncache_dir: .\n")
    code, _, err, _ = cli(["lint", "urdf/agv.urdf.xacro"], pkg, tmp_path / "env")
    assert code == 2 and "cache_dir" in err
    assert not list(pkg.rglob("*.json"))
    # ...but it can turn the cache off
    cfg.write_text(cfg.read_text().replace("\ncache_dir: .\n", "\ncache: false\n"))
    said = cli(["lint", "urdf/agv.urdf.xacro"], pkg, tmp_path / "env")[3]
    assert said == ["urdfcheck: cache miss", "urdfcheck: cache not stored (the config says cache: false)"]


def test_parallel_runs_share_an_entry(pkg, tmp_path):
    c = tmp_path / "cache"
    args = ["lint", "--format", "json", "urdf/agv.urdf.xacro"]
    with ThreadPoolExecutor(4) as pool:
        runs = list(pool.map(lambda _: cli(args, pkg, c), range(4)))
    assert len({r[:3] for r in runs}) == 1
    assert len(entries(c)) == 1 and not list((c / f"v{cache.SCHEMA}").glob("*/*.tmp"))
    assert cli(args, pkg, c)[3] == ["urdfcheck: cache hit"]


def test_a_run_that_reuses_expansions_stores_the_same_version(pkg, tmp_path):
    """What the parallel runs race into, in order: the second run finds the first one's expansions (but not its
    report) and must name its report as the first did (reading an entry is no look at the checked tree)."""
    c = tmp_path / "cache"
    args = ["lint", "--format", "json", "urdf/agv.urdf.xacro"]
    cli(args, pkg, c)
    [first] = entries(c)
    first.unlink()
    assert cli(args, pkg, c, raw=True)[3][-1].endswith("(xacro expansions: 2 reused, 0 expanded)")
    assert entries(c) == [first]


def test_prune_keeps_the_folder_bounded(tmp_path):
    folder = tmp_path / "v1"
    for i in range(10):
        p = folder / f"{i % 3:032x}" / f"{i:032x}.json"
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_bytes(b"x" * 1000)
        os.utime(p, ns=(i * 10**9, i * 10**9))
    stale = folder / f"{0:032x}" / ".stale.tmp"
    stale.write_bytes(b"x")
    os.utime(stale, (0, 0))
    cache.prune(str(folder), max_bytes=6000, max_entries=100)
    left = sorted(p.name for p in folder.rglob("*") if p.is_file())
    assert left == [f"{i:032x}.json" for i in range(6, 10)]  # the least recently used went first
    cache.prune(str(folder), max_bytes=10**6, max_entries=2)
    assert [p.name for p in folder.rglob("*.json")] == [f"{9:032x}.json"]
    assert len(list(folder.iterdir())) == 1  # emptied key folders are removed


def test_versions_per_key_are_bounded(pkg, tmp_path):
    c = tmp_path / "cache"
    args = ["lint", "urdf/agv.urdf.xacro"]
    xacro = pkg / "urdf" / "agv.urdf.xacro"
    text = xacro.read_text()
    for i in range(cache.MAX_VERSIONS + 2):
        xacro.write_text(text + f"<!-- edit {i} -->\n")
        assert cli(args, pkg, c)[3][-1] == "urdfcheck: cache stored"
    assert len(entries(c)) == cache.MAX_VERSIONS
    assert cli(args, pkg, c)[3] == ["urdfcheck: cache hit"]


def test_plan_reads_the_command_line():
    assert cache.plan(["expand", "x.xacro"]) is None
    assert cache.plan(["rules"]) is None
    assert cache.plan(["lint", "--write-baseline", "b.json"]) is None
    assert cache.plan(["lint", "--wr", "b.json"]) is None  # argparse's abbreviation
    assert cache.plan(["lint", "--no-cache"]) is None
    assert cache.plan(["lint", "--help"]) is None
    a, b = cache.plan(["lint", "m.urdf"]), cache.plan(["m.urdf"])
    assert a is not None and a.key == b.key  # `urdfcheck m.urdf` is `urdfcheck lint m.urdf`
    assert cache.plan(["lint", "--cache-dir=/tmp/x", "m.urdf"]).folder == os.path.join("/tmp/x", f"v{cache.SCHEMA}")


@pytest.mark.slow
def test_whole_corpus_same_json_with_and_without_cache(tmp_path):
    """The corpus root, zero-config: no cache, then a cold cache (stores), then a hit: the same bytes."""
    if not CORPUS.is_dir():
        pytest.skip("shared corpus not present")
    c = tmp_path / "cache"
    args = ["lint", "--format", "json"]
    plain = cli(args, CORPUS, c, env={"URDFCHECK_NO_CACHE": "1"}, timeout=900)
    cold = cli(args, CORPUS, c, timeout=900)
    warm = cli(args, CORPUS, c, timeout=900)
    assert plain[0] in (0, 1), plain[2]
    assert cold[3][-1] == "urdfcheck: cache stored" and warm[3] == ["urdfcheck: cache hit"]
    assert plain[:3] == cold[:3] == warm[:3]
    assert json.loads(warm[1])["findings"]


@pytest.mark.parametrize("argv, expected", [
    (["lint", "m.urdf.xacro"], (False, (), 20.0)),
    (["m.urdf.xacro", "--trusted", "--allow-env", "HOME", "--timeout=5"], (True, ("HOME",), 5.0)),
    (["lint", "--format", "json", "--arg", "a:=b", "m.urdf.xacro"], (False, (), 20.0)),
    (["lint", "plain.urdf"], None),  # no xacro, no folder: no worker
    (["lint", "--list", "m.urdf.xacro"], None),  # an option it does not know: cli.main decides
    (["lint", "--tim", "5", "m.urdf.xacro"], None),  # an abbreviation
    (["rules"], None),
])
def test_fork_early_reads_the_limits(monkeypatch, argv, expected):
    from urdfcheck.core import worker

    got = []
    monkeypatch.setattr(worker, "keep_spare", lambda key, limits, preload: got.append(limits))
    cache.fork_early(argv)
    if expected is None:
        assert got == []
    else:
        (lim,) = got
        assert (not lim.scrub_env, tuple(lim.env_keep), lim.timeout) == expected


def test_a_parameter_file_parsed_in_the_worker_is_still_part_of_the_key(pkg, tmp_path):
    """Zero config: the package's parameter files are parsed in the xacro worker (consumers.params.parse_ahead),
    where the console's audit hook cannot see the reads: the worker hands back what it read (and the console reads
    the files' suppression comments itself), so an edit is a miss."""
    c = tmp_path / "cache"
    zero = ["lint", "--no-config", "--format", "json", "urdf/agv.urdf.xacro"]
    clean = cli(zero, pkg, c)
    assert clean[3][-1] == "urdfcheck: cache stored" and cli(zero, pkg, c)[3] == ["urdfcheck: cache hit"]
    params = pkg / "config" / "agv_controllers.yaml"
    text = params.read_text()
    assert "wheel_radius" in text
    params.write_text(text.replace("wheel_radius:", "wheel_radius: 0.5\n    old_wheel_radius:", 1))
    edited = cli(zero, pkg, c)
    assert edited[3][0].startswith("urdfcheck: cache miss (")
    assert edited[1] != clean[1]  # the wheel geometry no longer matches the URDF
    assert edited[:3] == cli(zero, pkg, c, env={"URDFCHECK_NO_CACHE": "1"})[:3]


def test_a_miss_looks_at_each_path_once_and_at_the_read_files_first(tmp_path, monkeypatch):
    """Every stored version of a key is tried on a miss; the paths they share are fingerprinted once, and the
    files a run read come first (an edit changes one of them), so the installed modules are never looked at."""
    from urdfcheck.core import observe

    model = tmp_path / "m.urdf"
    model.write_text("<robot name='r'/>")
    spec = cache.Spec(str(tmp_path / "cache" / "v1"), "k" * 32, trace=False)
    os.makedirs(spec.versions)
    modules = [["m", f"/usr/lib/python3/mod{i}.py", "1:2"] for i in range(20)]
    for v in range(cache.MAX_VERSIONS):
        observed = modules + [["r", str(model), f"fold-{v}"]]  # each version saw other bytes of the model
        entry = {"schema": cache.SCHEMA, "key": spec.key, "code": 0, "stdout": "", "stderr": "",
                 "observed": observed, "expansions": [], "made": 0}
        entry["sum"] = cache._checksum(entry)
        (Path(spec.versions) / f"{v}.json").write_text(json.dumps(entry))
    asked = []
    real = observe.fingerprint

    def counting(kind, path, digest):
        asked.append((kind, path))
        return real(kind, path, digest)

    monkeypatch.setattr(observe, "fingerprint", counting)
    assert cache.replay(spec) is None
    assert asked == [("r", str(model))]


def test_a_link_that_points_elsewhere_looks_different(tmp_path):
    """What a link probed with lstat points to decides whether a run may read through it (the checkout boundary):
    a link moved to another target of the same length is a change."""
    from urdfcheck.core import observe

    (tmp_path / "in").mkdir()
    (tmp_path / "ot").mkdir()
    for d in ("in", "ot"):
        (tmp_path / d / "m.xacro").write_text("<robot name='r'/>")
    link = tmp_path / "m.xacro"
    link.symlink_to("in/m.xacro")
    before = observe.fingerprint("q", str(link), cache.digest)
    link.unlink()
    link.symlink_to("ot/m.xacro")
    assert observe.fingerprint("q", str(link), cache.digest) != before
    assert observe.fingerprint("r", str(link), cache.digest) == observe.fingerprint("r", str(tmp_path / "in" /
                                                                                               "m.xacro"), cache.digest)


def test_a_package_of_plain_urdfs_starts_no_xacro_worker(monkeypatch, tmp_path):
    """A folder without a .xacro file (nor a config that could name one elsewhere) forks no spare: its imports
    would be a sixth of the lint's CPU for nothing. One .xacro anywhere below, or a config, and it does."""
    from urdfcheck.core import worker

    got = []
    monkeypatch.setattr(worker, "keep_spare", lambda key, limits, preload: got.append(limits))
    pkg = tmp_path / "bot_description"
    (pkg / "urdf" / "deep").mkdir(parents=True)
    (pkg / "urdf" / "bot.urdf").write_text('<robot name="b"><link name="base_link"/></robot>')
    monkeypatch.chdir(tmp_path)
    cache.fork_early(["lint", "bot_description"])
    assert got == []
    (pkg / "urdf" / "deep" / "part.urdf.xacro").write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>')
    cache.fork_early(["lint", "bot_description"])
    assert len(got) == 1
    (pkg / "urdf" / "deep" / "part.urdf.xacro").unlink()
    (pkg / "urdfcheck.yaml").write_text("models:\n  - path: ../elsewhere/robot.urdf.xacro\n")
    worker.drop_spares()
    cache.fork_early(["lint", "bot_description"])
    assert len(got) == 2
    cache.fork_early(["lint", "--no-config", "bot_description"])  # the config is not read: no xacro
    assert len(got) == 2
