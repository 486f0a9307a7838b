"""Attack class (issue 11): guarded functions and bound methods handed to other functions as *values*.

The evaluator guards `str.format`, `ljust`, `join`, `math.factorial`, ... when it calls them itself. Passed as a
value (map, filter, sorted(key=), min/max(key=), nested maps, a property, a dict) C code calls them instead, with
no guard: `'{0.__globals__[os].environ[X]}'.format` walks from any xacro helper closure to the environment or
sys.argv, and `'x'.ljust(10**9)`, `math.factorial(10**7)`, a backtracking `xacro.tokenize` regex exhaust the
worker. Related routes in the same issue: `$(eval)`'s textual `__` check, YAML unit tags echoing evaluated
text, glob includes walking the runner's file system, `xacro.abs_filename()` / `$(dirname)` handing out the
runner's absolute path.

Every payload is a tiny xacro in a throw-away package. The real CLI runs in a *subprocess* (so the worker
inherits a real environment and a real argv) with a secret environment variable and a distinctive argv marker.
Each must: exit 1 with a located finding (file and line of the payload), leak neither secret nor argv marker,
nor the outside file's text, nor the runner's absolute path, and finish within a few seconds.

URDFCHECK_PYTHON selects the interpreter (default: this one), so the same file runs against an older tree.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

PY = os.environ.get("URDFCHECK_PYTHON", sys.executable)
SECRET_VAR = "URDFCHECK_TEST_SECRET"
SECRET = "s3cr3t-env-5b7d1c9e"
ARGV_MARK = "ARGVMARK_4f2a9c"  # passed as an (unused) --allow-env name: lands in sys.argv only
FILE_SECRET = "s3cr3t-file-8e0a3d"
BOUND = float(os.environ.get("URDFCHECK_HOSTILE_CALLABLE_BOUND", "6.0"))
NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'

# templates are properties: a '}' cannot appear inside ${...}
PRELUDE = (
    '  <xacro:property name="T" value="{0.__globals__[os].environ[' + SECRET_VAR + ']}"/>\n'
    '  <xacro:property name="A" value="{0.__globals__[sys].argv}"/>\n'
    '  <xacro:property name="M" value="{arg.__globals__[os].environ[' + SECRET_VAR + ']}"/>\n'
    '  <xacro:property name="G" value="{0.__getattr__.__globals__[os].environ[' + SECRET_VAR + ']}"/>\n'
    '  <xacro:property name="W" value="{:>999999999}"/>\n'
    '  <xacro:property name="WM" value="{a:>999999999}"/>\n'
)
PRELUDE_LINES = PRELUDE.count("\n")
FIRST = 2 + PRELUDE_LINES + 1  # line of the first payload line (after <robot> and <link name="a"/>)

# id -> (payload lines, finding code prefix). The payload's first line is the one the finding must point at.
CASES: dict[str, tuple[str, str]] = {
    # --- secrets through str.format / format_map called by C code -------------------------------
    "map_format_env": ('<link name="${list(map(T.format, [xacro.arg]))[0]}"/>', "X011"),
    "map_format_argv": ('<link name="${list(map(A.format, [xacro.arg]))[0]}"/>', "X011"),
    "python_map_format_env": ('<link name="${list(python.map(T.format, [xacro.message]))[0]}"/>', "X011"),
    "map_format_load_yaml_closure": ('<link name="${list(map(T.format, [xacro.load_yaml]))[0]}"/>', "X011"),
    "map_format_tokenize": ('<link name="${list(map(A.format, [xacro.tokenize]))[0]}"/>', "X011"),
    "map_format_fatal": ('<link name="${list(map(T.format, [xacro.fatal]))[0]}"/>', "X011"),
    "map_format_deprecated_wrapper": ('<link name="${list(map(T.format, [sorted]))[0]}"/>', "X011"),
    "map_format_dotify_class": ('<link name="${list(map(G.format, [xacro.dotify]))[0]}"/>', "X011"),
    "map_format_map_namespace": ('<link name="${list(map(M.format_map, [xacro]))[0]}"/>', "X011"),
    "sorted_key_format": ('<link name="${sorted([xacro.arg], key=T.format)}"/>', "X011"),
    "python_sorted_key_format": ('<link name="${python.sorted([xacro.arg], key=A.format)}"/>', "X011"),
    "min_key_format": ('<link name="${min([xacro.arg, xacro.fatal], key=T.format)}"/>', "X011"),
    "max_key_format": ('<link name="${max([xacro.arg], key=A.format)}"/>', "X011"),
    "filter_format": ('<link name="x${len(list(python.filter(T.format, [xacro.arg])))}"/>', "X011"),
    "join_over_map": ('<link name="${\'\'.join(map(T.format, [xacro.arg]))}"/>', "X011"),
    "tuple_over_map": ('<link name="${python.tuple(map(A.format, [xacro.arg]))[0]}"/>', "X011"),
    "nested_map": ('<link name="${list(list(map(python.map, [T.format], [[xacro.arg]]))[0])[0]}"/>', "X011"),
    "nested_map_twice": ('<link name="${list(list(list(map(python.map, [python.map], [[T.format]], '
                         '[[[xacro.arg]]]))[0])[0])[0]}"/>', "X011"),
    "property_holds_method": ('<xacro:property name="f" value="${T.format}"/>\n'
                              '  <link name="${list(map(f, [xacro.arg]))[0]}"/>', "X011"),
    "dict_holds_method": ('<link name="${list(map(dict(f=T.format)[\'f\'], [xacro.arg]))[0]}"/>', "X011"),
    "list_holds_method": ('<link name="${list(map([A.format][0], [xacro.arg]))[0]}"/>', "X011"),
    "comprehension_over_map": ('<link name="${[s for s in map(T.format, [xacro.arg])][0]}"/>', "X011"),
    "enumerate_over_map": ('<link name="${list(python.enumerate(map(T.format, [xacro.arg])))[0][1]}"/>', "X011"),
    "namespace_type_via_map": ('<link name="${list(list(map(python.map, [python.type], [[1]]))[0])}"/>', "X011"),
    "namespace_vars_via_map": ('<link name="${list(list(map(python.map, [python.vars], [[xacro]]))[0])}"/>', "X011"),
    "namespace_values_type": ('<link name="${[list(map(f, [1])) for f in python.values() if f is python.type]}"/>',
                              "X011"),
    "namespace_get_type": ('<link name="${list(map(python.get(\'vars\'), [xacro]))}"/>', "X011"),
    # --- $(eval): the same evaluator; a textual '__' check is no check ---------------------------
    # ($(...) ends at the first ')': the expression comes from a property, as in test_eval_smuggled_paren)
    "eval_split_underscores_env": ('<xacro:property name="E" value="list(map((\'{0._\' \'_globals_\' \'_[os].environ['
                                   + SECRET_VAR + ']}\').format, [dirname]))[0]"/>\n  <link name="$(eval ${E})"/>',
                                   "X011"),
    "eval_split_underscores_argv": ('<xacro:property name="E" value="list(map((\'{0._\' \'_globals_\' \'_[sys].argv}\')'
                                    '.format, [arg]))[0]"/>\n  <link name="$(eval ${E})"/>', "X011"),
    "eval_min_key": ('<xacro:property name="E" value="str(min([arg], key=(\'{0._\' \'_globals_\' \'_[sys].argv}\')'
                     '.format))"/>\n  <link name="$(eval ${E})"/>', "X011"),
    "eval_map_factorial": ('<xacro:property name="E" value="str(list(map(factorial, [10**7]))[0] % 7)"/>\n'
                           '  <link name="$(eval ${E})"/>', "X011"),
    # --- resource guards skipped by C callers ------------------------------------------------------
    "map_ljust": ('<link name="x${len(list(map(\'x\'.ljust, [10**9]))[0])}"/>', "X011"),
    "map_center": ('<link name="x${len(list(map(\'x\'.center, [10**9]))[0])}"/>', "X011"),
    "map_zfill": ('<link name="x${len(list(map(\'1\'.zfill, [10**9]))[0])}"/>', "X011"),
    "map_format_width": ('<link name="x${len(list(map(W.format, [1]))[0])}"/>', "X011"),
    "map_format_map_width": ('<link name="x${len(list(map(WM.format_map, [dict(a=1)]))[0])}"/>', "X011"),
    "map_join": ('<link name="x${len(list(map((\'x\'*10000).join, [[\'y\'*1000]*100000]))[0])}"/>', "X011"),
    "map_replace": ('<link name="x${len(list(map((\'a\'*100000).replace, [\'a\'], [\'b\'*100000]))[0])}"/>', "X011"),
    "map_expandtabs": ('<link name="x${len(list(map((\'\\t\'*100000).expandtabs, [100000]))[0])}"/>', "X011"),
    "map_factorial": ('<link name="x${len(str(list(map(math.factorial, [10**7]))[0]))}"/>', "X011"),
    "map_top_factorial": ('<link name="x${list(map(factorial, [5*10**6]))[0] % 7}"/>', "X011"),
    "map_comb": ('<link name="x${list(map(math.comb, [10**7], [5*10**6]))[0] % 7}"/>', "X011"),
    "map_perm": ('<link name="x${list(map(math.perm, [3*10**6], [3*10**6]))[0] % 7}"/>', "X011"),
    "map_round_power": ('<link name="x${list(map(round, [1], [-10**8]))[0]}"/>', "X011"),
    "map_sum_quadratic": ('<link name="x${len(list(map(python.sum, [[[0]*10000]*3000], [[]]))[0])}"/>', "X011"),
    "sorted_key_factorial": ('<link name="x${sorted([10**7, 10**7 + 1], key=math.factorial)[0]}"/>', "X011"),
    "min_key_factorial": ('<link name="x${min([5*10**6, 6*10**6], key=factorial)}"/>', "X011"),
    "filter_factorial": ('<link name="x${len(list(python.filter(math.factorial, [10**7])))}"/>', "X011"),
    "map_tokenize_backtracking": ('<link name="x${len(list(map(xacro.tokenize, [\'a\'*40 + \'!\'], '
                                  '[\',]|(a|aa)+$|[,\']))[0])}"/>', "X011"),
    "map_list_of_range": ('<link name="x${len(list(map(list, map(range, [10**8])))[0])}"/>', "X011"),
    "map_sorted_of_range": ('<link name="x${len(list(map(python.sorted, map(python.range, [10**8])))[0])}"/>', "X011"),
    "map_frozenset_of_range": ('<link name="x${len(list(map(python.frozenset, map(python.range, [10**8])))[0])}"/>',
                               "X011"),
    "property_holds_ljust": ('<xacro:property name="pad" value="${\'x\'.ljust}"/>\n'
                             '  <link name="x${len(list(map(pad, [10**9]))[0])}"/>', "X011"),
    "nested_map_center": ('<link name="x${len(list(list(map(python.map, [\'x\'.center], [[10**9]]))[0])[0])}"/>',
                          "X011"),
    # --- files outside the package / the runner's paths ----------------------------------------------
    "map_load_yaml_outside": ('<link name="${list(map(xacro.load_yaml, [\'../../../outside/secret.yaml\']))[0].x}"/>',
                              "X014"),
    "glob_include_outside": ('<xacro:include filename="../../../outside/*.xacro"/>', "X014"),
    "glob_include_root": ('<xacro:include filename="/*/*/*.xacro"/>', "X014"),
    "glob_include_dotdot_after_star": ('<xacro:include filename="../*/../../../outside/secret.xacro"/>', "X014"),
}

# payloads whose success shows the runner's absolute path: a finding is not required, but no path may leak
PATH_CASES = {
    "abs_filename": '<link name="${xacro.abs_filename(\'x.yaml\')}"/>',
    "map_abs_filename": '<link name="${list(map(xacro.abs_filename, [\'x.yaml\']))[0]}"/>',
    "dirname": '<link name="$(dirname)"/>',
    "eval_dirname": '<link name="$(eval dirname())"/>',
}

# YAML unit tags evaluate their scalar: (yaml line, finding code)
YAML_CASES = {
    "degrees_map_format_env": ('angle: !degrees "list(map(\'{0.__globals__[os].environ[' + SECRET_VAR
                               + ']}\'.format, [xacro.arg]))[0]"', "X011"),
    "radians_map_format_argv": ('angle: !radians "list(map(\'{0.__globals__[sys].argv}\'.format, [xacro.arg]))[0]"',
                                "X011"),
    "degrees_string_echo": ('angle: !degrees "str(xacro.arg)"', "X0"),
    "meters_ljust": ('angle: !meters "len(list(map(\'x\'.ljust, [10**9]))[0])"', "X011"),
}


def _package(tmp_path: Path) -> Path:
    pkg = tmp_path / "ws" / "victim_description"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "config").mkdir()
    (pkg / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="3"><name>victim_description</name><version>0.0.0</version>'
        '<description>d</description><maintainer email="a@b.c">a</maintainer><license>BSD</license></package>\n')
    out = tmp_path / "outside"
    out.mkdir()
    (out / "secret.yaml").write_text(f"x: {FILE_SECRET}\n")
    (out / "secret.xacro").write_text(f'<robot {NS}><link name="{FILE_SECRET}"/></robot>\n')
    return pkg


def _lint(tmp_path: Path, rel: str, fmt: str = "json"):
    env = {k: v for k, v in os.environ.items() if not k.startswith(("URDFCHECK_", "PYTEST", "COV_"))}
    env[SECRET_VAR] = SECRET
    args = [PY, "-m", "urdfcheck", "lint", "--no-config", "--format", fmt, "--color", "never",
            "--allow-env", ARGV_MARK, rel]
    t0 = time.monotonic()
    p = subprocess.run(args, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
    return p.returncode, p.stdout, p.stderr, time.monotonic() - t0


def _assert_clean(tmp_path: Path, code, out, err, seconds, where):
    text = out + err
    for secret in (SECRET, ARGV_MARK, FILE_SECRET, str(tmp_path)):
        assert secret not in text, f"{where}: leaked {secret!r}:\n{text[:2000]}"
    assert "Traceback" not in err and "internal error" not in err, f"{where}: {err[:2000]}"
    assert seconds <= BOUND, f"{where}: took {seconds:.1f} s (bound {BOUND} s)"


def _model(pkg: Path, body: str) -> Path:
    p = pkg / "urdf" / "p.urdf.xacro"
    p.write_text(f'<robot name="v" {NS}>\n  <link name="a"/>\n{PRELUDE}  {body}\n</robot>\n')
    return p


@pytest.mark.parametrize("name", sorted(CASES))
def test_callable_as_value_is_refused(tmp_path, name):
    body, want = CASES[name]
    pkg = _package(tmp_path)
    _model(pkg, body)
    code, out, err, seconds = _lint(tmp_path, "ws/victim_description/urdf/p.urdf.xacro")
    _assert_clean(tmp_path, code, out, err, seconds, name)
    assert code == 1, f"{name}: exit {code}\n{out[:2000]}{err[:2000]}"
    findings = json.loads(out)["findings"]
    hits = [f for f in findings if f["code"].startswith(want) and f["location"]["file"].endswith("p.urdf.xacro")
            and f["location"]["line"] == FIRST + body.count("\n")]
    assert hits, f"{name}: no {want} at line {FIRST + body.count(chr(10))}: " + json.dumps(
        [(f["code"], f["location"], f["message"][:200]) for f in findings], indent=1)


@pytest.mark.parametrize("name", sorted(PATH_CASES))
def test_no_xacro_function_hands_out_the_runners_path(tmp_path, name):
    pkg = _package(tmp_path)
    _model(pkg, PATH_CASES[name])
    for fmt in ("json", "text"):
        code, out, err, seconds = _lint(tmp_path, "ws/victim_description/urdf/p.urdf.xacro", fmt)
        _assert_clean(tmp_path, code, out, err, seconds, name)
        assert code in (0, 1), (name, code, err)


@pytest.mark.parametrize("name", sorted(YAML_CASES))
def test_unit_tags_evaluate_through_the_guards_and_echo_nothing(tmp_path, name):
    line, want = YAML_CASES[name]
    pkg = _package(tmp_path)
    (pkg / "config" / "u.yaml").write_text(f"# unit tag\n{line}\n")
    _model(pkg, '<link name="l${xacro.load_yaml(\'../config/u.yaml\').angle}"/>')
    code, out, err, seconds = _lint(tmp_path, "ws/victim_description/urdf/p.urdf.xacro")
    _assert_clean(tmp_path, code, out, err, seconds, name)
    assert code == 1, (name, out, err)
    findings = json.loads(out)["findings"]
    hits = [f for f in findings if f["code"].startswith(want) and f["location"]["file"].endswith("u.yaml")
            and f["location"]["line"] == 2]
    assert hits, f"{name}: " + json.dumps([(f["code"], f["location"], f["message"][:200]) for f in findings])


def test_payload_count():
    assert len(CASES) + len(PATH_CASES) + len(YAML_CASES) >= 40
