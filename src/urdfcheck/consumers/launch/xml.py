"""Launch files, read statically (never imported, never executed) for the TF-relevant nodes they start.

Formats: ROS 1 XML (`.launch`), ROS 2 XML (`.launch.xml`), ROS 2 YAML (`.launch.yaml`/`.launch.yml`) and
ROS 2 Python (`.launch.py`, parsed with `ast`; only literal values are used).

What is reported (`LaunchInfo`):

* `static_tfs`: `static_transform_publisher` nodes (`tf` or `tf2_ros`) as `StaticTF(parent, child, xyz, rpy, ...)`.
  Argument forms: ROS 1 `x y z yaw pitch roll parent child [period]` and `x y z qx qy qz qw parent child
  [period]` (`tf` takes the period, `tf2_ros` does not); ROS 2 positional (the same two without period) and
  the flag form `--x --y --z --roll --pitch --yaw --qx --qy --qz --qw --frame-id --child-frame-id`.
  Note the ROS positional order is yaw pitch roll; `rpy` in the result is (roll, pitch, yaw).
* `state_publishers`: robot_state_publisher nodes with their literal `frame_prefix` (ROS 2) / `tf_prefix` (ROS 1).
* `joint_state_publishers`: joint_state_publisher(_gui) nodes (a joint state source for every joint).
* `nodes`: every node found, `spawned` controllers (controller_manager spawner arguments), `param_files`,
  `includes` (followed by `consumers` for configured launch files) and `notes` for what was skipped (non-literal
  values, unknown substitutions, conditions that could not be decided).
* ROS 1 XML only, outside `<node>`: `param_sets`, the parameter server writes in document order, each either a
  literal `ParamSet` (`<param name=... value=...>`, inline `<rosparam>` YAML, names resolved against the
  enclosing `<group ns>`) or a `RosparamLoad` (`<rosparam command="load" file=... ns=...>`, read later by
  `launchparams`). They are applied to the controllers' parameters (see `launchparams.apply_launch_params`).

Substitutions resolved: `$(arg x)` / `$(var x)` from `<arg default|value>` / `<let>` and the caller's `args`,
`$(find pkg)` / `$(find-pkg-share pkg)` from the caller's `packages` map, `$(dirname)`, `$(anon n)`.
Anything else (`$(env)`, `$(eval)`, `$(command)`, ...) leaves the value unresolved: the item is skipped
with a note. A node with an `if`/`unless` that cannot be decided is kept with `condition` set.
"""
from __future__ import annotations

import math
import os
import re
import shlex
from collections.abc import Mapping

from urdfcheck.consumers.common import ConsumerError, Value, as_bool
from urdfcheck.consumers.launch.info import (  # noqa: F401 - the records are part of this module's interface
    _CMD_END,
    _CMD_START,
    _CMD_UNKNOWN,
    _DESCRIPTION_KEY,
    UNKNOWN,
    Declared,
    Include,
    JointStatePublisher,
    LaunchInfo,
    LaunchNode,
    ModelRef,
    ParamSet,
    RosparamLoad,
    StatePublisher,
    StaticTF,
    description_of,
    parse_static_tf_args,
    record_node,
)
from urdfcheck.core import lazyre, xmlfront
from urdfcheck.core.findings import Location
from urdfcheck.core.lxmlimport import etree
from urdfcheck.core.records import TYPE_CHECKING

if TYPE_CHECKING:
    import ast

    from urdfcheck.consumers.yamlsrc import YamlDoc

MAX_BYTES = 2 * 1024 * 1024


def parse_yaml(text, file: str) -> YamlDoc:
    """consumers.yamlsrc.parse_yaml, imported when a launch file holds YAML: PyYAML costs 10 ms to import."""
    from urdfcheck.consumers.yamlsrc import parse_yaml as parse

    return parse(text, file)
MAX_ELEMENTS = 100_000
MAX_VALUE = 64 * 1024  # characters of one substituted value: `<let>`s doubling each other stop here (issue 19)


# --- substitutions -----------------------------------------------------------------------------------
_SUBST = lazyre.compile(r"\$\(\s*([A-Za-z][\w-]*)((?:\s+[^()$]*)?)\)")


class _Subst:
    def __init__(self, path: str, args: Mapping[str, str] | None, packages: Mapping[str, str] | None):
        self.path = path
        self.overrides = dict(args or {})
        self.vars: dict[str, str | None] = {}  # None: declared, value unknown
        self.packages = dict(packages or {})

    def declare(self, name: str, default: str | None) -> None:
        """<arg name default=...>: the caller's value wins (None: unknown)."""
        if name in self.overrides:
            v = self.overrides[name]
            self.vars[name] = None if v is None else str(v)  # None: passed, but not literal
        else:
            self.vars[name] = default

    def fix(self, name: str, value: str | None) -> None:
        """<arg name value=...> / <let>: not overridable (None: not literal, unknown)."""
        self.vars[name] = value

    def __call__(self, text: str | None) -> tuple[str | None, bool]:
        """(substituted text, fully resolved?)"""
        if text is None:
            return None, True
        t = text.strip()
        if t.startswith("$(eval ") and t.endswith(")"):  # roslaunch: $(eval ...) is the whole attribute
            got = self._eval(t[7:-1])
            return (got, True) if got is not None else (text, False)
        ok = True
        for _ in range(32):  # innermost first; bounded
            m = _SUBST.search(text)
            if not m:
                break
            kind, arg = m.group(1), m.group(2).strip()
            rep = self._one(kind, arg)
            if rep is None:
                ok = False
                rep = "\x00" + kind + "\x00"  # mark, so the loop ends; restored below
            if len(text) - (m.end() - m.start()) + len(rep) > MAX_VALUE:
                return None, False  # unknown, not built
            text = text[: m.start()] + rep + text[m.end():]
        if "\x00" in text:
            text = re.sub(r"\x00([\w-]+)\x00", r"$(\1 ?)", text)
        if "$(" in text:
            ok = False
        return text, ok

    def _eval(self, expr: str) -> str | None:
        """`$(eval ...)` when it only joins strings and numbers with `+` from literals, `arg('x')` (or the
        argument's bare name), `find('pkg')` and `dirname()`; evaluated by consumers.launch.expr, never by
        Python. None otherwise (decided at launch time)."""
        from urdfcheck.consumers.launch import expr as launch_expr

        def name(arg: str):
            v = self._one("arg", arg)
            if v is None:
                return None
            # roslaunch reads a bare argument name with its type guessed ('true' is True), so that
            # `$(eval simulation_mode and not gazebo)` is a boolean (ned_ros picks its model this way)
            return {"true": True, "false": False}.get(v.strip().lower(), v)

        def call(func: str, args: list):
            if func in ("arg", "find") and len(args) == 1 and isinstance(args[0], str):
                return self._one(func, args[0])
            if func == "dirname" and not args:
                return self._one("dirname", "")
            return None

        v = launch_expr.evaluate(expr, name=name, call=call, typed=True)
        if v is None:
            return None
        return v if isinstance(v, str) else str(v)

    def _own_package(self, name: str) -> str | None:
        """A launch file names its own package (`$(find-pkg-share my_robot)`) without a package map."""
        if not hasattr(self, "_own"):
            self._own = _own(self.path)
        return self._own[1] if self._own[0] == name else None

    def _one(self, kind: str, arg: str) -> str | None:
        if kind in ("arg", "var"):
            v = self.vars.get(arg)
            if v is None and self.overrides.get(arg) is not None:
                v = str(self.overrides[arg])
            return v
        if kind in ("find", "find-pkg-share", "find-pkg-prefix"):
            got = self.packages.get(arg) or self._own_package(arg)
            if got is None and arg == "xacro":  # `$(find-pkg-prefix xacro)/bin/xacro`, `$(find xacro)/xacro`: the
                return "xacro-package"  # xacro executable, whose name is all a model reader needs
            return got
        if kind == "dirname":
            return os.path.dirname(os.path.abspath(self.path))
        if kind == "filename":
            return os.path.abspath(self.path)
        if kind == "anon":
            return f"{arg}_anon"
        if kind == "find-exec" and arg == "xacro":  # the xacro executable: its name is all a model reader needs
            return "xacro"
        if kind == "command":  # kept as a marked command line: robot_state_publisher's model is read from it
            return _CMD_START + re.sub(r"\x00[\w-]+\x00", _CMD_UNKNOWN, arg) + _CMD_END
        return None  # env, optenv, eval, command, exec-in-pkg, ...: never evaluated


def _own(path: str) -> tuple[str | None, str | None]:
    from urdfcheck.load.packages import own_package

    name, folder = own_package(path)
    return name, (str(folder) if folder is not None else None)


def _condition(subst: _Subst, if_text: str | None, unless_text: str | None) -> tuple[bool, str | None]:
    """(active?, undecided condition text). Inactive nodes are dropped."""
    for text, want in ((if_text, True), (unless_text, False)):
        if text is None:
            continue
        val, ok = subst(text)
        b = as_bool(val) if ok else None
        if b is None:
            return True, f"{'if' if want else 'unless'}={text}"
        if b != want:
            return False, None
    return True, None


def _split_args(text: str) -> list[str] | None:
    try:
        return shlex.split(text)
    except ValueError:
        return None


# --- XML (ROS 1 and ROS 2) ---------------------------------------------------------------------------
def _xml_root(data: bytes, path: str):
    if b"<!DOCTYPE" in data[:4096].upper() or b"<!ENTITY" in data.upper():
        raise ConsumerError("launch file has a DOCTYPE or entity declaration; refused", Location(path, 1))
    try:
        root = etree.fromstring(data, xmlfront.parser(comments=False))
    except etree.XMLSyntaxError as e:
        line = e.position[0] if getattr(e, "position", None) else None
        col = e.position[1] + 1 if getattr(e, "position", None) else None
        raise ConsumerError(f"XML syntax error: {e.msg}", Location(path, line, col)) from None
    n = 0
    for _ in root.iter():
        n += 1
        if n > MAX_ELEMENTS:
            raise ConsumerError(f"launch file has more than {MAX_ELEMENTS} elements; refused", Location(path))
    return root


def _tag(el) -> str:
    t = el.tag
    return t if isinstance(t, str) else ""


class _XmlReader:
    def __init__(self, path: str, root, args, packages):
        self.path = path
        self.root = root
        self.subst = _Subst(path, args, packages)
        ros2 = root.xpath("boolean(.//*[@exec] | .//let | .//push-ros-namespace | .//push_ros_namespace)")
        self.ros = 2 if ros2 or "$(var " in etree.tostring(root, encoding="unicode") else 1
        self.info = LaunchInfo(path, "ros2-xml" if self.ros == 2 else "ros1-xml")
        self.descriptions: dict = {}  # global parameter name -> ModelRef (ROS 1 <param command=...>)
        self.info.descriptions = self.descriptions

    def loc(self, el) -> Location:
        return Location(self.path, el.sourceline)

    def attr(self, el, name: str) -> tuple[str | None, bool]:
        return self.subst(el.get(name))

    def _desc_value(self, el):
        """<param name="robot_description" command="xacro ..."/> or textfile="..." -> ModelRef (or None)."""
        for attr, how in (("command", "xacro"), ("textfile", "file")):
            raw = el.get(attr)
            if raw is None:
                continue
            v, _ = self.subst(raw)
            text = re.sub(r"\$\([\w-]+ \?\)", UNKNOWN, v or "")
            if how == "xacro":
                return description_of(_CMD_START + text + _CMD_END, self.loc(el))
            return ModelRef(text.strip(), (), "file", self.loc(el))
        return None

    def run(self) -> LaunchInfo:
        if _tag(self.root) != "launch":
            raise ConsumerError(f"root element is <{_tag(self.root)}>, not <launch>", self.loc(self.root))
        self.walk(self.root, "", None)
        return self.info

    def walk(self, parent, ns: str, cond: str | None) -> None:
        for el in parent:
            tag = _tag(el)
            if not tag:
                continue
            active, c = _condition(self.subst, el.get("if"), el.get("unless"))
            if not active:
                continue
            c = c or cond
            if tag == "arg":
                name = el.get("name")
                if name:
                    if el.get("value") is not None:
                        v, ok = self.attr(el, "value")
                        self.subst.fix(name, v if ok else None)
                    else:
                        d, ok = self.attr(el, "default")
                        self.subst.declare(name, d if ok else None)
                        choices = tuple(c.get("value") for c in el if _tag(c) == "choice" and c.get("value"))
                        self.info.declared.setdefault(name, _declared(d if ok else None, choices, self.loc(el)))
            elif tag == "let":
                name = el.get("name")
                v, ok = self.attr(el, "value")
                if name:
                    self.subst.fix(name, v if ok else None)
            elif tag == "group":
                gns = el.get("ns") or el.get("namespace")
                sub_ns = ns
                if gns:
                    v, ok = self.subst(gns)
                    sub_ns = _join_ns(ns, v if ok else "?")
                self.walk(el, sub_ns, c)
            elif tag in ("push-ros-namespace", "push_ros_namespace"):
                v, ok = self.attr(el, "namespace")
                ns = _join_ns(ns, v if ok else "?")
            elif tag == "include":
                f, ok = self.attr(el, "file")
                # ROS 2 includes see the including file's configurations; ROS 1 only what they are passed
                passed = dict(self.subst.vars) if self.ros == 2 or as_bool(el.get("pass_all_args")) else {}
                for a in el:
                    if _tag(a) == "arg" and a.get("name"):
                        # <arg name="x" default="..."/> in an include passes its default like a value
                        v, aok = self.attr(a, "value" if a.get("value") is not None else "default")
                        passed[a.get("name")] = v if aok else None
                ins = ns
                if el.get("ns"):  # ROS 1: <include ns="...">
                    v, nok = self.subst(el.get("ns"))
                    ins = _join_ns(ns, v if nok else "?")
                self.info.includes.append(Include(f if ok else None, self.loc(el), passed, c,
                                                  *(_outside(el.get("file")) if not ok else (None, "")),
                                                  namespace=ins.strip("/")))
            elif tag == "rosparam":
                if (el.get("command") or "load") == "load" and el.get("file"):
                    f, ok = self.attr(el, "file")
                    if ok:
                        self.info.param_files.append((f, self.loc(el)))
                        if self.ros == 1 and not c:
                            rns = self._param_ns(el, ns)
                            if rns is not None:
                                subst = as_bool(el.get("subst_value")) is True
                                known = tuple(sorted((k, v) for k, v in self.subst.vars.items() if v is not None))
                                self._set(RosparamLoad(f, rns, self.loc(el), len(self.info.param_sets),
                                                       known if subst else None))
                    else:
                        self.info.notes.append((f"rosparam file {el.get('file')!r} not resolved", self.loc(el)))
                elif self.ros == 1 and not c and (el.get("command") or "load") == "load" and (el.text or "").strip():
                    self._inline_rosparam(el, ns)
            elif tag == "param" and el.get("value") is None and (el.get("command") or el.get("textfile")):
                d = self._desc_value(el)
                name, ok = self.subst(el.get("name"))
                if d is not None and ok and name:
                    self.descriptions[_join_ns(ns, name)] = d
            elif tag == "param" and self.ros == 1 and not c:
                self._param(el, ns)
            elif tag == "node":
                self.node(el, ns, c)

    # ROS 1 parameter server writes (outside nodes) ------------------------------------------------
    def _set(self, item) -> None:
        self.info.param_sets.append(item)

    def _param_ns(self, el, ns: str) -> str | None:
        """The global namespace a <rosparam>/<param> writes into (None: not literal, noted)."""
        raw = el.get("ns")
        if raw is None:
            return _join_ns(ns, "")
        v, ok = self.subst(raw)
        if not ok:
            self.info.notes.append((f"<{_tag(el)}> ns {raw!r} is not literal; its parameters are not applied",
                                    self.loc(el)))
            return None
        return _join_ns(ns, v)

    def _param(self, el, ns: str) -> None:
        raw_name = el.get("name")
        if not raw_name:
            return
        name, ok = self.subst(raw_name)
        if not ok or not name or name.startswith("~"):
            return
        if el.get("value") is None:  # command= / textfile= / binfile=: produced at launch time
            self.info.notes.append((f"parameter {name!r} is not a literal value (command/textfile); not applied",
                                    self.loc(el)))
            return
        text, ok = self.attr(el, "value")
        if not ok:
            self.info.notes.append((f"parameter {name!r} has a non-literal value; not applied", self.loc(el)))
            return
        value = _typed_param(text, (el.get("type") or "").strip(), self.path, self.loc(el))
        if value is _NOT_A_VALUE:
            self.info.notes.append((f"parameter {name!r}: type={el.get('type')!r} value not understood; not applied",
                                    self.loc(el)))
            return
        full = _join_ns(ns, name) if not name.startswith("/") else "/" + name.strip("/")
        self._set(ParamSet(full, Value(value, self.loc(el)), len(self.info.param_sets)))

    def _inline_rosparam(self, el, ns: str) -> None:
        """<rosparam ns=... param=...>YAML</rosparam>: the YAML body, located in the launch file."""
        base = self._param_ns(el, ns)
        if base is None:
            return
        param = el.get("param")
        if param is not None:
            p, ok = self.subst(param)
            if not ok or not p or p.startswith("~"):
                return
            base = "/" + p.strip("/") if p.startswith("/") else _join_ns(base, p)
        try:
            doc = parse_yaml(el.text, self.path)
        except ConsumerError as e:
            self.info.notes.append((f"inline <rosparam> YAML not readable ({e.message}); not applied", self.loc(el)))
            return
        first = el.sourceline or 1

        def shift(loc: Location) -> Location:  # lines of the element's text -> lines of the launch file
            return Location(self.path, first + (loc.line or 1) - 1) if loc.line else Location(self.path, first)

        def emit(value, path: tuple, name: str) -> None:
            if isinstance(value, dict) and value:
                for k, v in value.items():
                    emit(v, path + (k,), f"{name}/{k}")
                return
            if name:
                self._set(ParamSet(name, Value(value, shift(doc.loc(*path))), len(self.info.param_sets)))

        data = doc.data
        if isinstance(data, dict):
            emit(data, (), base.rstrip("/"))
        elif param is not None and data is not None:
            self._set(ParamSet(base, Value(data, shift(doc.loc())), len(self.info.param_sets)))

    def _node_rosparam(self, el) -> dict[str, Value]:
        """A node's inline `<rosparam>` YAML as its private parameters (dotted names), located in the launch file;
        with `subst_value="true"` the `$(arg ...)` in its values are substituted (a value left unresolved is
        dropped)."""
        try:
            doc = parse_yaml(el.text, self.path)
        except ConsumerError as e:
            self.info.notes.append((f"inline <rosparam> YAML not readable ({e.message}); not applied", self.loc(el)))
            return {}
        first = el.sourceline or 1
        subst = as_bool(el.get("subst_value")) is True
        prefix = (el.get("param") or "").strip("~/").replace("/", ".")
        out: dict[str, Value] = {}

        def emit(value, path: tuple) -> None:
            if isinstance(value, dict) and value:
                for k, v in value.items():
                    emit(v, path + (k,))
                return
            name = ".".join(str(x) for x in ((prefix,) if prefix else ()) + path)
            if not name:
                return
            if subst and isinstance(value, str) and "$(" in value:
                value, ok = self.subst(value)
                if not ok:
                    return
            loc = doc.loc(*path)
            out[name] = Value(value, Location(self.path, first + (loc.line or 1) - 1))

        emit(doc.data, ())
        return out

    def node(self, el, ns: str, cond: str | None) -> None:
        pkg, _ = self.attr(el, "pkg")
        exe, _ = self.subst(el.get("exec") or el.get("type") or el.get("executable"))
        name, _ = self.attr(el, "name")
        nns = el.get("ns") or el.get("namespace")
        if nns:
            v, ok = self.subst(nns)
            ns = _join_ns(ns, v if ok else "?")
        args = None
        if el.get("args") is not None:
            text, ok = self.attr(el, "args")
            args = _split_args(text) if ok else None  # record_node notes it where it matters
        else:
            args = ()
        params: dict[str, Value] = {}
        pfiles: list[str] = []
        for ch in el:
            t = _tag(ch)
            if t == "param":
                if ch.get("from") is not None:
                    f, ok = self.attr(ch, "from")
                    if ok:
                        pfiles.append(f)
                    continue
                pname = ch.get("name")
                if not pname:
                    continue
                raw = ch.get("value")
                if raw is None:
                    desc = self._desc_value(ch) if pname == "robot_description" else None
                    params[pname] = Value(desc, self.loc(ch))  # command=/textfile=: not literal
                    continue
                v, ok = self.subst(raw)
                params[pname] = Value(v if ok else None, self.loc(ch))
            elif t == "rosparam" and ch.get("file"):
                f, ok = self.attr(ch, "file")
                if ok:
                    pfiles.append(f)
                    if as_bool(ch.get("subst_value")) is True:  # the file's $(arg ...) take this file's values
                        got = params.get(SUBST_KEY)
                        files = (got.value[0] if got else ()) + (f,)
                        known = {k: v for k, v in self.subst.vars.items() if v is not None}
                        params[SUBST_KEY] = Value((files, known), self.loc(ch))
            elif t == "rosparam" and (ch.get("command") or "load") == "load" and (ch.text or "").strip():
                params.update(self._node_rosparam(ch))
        if pkg == "robot_state_publisher" and "robot_description" not in params:
            key = "robot_description"
            for ch in el:
                if _tag(ch) == "remap" and ch.get("from") == "robot_description" and ch.get("to"):
                    to, ok = self.subst(ch.get("to"))
                    key = to if ok and to else key
            full = _join_ns(ns, key)
            d = self.descriptions.get(full) or self.descriptions.get(_join_ns("/", key))
            if d is not None:
                params["robot_description"] = Value(d, d.loc)
            else:  # written by an included launch file, perhaps: the deployment finder looks there
                params[_DESCRIPTION_KEY] = Value(full, self.loc(el))
        node = LaunchNode(pkg or "", exe or "", name or "", ns or "/", tuple(args) if args is not None else None,
                          self.loc(el), params, tuple(pfiles), cond)
        record_node(self.info, node, self.ros)


_NOT_A_VALUE = object()
SUBST_KEY = "\x00subst_value"  # LaunchNode.params: ((files loaded with subst_value="true"), {arg: value})


def substitute_args(text: str, args: Mapping[str, str]) -> str:
    """`$(arg x)` in a value of a file loaded with `subst_value="true"`, from the launch file's arguments
    (others are left as written: decided at launch time)."""
    def one(m):
        got = args.get(m.group(2).strip())
        return m.group(0) if got is None else str(got)
    return re.sub(r"\$\(\s*(arg|var)\s+([^()$]*)\)", one, text)


def _typed_param(text: str, type_: str, path: str, loc: Location):
    """A roslaunch <param value=...> as the parameter server gets it (type= or roslaunch's guess)."""
    t = text.strip()
    if type_ == "str" or type_ == "string":
        return text
    if type_ in ("int", "double", "bool", "boolean"):
        try:
            if type_ == "int":
                return int(t)
            if type_ == "double":
                f = float(t)
                return f if math.isfinite(f) else _NOT_A_VALUE
        except ValueError:
            return _NOT_A_VALUE
        b = as_bool(t)
        return _NOT_A_VALUE if b is None or t.lower() not in ("true", "false") else b
    if type_ == "yaml":
        try:
            return parse_yaml(text, path).data
        except ConsumerError:
            return _NOT_A_VALUE
    if type_:
        return _NOT_A_VALUE
    # no type: roslaunch tries int, then float, then true/false, else keeps the string
    for conv in (int, float):
        try:
            v = conv(t)
        except ValueError:
            continue
        return v if not isinstance(v, float) or math.isfinite(v) else text
    if t.lower() in ("true", "false"):
        return t.lower() == "true"
    return text


_FIND_FILE = lazyre.compile(r"^\$\(\s*find(?:-pkg-share)?\s+([A-Za-z0-9_]+)\s*\)/(?:[^$]*/)?([^/$]+)$")


def _outside(raw: str | None) -> tuple[str | None, str]:
    """(package, base name) of an include written `$(find pkg)/.../file` whose package is not known here."""
    m = _FIND_FILE.match((raw or "").strip())
    return (m.group(1), m.group(2)) if m else (None, "")


def _declared(default: str | None, choices: tuple, loc: Location):
    """A launch argument as the deployment finder reads it (one variant per choice)."""
    ok = tuple(c for c in choices if isinstance(c, str) and c and "$(" not in c)
    return Declared(default, ok or None, loc)


def _join_ns(ns: str, sub: str | None) -> str:
    if not sub:
        return ns or "/"
    if sub.startswith("/"):
        return "/" + sub.strip("/")
    return "/" + "/".join(s for s in (ns.strip("/"), sub.strip("/")) if s)


# --- YAML (ROS 2) ------------------------------------------------------------------------------------
class _YamlReader:
    def __init__(self, doc: YamlDoc, args, packages):
        self.doc = doc
        self.subst = _Subst(doc.file, args, packages)
        self.info = LaunchInfo(doc.file, "ros2-yaml")

    def run(self) -> LaunchInfo:
        data = self.doc.data
        if not isinstance(data, dict) or "launch" not in data:
            raise ConsumerError("a YAML launch file needs a top-level 'launch:' list", self.doc.loc())
        items = data["launch"]
        if not isinstance(items, list):
            raise ConsumerError("'launch:' must be a list", self.doc.loc("launch"))
        self.walk(items, ("launch",), "/", None)
        return self.info

    def s(self, v) -> tuple[str | None, bool]:
        if v is None:
            return None, True
        if isinstance(v, bool):
            return ("true" if v else "false"), True
        return self.subst(str(v))

    def walk(self, items: list, path: tuple, ns: str, cond: str | None) -> None:
        for i, item in enumerate(items):
            if not isinstance(item, dict) or len(item) != 1:
                continue
            (tag, body), = item.items()
            p = path + (i, tag)
            if not isinstance(body, dict):
                continue
            active, c = _condition(self.subst, _opt_str(body.get("if")), _opt_str(body.get("unless")))
            if not active:
                continue
            c = c or cond
            if tag == "arg" and body.get("name"):
                if "value" in body:
                    v, ok = self.s(body.get("value"))
                    self.subst.fix(str(body["name"]), v if ok else None)
                else:
                    d, ok = self.s(body.get("default"))
                    self.subst.declare(str(body["name"]), d if ok else None)
                    raw = body.get("choices") or body.get("choice") or ()
                    choices = tuple(str(c.get("value") if isinstance(c, dict) else c)
                                    for c in (raw if isinstance(raw, list) else ()) if c is not None)
                    self.info.declared.setdefault(str(body["name"]), _declared(d if ok else None, choices,
                                                                               self.doc.loc(*p)))
            elif tag == "let" and body.get("name"):
                v, ok = self.s(body.get("value"))
                self.subst.fix(str(body["name"]), v if ok else None)
            elif tag == "group":
                sub_ns = ns
                for key in ("namespace", "ns"):
                    if body.get(key):
                        v, ok = self.s(body[key])
                        sub_ns = _join_ns(ns, v if ok else "?")
                children = body.get("children")
                if isinstance(children, list):
                    self.walk(children, p + ("children",), sub_ns, c)
            elif tag in ("push-ros-namespace", "push_ros_namespace"):
                v, ok = self.s(body.get("namespace"))
                ns = _join_ns(ns, v if ok else "?")
            elif tag == "include":
                f, ok = self.s(body.get("file"))
                passed = dict(self.subst.vars)
                given = body.get("arg")
                for a in given if isinstance(given, list) else ():
                    if isinstance(a, dict) and a.get("name"):
                        v, aok = self.s(a.get("value"))
                        passed[str(a["name"])] = v if aok else None
                self.info.includes.append(Include(f if ok else None, self.doc.loc(*p), passed, c,
                                                  namespace=ns.strip("/")))
            elif tag == "node":
                self.node(body, p, ns, c)

    def node(self, body: dict, p: tuple, ns: str, cond: str | None) -> None:
        loc = self.doc.key_loc(*p)
        pkg, _ = self.s(body.get("pkg"))
        exe, _ = self.s(body.get("exec") or body.get("executable"))
        name, _ = self.s(body.get("name"))
        if body.get("namespace"):
            v, ok = self.s(body["namespace"])
            ns = _join_ns(ns, v if ok else "?")
        args = ()
        if body.get("args") is not None:
            raw = body["args"]
            if isinstance(raw, list):
                vals = [self.s(x) for x in raw]
                args = tuple(v for v, _ in vals) if all(ok for _, ok in vals) else None
            else:
                text, ok = self.s(raw)
                args = _split_args(text) if ok else None
        params: dict[str, Value] = {}
        pfiles: list[str] = []
        plist = body.get("param")
        if isinstance(plist, list):
            for j, entry in enumerate(plist):
                if not isinstance(entry, dict):
                    continue
                eloc = self.doc.loc(*p, "param", j)
                if "from" in entry:
                    f, ok = self.s(entry["from"])
                    if ok:
                        pfiles.append(f)
                elif "name" in entry:
                    v, ok = self.s(entry.get("value"))
                    params[str(entry["name"])] = Value(v if ok else None, self.doc.loc(*p, "param", j, "value") or eloc)
        node = LaunchNode(pkg or "", exe or "", name or "", ns, tuple(args) if args is not None else None,
                          loc, params, tuple(pfiles), cond)
        record_node(self.info, node, 2)


def _opt_str(v) -> str | None:
    if v is None:
        return None
    if isinstance(v, bool):
        return "true" if v else "false"
    return str(v)


# --- entry point -------------------------------------------------------------------------------------
def launch_format(path: str) -> str | None:
    p = path.lower()
    if p.endswith(".py"):
        return "py"
    if p.endswith((".yaml", ".yml")):
        return "yaml"
    if p.endswith((".launch", ".xml")):
        return "xml"
    return None


def read_source(path: str) -> bytes:
    """The bytes of a launch file, through the door, capped at MAX_BYTES. Raises ConsumerError."""
    from urdfcheck.consumers.common import read_capped

    return read_capped(path, MAX_BYTES, "launch file")


def python_tree(raw: bytes, path: str) -> ast.AST:
    """The syntax tree of a Python launch file, never run. Raises ConsumerError."""
    import ast

    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        raise ConsumerError(f"not valid UTF-8 ({e.reason})", Location(path)) from None
    try:
        return ast.parse(text, filename=path)
    except SyntaxError as e:
        raise ConsumerError(f"Python syntax error: {e.msg}", Location(path, e.lineno, e.offset)) from None
    except (RecursionError, MemoryError, ValueError):
        raise ConsumerError("Python launch file nested too deeply or otherwise unparsable; refused",
                            Location(path)) from None


def parse_launch(data: bytes | str | ast.AST, path: str, *, args: Mapping[str, str | None] | None = None,
                 packages: Mapping[str, str] | None = None, find_package=None) -> LaunchInfo:
    """THE entry point for launch content (issue 42): every reader of a launch file (a config's, zero-config
    discovery, the deployment finder) comes through here, so a limit or a refusal is made once. `data`: the bytes
    (`read_source`), or the tree `python_tree` made of them (a reader that keeps it for other questions).
    `find_package(name)`: the Python reader's package finder, when the caller knows more than `packages`.
    Raises ConsumerError when it cannot be read at all."""
    if not isinstance(data, (bytes, str)):
        return _guarded(lambda: _read_python(path, data, args, packages, find_package), path)
    raw = data.encode("utf-8") if isinstance(data, str) else data
    if len(raw) > MAX_BYTES:
        raise ConsumerError(f"launch file is larger than {MAX_BYTES} bytes; refused", Location(path))
    return _guarded(lambda: _parse(raw, path, args, packages, find_package), path)


def _guarded(read, path: str) -> LaunchInfo:
    try:
        return read()
    except (RecursionError, MemoryError):  # any reader: a located error, never a traceback (issue 19)
        raise ConsumerError("launch file nested too deeply or too large to read; refused", Location(path)) from None
    except ValueError:
        raise ConsumerError("launch file not understood", Location(path)) from None


def _parse(raw: bytes, path: str, args, packages, find_package) -> LaunchInfo:
    fmt = launch_format(path)
    if fmt == "yaml":
        return _YamlReader(parse_yaml(raw, path), args, packages).run()
    if fmt == "py":
        return _read_python(path, python_tree(raw, path), args, packages, find_package)
    if fmt == "xml":
        root = _xml_root(raw, path)
        return _XmlReader(path, root, args, packages).run()
    raise ConsumerError("unknown launch file type (expected .launch, .launch.xml, .launch.py, .launch.yaml)",
                        Location(path))


def _read_python(path: str, tree: ast.AST, args, packages, find_package=None) -> LaunchInfo:
    """The one Python reader (`pylaunch.read`), whoever asks: a config's launch files, zero-config discovery
    and the deployment finder read the same `LaunchInfo` from the same file."""
    from urdfcheck.consumers.launch import python as pylaunch

    if find_package is not None:
        return pylaunch.read(path, tree, args, find_package)
    known = dict(packages or {})
    own: list = []

    def find_in_map(name: str) -> str | None:
        if name in known:
            return known[name]
        if not own:
            own.append(_own(path))
        return own[0][1] if own[0][0] == name else None

    return pylaunch.read(path, tree, args, find_in_map)


def read_launch(path: str | os.PathLike, *, args: Mapping[str, str] | None = None,
                packages: Mapping[str, str] | None = None) -> LaunchInfo:
    """Read a launch file. Raises ConsumerError (unreadable, too large, bad syntax)."""
    file = str(path)
    return parse_launch(read_source(file), file, args=args, packages=packages)
