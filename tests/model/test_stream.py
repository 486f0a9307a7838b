"""A large plain URDF is read as its model is built (core.xmlfront.stream, model.build.build_streamed): the
whole libxml2 tree never exists. The model, the findings and the errors must be those of the whole-tree read."""
import json
import random

import pytest
from conftest import lint_json

from urdfcheck.core import xmlfront
from urdfcheck.core.findings import Location
from urdfcheck.load import loader
from urdfcheck.model.build import build, build_streamed

# every kind of root child the builder reads or reports, nested names that are top-level tags elsewhere, comments
PARTS = [
    '<!-- a comment between parts -->',
    '<material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>',
    '<link name="L{i}"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'
    '</inertial><visual><origin xyz="0 0 {i}"/><geometry><box size="1 1 1"/></geometry><material name="grey"/>'
    '</visual><collision><geometry><cylinder radius="0.1" length="0.2"/></geometry></collision></link>'
    '<joint name="F{i}" type="fixed"><parent link="L{p}"/><child link="L{i}"/></joint>',
    '<link name="K{i}"/>'
    '<joint name="J{i}" type="revolute" dont_collapse="{keep}"><parent link="L{p}"/><child link="K{i}"/>'
    '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
    '<safety_controller soft_lower_limit="-0.5" soft_upper_limit="0.5" k_velocity="1"/></joint>',
    '<transmission name="T{i}"><type>x</type><joint name="J{j}"><hardwareInterface>y</hardwareInterface>'
    '</joint><actuator name="A{i}"/></transmission>',
    '<gazebo reference="L{i}"><link name="nested"/><plugin name="p{i}" filename="libp.so"><x>1</x></plugin>'
    '<ros2_control name="g{i}" type="system"><joint name="J{j}"/></ros2_control></gazebo>',
    '<ros2_control name="R{i}" type="system"><hardware><plugin>h</plugin></hardware><joint name="J{j}">'
    '<command_interface name="position"/><state_interface name="position"/></joint></ros2_control>',
    '<frobnicate name="F{i}"><link name="inside"/></frobnicate>',  # unknown at the top: U002
    '<link name="B{i}"/><joint name="bad{i}" type="revolute"><parent link="L{p}"/><child link="B{i}"/>'
    '<origin xyz="1 2"/>'
    '<limit effort="x" velocity="1"/></joint>',  # U004, U005
    '<link name="L{i}"/>',  # a duplicate
]


def document(n: int, seed: int = 1, root: str = '<robot name="r">', plain: float = 0.0) -> str:
    """`n` children of the root, drawn from PARTS (a share `plain` of them a link and its joint). A joint's
    parent is a link written before it, a block's joint one written before it (many names that are not there
    make the rules slow with "did you mean" hints: not this test's business)."""
    rng = random.Random(seed)
    body, links, joints = ['<link name="L0"/>'], [0], [0]
    for i in range(1, n):
        part = PARTS[rng.choice((2, 3))] if rng.random() < plain else PARTS[rng.randrange(len(PARTS))]
        body.append(part.format(i=i, p=rng.choice(links), j=joints[-1], keep=rng.choice(("true", "false", "TRUE"))))
        if part.startswith('<link name="L{i}">'):
            links.append(i)
        elif part.startswith('<link name="K{i}"/>'):
            joints.append(i)
    end = "</" + root[1:].split()[0].rstrip(">") + ">"
    return '<?xml version="1.0"?>\n' + root + "\n" + "\n".join(body) + "\n" + end + "\n"


def _locate(el):
    return Location("m.urdf", el.sourceline)


def both(text: str):
    data = text.encode()
    root, _ = xmlfront.parse(data)
    return build(root, _locate, "m.urdf"), build_streamed(xmlfront.stream(data), _locate, "m.urdf")


@pytest.mark.parametrize("seed", range(6))
def test_streamed_model_is_the_whole_tree_model(seed):
    tree, streamed = both(document(300, seed))
    assert streamed == tree
    assert streamed.issues and streamed.blocks and streamed.ros2_control  # the document exercised them


@pytest.mark.parametrize("root", ['<robot name="r" version="1.1" extra="1">', '<robot>', '<model name="m">'])
def test_root_element_read_before_its_children(root):
    tree, streamed = both(document(40, 7, root))
    assert streamed == tree


@pytest.mark.parametrize("text", [
    '<robot name="r"/>',
    '<robot name="r"><!-- only a comment --></robot>',
    '<robot name="r"><frobnicate/><other/></robot>',  # no child the parser announces
    '<link name="solo"><visual><geometry><box size="1 1 1"/></geometry></visual></link>',  # a part as the root
    '<robot name="r"><link name="a"/><frobnicate/></robot>',  # an unknown child after the last part
])
def test_edge_documents(text):
    tree, streamed = both(text)
    assert streamed == tree


@pytest.mark.parametrize("newline", ["\n", "\r\n", "\r"])
def test_pieces_cut_anywhere_read_as_the_whole(newline):
    """The parser is fed the bytes in pieces: a piece may end inside a multi-byte character, a tag spread over
    lines or a line ending; the lines and names are still those of one whole parse."""
    text = document(1500, 11).replace('"L', '"Łącznik-L').replace("<joint ", "<joint\n   ")
    text = text.replace("\n", newline)
    assert len(text.encode()) > 4 * xmlfront._PIECE
    tree, streamed = both(text)
    assert streamed == tree
    assert any("Łącznik" in name for name in streamed.links)


def test_a_child_is_dropped_once_read():
    data = document(5000, 3).encode()
    elements = xmlfront.stream(data)
    root = next(elements)
    most = seen = 0
    for el in elements:
        assert root[0] is el  # everything before it is gone
        most = max(most, len(root))
        seen += 1
    assert seen == len(xmlfront.parse(data)[0]) and len(data) > 500_000  # many of the parser's chunks
    assert most < 500  # besides it, only what the parser read ahead in its current chunk


def test_streamed_errors_raise_for_the_whole_read():
    from lxml import etree

    good = document(50, 2)
    for bad in (good.replace("</robot>", "</robot><robot/>"), good[: len(good) // 2],
                good.replace('<link name="L0"/>', '<link name="L0/>')):
        with pytest.raises(etree.XMLSyntaxError):
            list(xmlfront.stream(bad.encode()))
        with pytest.raises(xmlfront.XmlRefused):
            xmlfront.parse(bad.encode())


# --- through the loader: the large file streams, and its findings are the whole-tree read's ------------------------
def large(n_min: int = xmlfront.STREAM_BYTES) -> str:
    n = 200
    while True:
        text = document(n, 5, plain=0.97)  # mostly links and joints: the findings of a real large model
        if len(text) >= n_min:
            return text
        n *= 2


def test_large_file_is_read_without_its_tree(tmp_path):
    p = tmp_path / "big.urdf"
    p.write_text(large())
    pending = loader.begin(p, stream=True).result()
    assert pending.root is None and pending.stream is not None
    model = loader.build_model(pending)
    whole = loader.expand(p)
    assert whole.root is not None and whole.stream is None
    assert model == loader.build_model(whole)


def test_large_file_findings_match_the_whole_tree(tmp_path, monkeypatch):
    p = tmp_path / "big.urdf"
    p.write_text(large())
    streamed = lint_json([str(p), "--profile", "isaac", "--profile", "moveit"])[1]
    monkeypatch.setattr(xmlfront, "STREAM_BYTES", 10**12)
    whole = lint_json([str(p), "--profile", "isaac", "--profile", "moveit"])[1]
    assert json.dumps(streamed, sort_keys=True) == json.dumps(whole, sort_keys=True)
    codes = {f["code"] for f in streamed["findings"]}
    assert {"U002", "U004", "U005", "P060"} <= codes


@pytest.mark.parametrize("spoil", [
    lambda t: t.replace("</robot>", "</robot>\n<robot/>"),  # content after the root: X002
    lambda t: t[: len(t) * 2 // 3],  # cut short: X001, found at the end of a streamed read
    lambda t: t.replace('<link name="L0"/>', '<link name="L0" drake:x="1"/>'),  # an undeclared prefix: X005
    lambda t: t.replace('<?xml version="1.0"?>', '<?xml verison="1.0"?>'),  # the declaration: X003, read on
])
def test_large_broken_file_reports_what_the_whole_read_reports(tmp_path, monkeypatch, spoil):
    p = tmp_path / "big.urdf"
    p.write_text(spoil(large()))
    streamed = lint_json([str(p)])[1]
    monkeypatch.setattr(xmlfront, "STREAM_BYTES", 10**12)
    whole = lint_json([str(p)])[1]
    assert json.dumps(streamed, sort_keys=True) == json.dumps(whole, sort_keys=True)
    assert {f["code"] for f in streamed["findings"]} & {"X001", "X002", "X003", "X005"}


XACRO_ROOT = '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'


def test_exported_xacro_output_streams(tmp_path):
    """`xacro robot.urdf.xacro > robot.urdf` keeps xmlns:xacro on <robot>: no xacro element, so it streams."""
    p = tmp_path / "big.urdf"
    p.write_text(large().replace('<robot name="r">', XACRO_ROOT, 1))
    exp = loader.begin(p, stream=True).result()
    assert exp.stream is not None and not exp.xacro


@pytest.mark.parametrize("element", ['<xacro:property name="a" value="1"/>',
                                     '<x:property xmlns:x="http://www.ros.org/wiki/xacro" name="a" value="1"/>'])
def test_a_xacro_element_is_never_streamed(tmp_path, element):
    p = tmp_path / "big.urdf"
    text = large().replace('<robot name="r">', XACRO_ROOT, 1)
    p.write_text(text.replace('<link name="L0"/>', '<link name="L0"/>' + element, 1))
    exp = loader.begin(p, stream=True).result()
    assert exp.stream is None and exp.xacro  # read whole, found to be xacro, expanded as such
