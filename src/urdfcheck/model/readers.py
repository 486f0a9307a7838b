"""Attribute readers, one per URDF element and version: GENERATED from model/grammar.py by
`python -m urdfcheck.model.readergen`. Do not edit; see readergen.py."""
# flake8: noqa

SRC = '__ucsrc'


def robot_1_0(b, el):
    get = el.get
    a0 = get('name')
    a1 = get('version')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'robot')
    if a0 is None:
        v0 = None
    else:
        v0 = a0
    if a1 is None:
        v1 = None
    else:
        v1 = a1
    return (v0, v1, )


def link_1_0(b, el):
    get = el.get
    a0 = get('name')
    a1 = get('type')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'link')
    if not a0:
        b.missing(el, 'link', 0)
        v0 = None
    else:
        v0 = a0
    if a1 is None:
        v1 = None
    else:
        v1 = a1
    return (v0, v1, )


def inertial_1_0(b, el):
    n = len(el.attrib)
    if n and (n != 1 or el.get(SRC) is None):
        b.odd_attributes(el, 'inertial')
    return ()


def mass_1_0(b, el):
    get = el.get
    a0 = get('value')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'mass')
    if len(el):
        b.children_of_leaf(el, 'mass')
    if a0 is None:
        b.missing(el, 'mass', 0)
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'mass', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'mass', 0, a0, True)
    return (v0, )


def inertia_1_0(b, el):
    get = el.get
    a0 = get('ixx')
    a1 = get('ixy')
    a2 = get('ixz')
    a3 = get('iyy')
    a4 = get('iyz')
    a5 = get('izz')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None) + (a3 is not None) + (a4 is not None) + (a5 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'inertia')
    if len(el):
        b.children_of_leaf(el, 'inertia')
    if a0 is None:
        b.missing(el, 'inertia', 0)
        v0 = 0.0
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'inertia', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'inertia', 0, a0, True)
    if a1 is None:
        b.missing(el, 'inertia', 1)
        v1 = 0.0
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'inertia', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'inertia', 1, a1, True)
    if a2 is None:
        b.missing(el, 'inertia', 2)
        v2 = 0.0
    else:
        try:
            v2 = float(a2)
        except ValueError:
            v2 = b.bad_number(el, 'inertia', 2, a2, False)
        else:
            if v2 - v2 != 0.0 or '_' in a2:  # nan/inf, or Python-only digit separators
                v2 = b.bad_number(el, 'inertia', 2, a2, True)
    if a3 is None:
        b.missing(el, 'inertia', 3)
        v3 = 0.0
    else:
        try:
            v3 = float(a3)
        except ValueError:
            v3 = b.bad_number(el, 'inertia', 3, a3, False)
        else:
            if v3 - v3 != 0.0 or '_' in a3:  # nan/inf, or Python-only digit separators
                v3 = b.bad_number(el, 'inertia', 3, a3, True)
    if a4 is None:
        b.missing(el, 'inertia', 4)
        v4 = 0.0
    else:
        try:
            v4 = float(a4)
        except ValueError:
            v4 = b.bad_number(el, 'inertia', 4, a4, False)
        else:
            if v4 - v4 != 0.0 or '_' in a4:  # nan/inf, or Python-only digit separators
                v4 = b.bad_number(el, 'inertia', 4, a4, True)
    if a5 is None:
        b.missing(el, 'inertia', 5)
        v5 = 0.0
    else:
        try:
            v5 = float(a5)
        except ValueError:
            v5 = b.bad_number(el, 'inertia', 5, a5, False)
        else:
            if v5 - v5 != 0.0 or '_' in a5:  # nan/inf, or Python-only digit separators
                v5 = b.bad_number(el, 'inertia', 5, a5, True)
    return (v0, v1, v2, v3, v4, v5, )


def visual_1_0(b, el):
    get = el.get
    a0 = get('name')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'visual')
    if a0 is None:
        v0 = None
    else:
        v0 = a0
    return (v0, )


def collision_1_0(b, el):
    get = el.get
    a0 = get('name')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'collision')
    if a0 is None:
        v0 = None
    else:
        v0 = a0
    return (v0, )


def origin_1_0(b, el):
    get = el.get
    a0 = get('xyz')
    a1 = get('rpy')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'origin')
    if len(el):
        b.children_of_leaf(el, 'origin')
    vectors = b.vectors
    if a0 is None:
        v0 = (0.0, 0.0, 0.0)
    else:
        v0 = vectors.get(a0)
        if v0 is None or len(v0) != 3:
            v0 = b.vector(el, 'origin', 0, a0, 3)
    if a1 is None:
        v1 = (0.0, 0.0, 0.0)
    else:
        v1 = vectors.get(a1)
        if v1 is None or len(v1) != 3:
            v1 = b.vector(el, 'origin', 1, a1, 3)
    return (v0, v1, )


def geometry_1_0(b, el):
    n = len(el.attrib)
    if n and (n != 1 or el.get(SRC) is None):
        b.odd_attributes(el, 'geometry')
    return ()


def box_1_0(b, el):
    get = el.get
    a0 = get('size')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'box')
    if len(el):
        b.children_of_leaf(el, 'box')
    vectors = b.vectors
    if a0 is None:
        b.missing(el, 'box', 0)
        v0 = None
    else:
        v0 = vectors.get(a0)
        if v0 is None or len(v0) != 3:
            v0 = b.vector(el, 'box', 0, a0, 3)
    return (v0, )


def cylinder_1_0(b, el):
    get = el.get
    a0 = get('radius')
    a1 = get('length')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'cylinder')
    if len(el):
        b.children_of_leaf(el, 'cylinder')
    if a0 is None:
        b.missing(el, 'cylinder', 0)
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'cylinder', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'cylinder', 0, a0, True)
    if a1 is None:
        b.missing(el, 'cylinder', 1)
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'cylinder', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'cylinder', 1, a1, True)
    return (v0, v1, )


def capsule_1_0(b, el):
    get = el.get
    a0 = get('radius')
    a1 = get('length')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'capsule')
    if len(el):
        b.children_of_leaf(el, 'capsule')
    if a0 is None:
        b.missing(el, 'capsule', 0)
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'capsule', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'capsule', 0, a0, True)
    if a1 is None:
        b.missing(el, 'capsule', 1)
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'capsule', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'capsule', 1, a1, True)
    return (v0, v1, )


def sphere_1_0(b, el):
    get = el.get
    a0 = get('radius')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'sphere')
    if len(el):
        b.children_of_leaf(el, 'sphere')
    if a0 is None:
        b.missing(el, 'sphere', 0)
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'sphere', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'sphere', 0, a0, True)
    return (v0, )


def mesh_1_0(b, el):
    get = el.get
    a0 = get('filename')
    a1 = get('scale')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'mesh')
    if len(el):
        b.children_of_leaf(el, 'mesh')
    vectors = b.vectors
    if not a0:
        b.missing(el, 'mesh', 0)
        v0 = None
    else:
        v0 = a0
    if a1 is None:
        v1 = (1.0, 1.0, 1.0)
    else:
        v1 = vectors.get(a1)
        if v1 is None or len(v1) != 3:
            v1 = b.vector(el, 'mesh', 1, a1, 3)
    return (v0, v1, )


def material_1_0(b, el):
    get = el.get
    a0 = get('name')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'material')
    if a0 is None:
        b.missing(el, 'material', 0)
        v0 = None
    else:
        v0 = a0
    return (v0, )


def color_1_0(b, el):
    get = el.get
    a0 = get('rgba')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'color')
    if len(el):
        b.children_of_leaf(el, 'color')
    vectors = b.vectors
    if a0 is None:
        b.missing(el, 'color', 0)
        v0 = None
    else:
        v0 = vectors.get(a0)
        if v0 is None or len(v0) != 4:
            v0 = b.vector(el, 'color', 0, a0, 4)
    return (v0, )


def texture_1_0(b, el):
    get = el.get
    a0 = get('filename')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'texture')
    if len(el):
        b.children_of_leaf(el, 'texture')
    if a0 is None:
        v0 = None
    else:
        v0 = a0
    return (v0, )


def joint_1_0(b, el):
    get = el.get
    a0 = get('name')
    a1 = get('type')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'joint')
    if not a0:
        b.missing(el, 'joint', 0)
        v0 = None
    else:
        v0 = a0
    if a1 is None:
        b.missing(el, 'joint', 1)
        v1 = None
    else:
        v1 = a1
    return (v0, v1, )


def parent_1_0(b, el):
    get = el.get
    a0 = get('link')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'parent')
    if len(el):
        b.children_of_leaf(el, 'parent')
    if not a0:
        b.missing(el, 'parent', 0)
        v0 = None
    else:
        v0 = a0
    return (v0, )


def child_1_0(b, el):
    get = el.get
    a0 = get('link')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'child')
    if len(el):
        b.children_of_leaf(el, 'child')
    if not a0:
        b.missing(el, 'child', 0)
        v0 = None
    else:
        v0 = a0
    return (v0, )


def axis_1_0(b, el):
    get = el.get
    a0 = get('xyz')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'axis')
    if len(el):
        b.children_of_leaf(el, 'axis')
    vectors = b.vectors
    if a0 is None:
        b.missing(el, 'axis', 0)
        v0 = (0.0, 0.0, 0.0)
    else:
        v0 = vectors.get(a0)
        if v0 is None or len(v0) != 3:
            v0 = b.vector(el, 'axis', 0, a0, 3)
    return (v0, )


def calibration_1_0(b, el):
    get = el.get
    a0 = get('rising')
    a1 = get('falling')
    a2 = get('reference_position')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'calibration')
    if len(el):
        b.children_of_leaf(el, 'calibration')
    if a0 is None:
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'calibration', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'calibration', 0, a0, True)
    if a1 is None:
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'calibration', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'calibration', 1, a1, True)
    if a2 is None:
        v2 = None
    else:
        try:
            v2 = float(a2)
        except ValueError:
            v2 = b.bad_number(el, 'calibration', 2, a2, False)
        else:
            if v2 - v2 != 0.0 or '_' in a2:  # nan/inf, or Python-only digit separators
                v2 = b.bad_number(el, 'calibration', 2, a2, True)
    return (v0, v1, v2, )


def dynamics_1_0(b, el):
    get = el.get
    a0 = get('damping')
    a1 = get('friction')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'dynamics')
    if len(el):
        b.children_of_leaf(el, 'dynamics')
    if a0 is None:
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'dynamics', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'dynamics', 0, a0, True)
    if a1 is None:
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'dynamics', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'dynamics', 1, a1, True)
    return (v0, v1, )


def limit_1_0(b, el):
    get = el.get
    a0 = get('lower')
    a1 = get('upper')
    a2 = get('effort')
    a3 = get('velocity')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None) + (a3 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'limit')
    if len(el):
        b.children_of_leaf(el, 'limit')
    if a0 is None:
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'limit', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'limit', 0, a0, True)
    if a1 is None:
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'limit', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'limit', 1, a1, True)
    if a2 is None:
        b.missing(el, 'limit', 2)
        v2 = None
    else:
        try:
            v2 = float(a2)
        except ValueError:
            v2 = b.bad_number(el, 'limit', 2, a2, False)
        else:
            if v2 - v2 != 0.0 or '_' in a2:  # nan/inf, or Python-only digit separators
                v2 = b.bad_number(el, 'limit', 2, a2, True)
    if a3 is None:
        b.missing(el, 'limit', 3)
        v3 = None
    else:
        try:
            v3 = float(a3)
        except ValueError:
            v3 = b.bad_number(el, 'limit', 3, a3, False)
        else:
            if v3 - v3 != 0.0 or '_' in a3:  # nan/inf, or Python-only digit separators
                v3 = b.bad_number(el, 'limit', 3, a3, True)
    return (v0, v1, v2, v3, )


def mimic_1_0(b, el):
    get = el.get
    a0 = get('joint')
    a1 = get('multiplier')
    a2 = get('offset')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'mimic')
    if len(el):
        b.children_of_leaf(el, 'mimic')
    if not a0:
        b.missing(el, 'mimic', 0)
        v0 = None
    else:
        v0 = a0
    if a1 is None:
        v1 = 1.0
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'mimic', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'mimic', 1, a1, True)
    if a2 is None:
        v2 = 0.0
    else:
        try:
            v2 = float(a2)
        except ValueError:
            v2 = b.bad_number(el, 'mimic', 2, a2, False)
        else:
            if v2 - v2 != 0.0 or '_' in a2:  # nan/inf, or Python-only digit separators
                v2 = b.bad_number(el, 'mimic', 2, a2, True)
    return (v0, v1, v2, )


def safety_controller_1_0(b, el):
    get = el.get
    a0 = get('soft_lower_limit')
    a1 = get('soft_upper_limit')
    a2 = get('k_position')
    a3 = get('k_velocity')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None) + (a3 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'safety_controller')
    if len(el):
        b.children_of_leaf(el, 'safety_controller')
    if a0 is None:
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'safety_controller', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'safety_controller', 0, a0, True)
    if a1 is None:
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'safety_controller', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'safety_controller', 1, a1, True)
    if a2 is None:
        v2 = None
    else:
        try:
            v2 = float(a2)
        except ValueError:
            v2 = b.bad_number(el, 'safety_controller', 2, a2, False)
        else:
            if v2 - v2 != 0.0 or '_' in a2:  # nan/inf, or Python-only digit separators
                v2 = b.bad_number(el, 'safety_controller', 2, a2, True)
    if a3 is None:
        v3 = None
    else:
        try:
            v3 = float(a3)
        except ValueError:
            v3 = b.bad_number(el, 'safety_controller', 3, a3, False)
        else:
            if v3 - v3 != 0.0 or '_' in a3:  # nan/inf, or Python-only digit separators
                v3 = b.bad_number(el, 'safety_controller', 3, a3, True)
    return (v0, v1, v2, v3, )


def robot_1_1(b, el):
    get = el.get
    a0 = get('name')
    a1 = get('version')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'robot')
    if a0 is None:
        v0 = None
    else:
        v0 = a0
    if a1 is None:
        v1 = None
    else:
        v1 = a1
    return (v0, v1, )


def link_1_1(b, el):
    get = el.get
    a0 = get('name')
    a1 = get('type')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'link')
    if not a0:
        b.missing(el, 'link', 0)
        v0 = None
    else:
        v0 = a0
    if a1 is None:
        v1 = None
    else:
        v1 = a1
    return (v0, v1, )


def inertial_1_1(b, el):
    n = len(el.attrib)
    if n and (n != 1 or el.get(SRC) is None):
        b.odd_attributes(el, 'inertial')
    return ()


def mass_1_1(b, el):
    get = el.get
    a0 = get('value')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'mass')
    if len(el):
        b.children_of_leaf(el, 'mass')
    if a0 is None:
        b.missing(el, 'mass', 0)
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'mass', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'mass', 0, a0, True)
    return (v0, )


def inertia_1_1(b, el):
    get = el.get
    a0 = get('ixx')
    a1 = get('ixy')
    a2 = get('ixz')
    a3 = get('iyy')
    a4 = get('iyz')
    a5 = get('izz')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None) + (a3 is not None) + (a4 is not None) + (a5 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'inertia')
    if len(el):
        b.children_of_leaf(el, 'inertia')
    if a0 is None:
        b.missing(el, 'inertia', 0)
        v0 = 0.0
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'inertia', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'inertia', 0, a0, True)
    if a1 is None:
        b.missing(el, 'inertia', 1)
        v1 = 0.0
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'inertia', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'inertia', 1, a1, True)
    if a2 is None:
        b.missing(el, 'inertia', 2)
        v2 = 0.0
    else:
        try:
            v2 = float(a2)
        except ValueError:
            v2 = b.bad_number(el, 'inertia', 2, a2, False)
        else:
            if v2 - v2 != 0.0 or '_' in a2:  # nan/inf, or Python-only digit separators
                v2 = b.bad_number(el, 'inertia', 2, a2, True)
    if a3 is None:
        b.missing(el, 'inertia', 3)
        v3 = 0.0
    else:
        try:
            v3 = float(a3)
        except ValueError:
            v3 = b.bad_number(el, 'inertia', 3, a3, False)
        else:
            if v3 - v3 != 0.0 or '_' in a3:  # nan/inf, or Python-only digit separators
                v3 = b.bad_number(el, 'inertia', 3, a3, True)
    if a4 is None:
        b.missing(el, 'inertia', 4)
        v4 = 0.0
    else:
        try:
            v4 = float(a4)
        except ValueError:
            v4 = b.bad_number(el, 'inertia', 4, a4, False)
        else:
            if v4 - v4 != 0.0 or '_' in a4:  # nan/inf, or Python-only digit separators
                v4 = b.bad_number(el, 'inertia', 4, a4, True)
    if a5 is None:
        b.missing(el, 'inertia', 5)
        v5 = 0.0
    else:
        try:
            v5 = float(a5)
        except ValueError:
            v5 = b.bad_number(el, 'inertia', 5, a5, False)
        else:
            if v5 - v5 != 0.0 or '_' in a5:  # nan/inf, or Python-only digit separators
                v5 = b.bad_number(el, 'inertia', 5, a5, True)
    return (v0, v1, v2, v3, v4, v5, )


def visual_1_1(b, el):
    get = el.get
    a0 = get('name')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'visual')
    if a0 is None:
        v0 = None
    else:
        v0 = a0
    return (v0, )


def collision_1_1(b, el):
    get = el.get
    a0 = get('name')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'collision')
    if a0 is None:
        v0 = None
    else:
        v0 = a0
    return (v0, )


def origin_1_1(b, el):
    get = el.get
    a0 = get('xyz')
    a1 = get('rpy')
    a2 = get('quat_xyzw')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'origin')
    if len(el):
        b.children_of_leaf(el, 'origin')
    if a1 is not None and a2 is not None:
        b.exclusive(el, ('rpy', 'quat_xyzw'))
    vectors = b.vectors
    if a0 is None:
        v0 = (0.0, 0.0, 0.0)
    else:
        v0 = vectors.get(a0)
        if v0 is None or len(v0) != 3:
            v0 = b.vector(el, 'origin', 0, a0, 3)
    if a1 is None:
        v1 = (0.0, 0.0, 0.0)
    else:
        v1 = vectors.get(a1)
        if v1 is None or len(v1) != 3:
            v1 = b.vector(el, 'origin', 1, a1, 3)
    if a2 is None:
        v2 = None
    else:
        v2 = vectors.get(a2)
        if v2 is None or len(v2) != 4:
            v2 = b.vector(el, 'origin', 2, a2, 4)
    return (v0, v1, v2, )


def geometry_1_1(b, el):
    n = len(el.attrib)
    if n and (n != 1 or el.get(SRC) is None):
        b.odd_attributes(el, 'geometry')
    return ()


def box_1_1(b, el):
    get = el.get
    a0 = get('size')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'box')
    if len(el):
        b.children_of_leaf(el, 'box')
    vectors = b.vectors
    if a0 is None:
        b.missing(el, 'box', 0)
        v0 = None
    else:
        v0 = vectors.get(a0)
        if v0 is None or len(v0) != 3:
            v0 = b.vector(el, 'box', 0, a0, 3)
    return (v0, )


def cylinder_1_1(b, el):
    get = el.get
    a0 = get('radius')
    a1 = get('length')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'cylinder')
    if len(el):
        b.children_of_leaf(el, 'cylinder')
    if a0 is None:
        b.missing(el, 'cylinder', 0)
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'cylinder', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'cylinder', 0, a0, True)
    if a1 is None:
        b.missing(el, 'cylinder', 1)
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'cylinder', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'cylinder', 1, a1, True)
    return (v0, v1, )


def capsule_1_1(b, el):
    get = el.get
    a0 = get('radius')
    a1 = get('length')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'capsule')
    if len(el):
        b.children_of_leaf(el, 'capsule')
    if a0 is None:
        b.missing(el, 'capsule', 0)
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'capsule', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'capsule', 0, a0, True)
    if a1 is None:
        b.missing(el, 'capsule', 1)
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'capsule', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'capsule', 1, a1, True)
    return (v0, v1, )


def sphere_1_1(b, el):
    get = el.get
    a0 = get('radius')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'sphere')
    if len(el):
        b.children_of_leaf(el, 'sphere')
    if a0 is None:
        b.missing(el, 'sphere', 0)
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'sphere', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'sphere', 0, a0, True)
    return (v0, )


def mesh_1_1(b, el):
    get = el.get
    a0 = get('filename')
    a1 = get('scale')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'mesh')
    if len(el):
        b.children_of_leaf(el, 'mesh')
    vectors = b.vectors
    if not a0:
        b.missing(el, 'mesh', 0)
        v0 = None
    else:
        v0 = a0
    if a1 is None:
        v1 = (1.0, 1.0, 1.0)
    else:
        v1 = vectors.get(a1)
        if v1 is None or len(v1) != 3:
            v1 = b.vector(el, 'mesh', 1, a1, 3)
    return (v0, v1, )


def material_1_1(b, el):
    get = el.get
    a0 = get('name')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'material')
    if a0 is None:
        b.missing(el, 'material', 0)
        v0 = None
    else:
        v0 = a0
    return (v0, )


def color_1_1(b, el):
    get = el.get
    a0 = get('rgba')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'color')
    if len(el):
        b.children_of_leaf(el, 'color')
    vectors = b.vectors
    if a0 is None:
        b.missing(el, 'color', 0)
        v0 = None
    else:
        v0 = vectors.get(a0)
        if v0 is None or len(v0) != 4:
            v0 = b.vector(el, 'color', 0, a0, 4)
    return (v0, )


def texture_1_1(b, el):
    get = el.get
    a0 = get('filename')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'texture')
    if len(el):
        b.children_of_leaf(el, 'texture')
    if a0 is None:
        v0 = None
    else:
        v0 = a0
    return (v0, )


def joint_1_1(b, el):
    get = el.get
    a0 = get('name')
    a1 = get('type')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'joint')
    if not a0:
        b.missing(el, 'joint', 0)
        v0 = None
    else:
        v0 = a0
    if a1 is None:
        b.missing(el, 'joint', 1)
        v1 = None
    else:
        v1 = a1
    return (v0, v1, )


def parent_1_1(b, el):
    get = el.get
    a0 = get('link')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'parent')
    if len(el):
        b.children_of_leaf(el, 'parent')
    if not a0:
        b.missing(el, 'parent', 0)
        v0 = None
    else:
        v0 = a0
    return (v0, )


def child_1_1(b, el):
    get = el.get
    a0 = get('link')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'child')
    if len(el):
        b.children_of_leaf(el, 'child')
    if not a0:
        b.missing(el, 'child', 0)
        v0 = None
    else:
        v0 = a0
    return (v0, )


def axis_1_1(b, el):
    get = el.get
    a0 = get('xyz')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'axis')
    if len(el):
        b.children_of_leaf(el, 'axis')
    vectors = b.vectors
    if a0 is None:
        b.missing(el, 'axis', 0)
        v0 = (0.0, 0.0, 0.0)
    else:
        v0 = vectors.get(a0)
        if v0 is None or len(v0) != 3:
            v0 = b.vector(el, 'axis', 0, a0, 3)
    return (v0, )


def calibration_1_1(b, el):
    get = el.get
    a0 = get('rising')
    a1 = get('falling')
    a2 = get('reference_position')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'calibration')
    if len(el):
        b.children_of_leaf(el, 'calibration')
    if a0 is None:
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'calibration', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'calibration', 0, a0, True)
    if a1 is None:
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'calibration', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'calibration', 1, a1, True)
    if a2 is None:
        v2 = None
    else:
        try:
            v2 = float(a2)
        except ValueError:
            v2 = b.bad_number(el, 'calibration', 2, a2, False)
        else:
            if v2 - v2 != 0.0 or '_' in a2:  # nan/inf, or Python-only digit separators
                v2 = b.bad_number(el, 'calibration', 2, a2, True)
    return (v0, v1, v2, )


def dynamics_1_1(b, el):
    get = el.get
    a0 = get('damping')
    a1 = get('friction')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'dynamics')
    if len(el):
        b.children_of_leaf(el, 'dynamics')
    if a0 is None:
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'dynamics', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'dynamics', 0, a0, True)
    if a1 is None:
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'dynamics', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'dynamics', 1, a1, True)
    return (v0, v1, )


def limit_1_1(b, el):
    get = el.get
    a0 = get('lower')
    a1 = get('upper')
    a2 = get('effort')
    a3 = get('velocity')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None) + (a3 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'limit')
    if len(el):
        b.children_of_leaf(el, 'limit')
    if a0 is None:
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'limit', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'limit', 0, a0, True)
    if a1 is None:
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'limit', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'limit', 1, a1, True)
    if a2 is None:
        b.missing(el, 'limit', 2)
        v2 = None
    else:
        try:
            v2 = float(a2)
        except ValueError:
            v2 = b.bad_number(el, 'limit', 2, a2, False)
        else:
            if v2 - v2 != 0.0 or '_' in a2:  # nan/inf, or Python-only digit separators
                v2 = b.bad_number(el, 'limit', 2, a2, True)
    if a3 is None:
        b.missing(el, 'limit', 3)
        v3 = None
    else:
        try:
            v3 = float(a3)
        except ValueError:
            v3 = b.bad_number(el, 'limit', 3, a3, False)
        else:
            if v3 - v3 != 0.0 or '_' in a3:  # nan/inf, or Python-only digit separators
                v3 = b.bad_number(el, 'limit', 3, a3, True)
    return (v0, v1, v2, v3, )


def mimic_1_1(b, el):
    get = el.get
    a0 = get('joint')
    a1 = get('multiplier')
    a2 = get('offset')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'mimic')
    if len(el):
        b.children_of_leaf(el, 'mimic')
    if not a0:
        b.missing(el, 'mimic', 0)
        v0 = None
    else:
        v0 = a0
    if a1 is None:
        v1 = 1.0
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'mimic', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'mimic', 1, a1, True)
    if a2 is None:
        v2 = 0.0
    else:
        try:
            v2 = float(a2)
        except ValueError:
            v2 = b.bad_number(el, 'mimic', 2, a2, False)
        else:
            if v2 - v2 != 0.0 or '_' in a2:  # nan/inf, or Python-only digit separators
                v2 = b.bad_number(el, 'mimic', 2, a2, True)
    return (v0, v1, v2, )


def safety_controller_1_1(b, el):
    get = el.get
    a0 = get('soft_lower_limit')
    a1 = get('soft_upper_limit')
    a2 = get('k_position')
    a3 = get('k_velocity')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None) + (a3 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'safety_controller')
    if len(el):
        b.children_of_leaf(el, 'safety_controller')
    if a0 is None:
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'safety_controller', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'safety_controller', 0, a0, True)
    if a1 is None:
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'safety_controller', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'safety_controller', 1, a1, True)
    if a2 is None:
        v2 = None
    else:
        try:
            v2 = float(a2)
        except ValueError:
            v2 = b.bad_number(el, 'safety_controller', 2, a2, False)
        else:
            if v2 - v2 != 0.0 or '_' in a2:  # nan/inf, or Python-only digit separators
                v2 = b.bad_number(el, 'safety_controller', 2, a2, True)
    if a3 is None:
        v3 = None
    else:
        try:
            v3 = float(a3)
        except ValueError:
            v3 = b.bad_number(el, 'safety_controller', 3, a3, False)
        else:
            if v3 - v3 != 0.0 or '_' in a3:  # nan/inf, or Python-only digit separators
                v3 = b.bad_number(el, 'safety_controller', 3, a3, True)
    return (v0, v1, v2, v3, )


def robot_1_2(b, el):
    get = el.get
    a0 = get('name')
    a1 = get('version')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'robot')
    if a0 is None:
        v0 = None
    else:
        v0 = a0
    if a1 is None:
        v1 = None
    else:
        v1 = a1
    return (v0, v1, )


def link_1_2(b, el):
    get = el.get
    a0 = get('name')
    a1 = get('type')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'link')
    if not a0:
        b.missing(el, 'link', 0)
        v0 = None
    else:
        v0 = a0
    if a1 is None:
        v1 = None
    else:
        v1 = a1
    return (v0, v1, )


def inertial_1_2(b, el):
    n = len(el.attrib)
    if n and (n != 1 or el.get(SRC) is None):
        b.odd_attributes(el, 'inertial')
    return ()


def mass_1_2(b, el):
    get = el.get
    a0 = get('value')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'mass')
    if len(el):
        b.children_of_leaf(el, 'mass')
    if a0 is None:
        b.missing(el, 'mass', 0)
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'mass', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'mass', 0, a0, True)
    return (v0, )


def inertia_1_2(b, el):
    get = el.get
    a0 = get('ixx')
    a1 = get('ixy')
    a2 = get('ixz')
    a3 = get('iyy')
    a4 = get('iyz')
    a5 = get('izz')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None) + (a3 is not None) + (a4 is not None) + (a5 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'inertia')
    if len(el):
        b.children_of_leaf(el, 'inertia')
    if a0 is None:
        b.missing(el, 'inertia', 0)
        v0 = 0.0
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'inertia', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'inertia', 0, a0, True)
    if a1 is None:
        b.missing(el, 'inertia', 1)
        v1 = 0.0
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'inertia', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'inertia', 1, a1, True)
    if a2 is None:
        b.missing(el, 'inertia', 2)
        v2 = 0.0
    else:
        try:
            v2 = float(a2)
        except ValueError:
            v2 = b.bad_number(el, 'inertia', 2, a2, False)
        else:
            if v2 - v2 != 0.0 or '_' in a2:  # nan/inf, or Python-only digit separators
                v2 = b.bad_number(el, 'inertia', 2, a2, True)
    if a3 is None:
        b.missing(el, 'inertia', 3)
        v3 = 0.0
    else:
        try:
            v3 = float(a3)
        except ValueError:
            v3 = b.bad_number(el, 'inertia', 3, a3, False)
        else:
            if v3 - v3 != 0.0 or '_' in a3:  # nan/inf, or Python-only digit separators
                v3 = b.bad_number(el, 'inertia', 3, a3, True)
    if a4 is None:
        b.missing(el, 'inertia', 4)
        v4 = 0.0
    else:
        try:
            v4 = float(a4)
        except ValueError:
            v4 = b.bad_number(el, 'inertia', 4, a4, False)
        else:
            if v4 - v4 != 0.0 or '_' in a4:  # nan/inf, or Python-only digit separators
                v4 = b.bad_number(el, 'inertia', 4, a4, True)
    if a5 is None:
        b.missing(el, 'inertia', 5)
        v5 = 0.0
    else:
        try:
            v5 = float(a5)
        except ValueError:
            v5 = b.bad_number(el, 'inertia', 5, a5, False)
        else:
            if v5 - v5 != 0.0 or '_' in a5:  # nan/inf, or Python-only digit separators
                v5 = b.bad_number(el, 'inertia', 5, a5, True)
    return (v0, v1, v2, v3, v4, v5, )


def visual_1_2(b, el):
    get = el.get
    a0 = get('name')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'visual')
    if a0 is None:
        v0 = None
    else:
        v0 = a0
    return (v0, )


def collision_1_2(b, el):
    get = el.get
    a0 = get('name')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'collision')
    if a0 is None:
        v0 = None
    else:
        v0 = a0
    return (v0, )


def origin_1_2(b, el):
    get = el.get
    a0 = get('xyz')
    a1 = get('rpy')
    a2 = get('quat_xyzw')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'origin')
    if len(el):
        b.children_of_leaf(el, 'origin')
    if a1 is not None and a2 is not None:
        b.exclusive(el, ('rpy', 'quat_xyzw'))
    vectors = b.vectors
    if a0 is None:
        v0 = (0.0, 0.0, 0.0)
    else:
        v0 = vectors.get(a0)
        if v0 is None or len(v0) != 3:
            v0 = b.vector(el, 'origin', 0, a0, 3)
    if a1 is None:
        v1 = (0.0, 0.0, 0.0)
    else:
        v1 = vectors.get(a1)
        if v1 is None or len(v1) != 3:
            v1 = b.vector(el, 'origin', 1, a1, 3)
    if a2 is None:
        v2 = None
    else:
        v2 = vectors.get(a2)
        if v2 is None or len(v2) != 4:
            v2 = b.vector(el, 'origin', 2, a2, 4)
    return (v0, v1, v2, )


def geometry_1_2(b, el):
    n = len(el.attrib)
    if n and (n != 1 or el.get(SRC) is None):
        b.odd_attributes(el, 'geometry')
    return ()


def box_1_2(b, el):
    get = el.get
    a0 = get('size')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'box')
    if len(el):
        b.children_of_leaf(el, 'box')
    vectors = b.vectors
    if a0 is None:
        b.missing(el, 'box', 0)
        v0 = None
    else:
        v0 = vectors.get(a0)
        if v0 is None or len(v0) != 3:
            v0 = b.vector(el, 'box', 0, a0, 3)
    return (v0, )


def cylinder_1_2(b, el):
    get = el.get
    a0 = get('radius')
    a1 = get('length')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'cylinder')
    if len(el):
        b.children_of_leaf(el, 'cylinder')
    if a0 is None:
        b.missing(el, 'cylinder', 0)
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'cylinder', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'cylinder', 0, a0, True)
    if a1 is None:
        b.missing(el, 'cylinder', 1)
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'cylinder', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'cylinder', 1, a1, True)
    return (v0, v1, )


def capsule_1_2(b, el):
    get = el.get
    a0 = get('radius')
    a1 = get('length')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'capsule')
    if len(el):
        b.children_of_leaf(el, 'capsule')
    if a0 is None:
        b.missing(el, 'capsule', 0)
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'capsule', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'capsule', 0, a0, True)
    if a1 is None:
        b.missing(el, 'capsule', 1)
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'capsule', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'capsule', 1, a1, True)
    return (v0, v1, )


def sphere_1_2(b, el):
    get = el.get
    a0 = get('radius')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'sphere')
    if len(el):
        b.children_of_leaf(el, 'sphere')
    if a0 is None:
        b.missing(el, 'sphere', 0)
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'sphere', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'sphere', 0, a0, True)
    return (v0, )


def mesh_1_2(b, el):
    get = el.get
    a0 = get('filename')
    a1 = get('scale')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'mesh')
    if len(el):
        b.children_of_leaf(el, 'mesh')
    vectors = b.vectors
    if not a0:
        b.missing(el, 'mesh', 0)
        v0 = None
    else:
        v0 = a0
    if a1 is None:
        v1 = (1.0, 1.0, 1.0)
    else:
        v1 = vectors.get(a1)
        if v1 is None or len(v1) != 3:
            v1 = b.vector(el, 'mesh', 1, a1, 3)
    return (v0, v1, )


def material_1_2(b, el):
    get = el.get
    a0 = get('name')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'material')
    if a0 is None:
        b.missing(el, 'material', 0)
        v0 = None
    else:
        v0 = a0
    return (v0, )


def color_1_2(b, el):
    get = el.get
    a0 = get('rgba')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'color')
    if len(el):
        b.children_of_leaf(el, 'color')
    vectors = b.vectors
    if a0 is None:
        b.missing(el, 'color', 0)
        v0 = None
    else:
        v0 = vectors.get(a0)
        if v0 is None or len(v0) != 4:
            v0 = b.vector(el, 'color', 0, a0, 4)
    return (v0, )


def texture_1_2(b, el):
    get = el.get
    a0 = get('filename')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'texture')
    if len(el):
        b.children_of_leaf(el, 'texture')
    if a0 is None:
        v0 = None
    else:
        v0 = a0
    return (v0, )


def joint_1_2(b, el):
    get = el.get
    a0 = get('name')
    a1 = get('type')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'joint')
    if not a0:
        b.missing(el, 'joint', 0)
        v0 = None
    else:
        v0 = a0
    if a1 is None:
        b.missing(el, 'joint', 1)
        v1 = None
    else:
        v1 = a1
    return (v0, v1, )


def parent_1_2(b, el):
    get = el.get
    a0 = get('link')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'parent')
    if len(el):
        b.children_of_leaf(el, 'parent')
    if not a0:
        b.missing(el, 'parent', 0)
        v0 = None
    else:
        v0 = a0
    return (v0, )


def child_1_2(b, el):
    get = el.get
    a0 = get('link')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'child')
    if len(el):
        b.children_of_leaf(el, 'child')
    if not a0:
        b.missing(el, 'child', 0)
        v0 = None
    else:
        v0 = a0
    return (v0, )


def axis_1_2(b, el):
    get = el.get
    a0 = get('xyz')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'axis')
    if len(el):
        b.children_of_leaf(el, 'axis')
    vectors = b.vectors
    if a0 is None:
        b.missing(el, 'axis', 0)
        v0 = (0.0, 0.0, 0.0)
    else:
        v0 = vectors.get(a0)
        if v0 is None or len(v0) != 3:
            v0 = b.vector(el, 'axis', 0, a0, 3)
    return (v0, )


def calibration_1_2(b, el):
    get = el.get
    a0 = get('rising')
    a1 = get('falling')
    a2 = get('reference_position')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'calibration')
    if len(el):
        b.children_of_leaf(el, 'calibration')
    if a0 is None:
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'calibration', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'calibration', 0, a0, True)
    if a1 is None:
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'calibration', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'calibration', 1, a1, True)
    if a2 is None:
        v2 = None
    else:
        try:
            v2 = float(a2)
        except ValueError:
            v2 = b.bad_number(el, 'calibration', 2, a2, False)
        else:
            if v2 - v2 != 0.0 or '_' in a2:  # nan/inf, or Python-only digit separators
                v2 = b.bad_number(el, 'calibration', 2, a2, True)
    return (v0, v1, v2, )


def dynamics_1_2(b, el):
    get = el.get
    a0 = get('damping')
    a1 = get('friction')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'dynamics')
    if len(el):
        b.children_of_leaf(el, 'dynamics')
    if a0 is None:
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'dynamics', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'dynamics', 0, a0, True)
    if a1 is None:
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'dynamics', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'dynamics', 1, a1, True)
    return (v0, v1, )


def limit_1_2(b, el):
    get = el.get
    a0 = get('lower')
    a1 = get('upper')
    a2 = get('effort')
    a3 = get('velocity')
    a4 = get('acceleration')
    a5 = get('deceleration')
    a6 = get('jerk')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None) + (a3 is not None) + (a4 is not None) + (a5 is not None) + (a6 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'limit')
    if len(el):
        b.children_of_leaf(el, 'limit')
    if a0 is None:
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'limit', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'limit', 0, a0, True)
    if a1 is None:
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'limit', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'limit', 1, a1, True)
    if a2 is None:
        v2 = None
    else:
        try:
            v2 = float(a2)
        except ValueError:
            v2 = b.bad_number(el, 'limit', 2, a2, False)
        else:
            if v2 - v2 != 0.0 or '_' in a2:  # nan/inf, or Python-only digit separators
                v2 = b.bad_number(el, 'limit', 2, a2, True)
    if a3 is None:
        v3 = None
    else:
        try:
            v3 = float(a3)
        except ValueError:
            v3 = b.bad_number(el, 'limit', 3, a3, False)
        else:
            if v3 - v3 != 0.0 or '_' in a3:  # nan/inf, or Python-only digit separators
                v3 = b.bad_number(el, 'limit', 3, a3, True)
    if a4 is None:
        v4 = None
    else:
        try:
            v4 = float(a4)
        except ValueError:
            v4 = b.bad_number(el, 'limit', 4, a4, False)
        else:
            if v4 - v4 != 0.0 or '_' in a4:  # nan/inf, or Python-only digit separators
                v4 = b.bad_number(el, 'limit', 4, a4, True)
    if a5 is None:
        v5 = None
    else:
        try:
            v5 = float(a5)
        except ValueError:
            v5 = b.bad_number(el, 'limit', 5, a5, False)
        else:
            if v5 - v5 != 0.0 or '_' in a5:  # nan/inf, or Python-only digit separators
                v5 = b.bad_number(el, 'limit', 5, a5, True)
    if a6 is None:
        v6 = None
    else:
        try:
            v6 = float(a6)
        except ValueError:
            v6 = b.bad_number(el, 'limit', 6, a6, False)
        else:
            if v6 - v6 != 0.0 or '_' in a6:  # nan/inf, or Python-only digit separators
                v6 = b.bad_number(el, 'limit', 6, a6, True)
    return (v0, v1, v2, v3, v4, v5, v6, )


def mimic_1_2(b, el):
    get = el.get
    a0 = get('joint')
    a1 = get('multiplier')
    a2 = get('offset')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'mimic')
    if len(el):
        b.children_of_leaf(el, 'mimic')
    if not a0:
        b.missing(el, 'mimic', 0)
        v0 = None
    else:
        v0 = a0
    if a1 is None:
        v1 = 1.0
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'mimic', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'mimic', 1, a1, True)
    if a2 is None:
        v2 = 0.0
    else:
        try:
            v2 = float(a2)
        except ValueError:
            v2 = b.bad_number(el, 'mimic', 2, a2, False)
        else:
            if v2 - v2 != 0.0 or '_' in a2:  # nan/inf, or Python-only digit separators
                v2 = b.bad_number(el, 'mimic', 2, a2, True)
    return (v0, v1, v2, )


def safety_controller_1_2(b, el):
    get = el.get
    a0 = get('soft_lower_limit')
    a1 = get('soft_upper_limit')
    a2 = get('k_position')
    a3 = get('k_velocity')
    n = len(el.attrib)
    if n and n != (k := (a0 is not None) + (a1 is not None) + (a2 is not None) + (a3 is not None)) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker
        b.odd_attributes(el, 'safety_controller')
    if len(el):
        b.children_of_leaf(el, 'safety_controller')
    if a0 is None:
        v0 = None
    else:
        try:
            v0 = float(a0)
        except ValueError:
            v0 = b.bad_number(el, 'safety_controller', 0, a0, False)
        else:
            if v0 - v0 != 0.0 or '_' in a0:  # nan/inf, or Python-only digit separators
                v0 = b.bad_number(el, 'safety_controller', 0, a0, True)
    if a1 is None:
        v1 = None
    else:
        try:
            v1 = float(a1)
        except ValueError:
            v1 = b.bad_number(el, 'safety_controller', 1, a1, False)
        else:
            if v1 - v1 != 0.0 or '_' in a1:  # nan/inf, or Python-only digit separators
                v1 = b.bad_number(el, 'safety_controller', 1, a1, True)
    if a2 is None:
        v2 = None
    else:
        try:
            v2 = float(a2)
        except ValueError:
            v2 = b.bad_number(el, 'safety_controller', 2, a2, False)
        else:
            if v2 - v2 != 0.0 or '_' in a2:  # nan/inf, or Python-only digit separators
                v2 = b.bad_number(el, 'safety_controller', 2, a2, True)
    if a3 is None:
        v3 = None
    else:
        try:
            v3 = float(a3)
        except ValueError:
            v3 = b.bad_number(el, 'safety_controller', 3, a3, False)
        else:
            if v3 - v3 != 0.0 or '_' in a3:  # nan/inf, or Python-only digit separators
                v3 = b.bad_number(el, 'safety_controller', 3, a3, True)
    return (v0, v1, v2, v3, )

READERS = {
    (1, 0): {
        'robot': robot_1_0,
        'link': link_1_0,
        'inertial': inertial_1_0,
        'mass': mass_1_0,
        'inertia': inertia_1_0,
        'visual': visual_1_0,
        'collision': collision_1_0,
        'origin': origin_1_0,
        'geometry': geometry_1_0,
        'box': box_1_0,
        'cylinder': cylinder_1_0,
        'capsule': capsule_1_0,
        'sphere': sphere_1_0,
        'mesh': mesh_1_0,
        'material': material_1_0,
        'color': color_1_0,
        'texture': texture_1_0,
        'joint': joint_1_0,
        'parent': parent_1_0,
        'child': child_1_0,
        'axis': axis_1_0,
        'calibration': calibration_1_0,
        'dynamics': dynamics_1_0,
        'limit': limit_1_0,
        'mimic': mimic_1_0,
        'safety_controller': safety_controller_1_0,
    },
    (1, 1): {
        'robot': robot_1_1,
        'link': link_1_1,
        'inertial': inertial_1_1,
        'mass': mass_1_1,
        'inertia': inertia_1_1,
        'visual': visual_1_1,
        'collision': collision_1_1,
        'origin': origin_1_1,
        'geometry': geometry_1_1,
        'box': box_1_1,
        'cylinder': cylinder_1_1,
        'capsule': capsule_1_1,
        'sphere': sphere_1_1,
        'mesh': mesh_1_1,
        'material': material_1_1,
        'color': color_1_1,
        'texture': texture_1_1,
        'joint': joint_1_1,
        'parent': parent_1_1,
        'child': child_1_1,
        'axis': axis_1_1,
        'calibration': calibration_1_1,
        'dynamics': dynamics_1_1,
        'limit': limit_1_1,
        'mimic': mimic_1_1,
        'safety_controller': safety_controller_1_1,
    },
    (1, 2): {
        'robot': robot_1_2,
        'link': link_1_2,
        'inertial': inertial_1_2,
        'mass': mass_1_2,
        'inertia': inertia_1_2,
        'visual': visual_1_2,
        'collision': collision_1_2,
        'origin': origin_1_2,
        'geometry': geometry_1_2,
        'box': box_1_2,
        'cylinder': cylinder_1_2,
        'capsule': capsule_1_2,
        'sphere': sphere_1_2,
        'mesh': mesh_1_2,
        'material': material_1_2,
        'color': color_1_2,
        'texture': texture_1_2,
        'joint': joint_1_2,
        'parent': parent_1_2,
        'child': child_1_2,
        'axis': axis_1_2,
        'calibration': calibration_1_2,
        'dynamics': dynamics_1_2,
        'limit': limit_1_2,
        'mimic': mimic_1_2,
        'safety_controller': safety_controller_1_2,
    },
}
