"""Every field of every .lcm message reaches Python through mrsim.Node.

Each message type is published with every field set (non-zero numbers,
non-empty strings and arrays, nested structs filled) on LCM's in-process
memq:// and read back field by field. The fields come from the .lcm files
themselves (lcmtypes/wire_check_gen.py's parser), so a field added to a
.lcm file that does not reach Python fails here.
"""

import glob
import os
import sys

import numpy as np
import pytest

import mrsim
from mrsim import _core

SOURCE = os.environ.get(
    "MRSIM_SOURCE_DIR",
    os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(SOURCE, "lcmtypes"))
import wire_check_gen  # noqa: E402

LCM_FILES = sorted(glob.glob(os.path.join(SOURCE, "lcmtypes", "mrsim",
                                          "*.lcm")))
STRUCTS = {s.name: s for f in LCM_FILES for s in wire_check_gen.parse(f)}
TYPES = _core.message_types()

INTEGER_RANGE = {"int8_t": 127, "int16_t": 32767, "int32_t": 2**31 - 1,
                 "int64_t": 2**63 - 1, "byte": 255}


def label(type_name, value):
    """An enum field in words: the lower-case name of its const."""
    names = [n for n, v in TYPES[type_name]["consts"].items() if v == value]
    return names[0].lower() if names else "unknown"


# Fields whose Python value has a meaning beyond the wire value: how the
# value published reads. Every other field must read back as published.
MEANING = {
    ("sim_status_t", "mode"): lambda v: label("sim_status_t", v),
    ("gait_status_t", "command_result"): lambda v: label("gait_status_t", v),
    ("scene_state_t", "poses"): lambda poses: np.array(
        [list(p["position"]) + list(p["orientation"]) for p in poses]),
}


def length_members(type_name):
    return {d for f in TYPES[type_name]["fields"] for d in f["dims"]
            if isinstance(d, str)}


class Values:
    """Distinct, non-zero values for every field, within its limits."""

    def __init__(self):
        self.n = 0

    def scalar(self, type_name, field):
        self.n += 1
        if type_name == "boolean":
            return True
        if type_name in ("double", "float"):
            return self.n + 0.25
        if type_name == "string":
            text = "%s-%d" % (field["name"], self.n)
            return text[:field["max"]] if field["max"] else text
        if type_name in INTEGER_RANGE:
            return 1 + self.n % min(INTEGER_RANGE[type_name], 120)
        return self.message(type_name)

    def array(self, type_name, field, dims):
        if not dims:
            return self.scalar(type_name, field)
        count = dims[0] if isinstance(dims[0], int) else 2
        return [self.array(type_name, field, dims[1:]) for _ in range(count)]

    def message(self, type_name):
        lengths = length_members(type_name)
        fields = {f["name"]: self.array(f["type"], f, list(f["dims"]))
                  for f in TYPES[type_name]["fields"]
                  if f["name"] not in lengths}
        fields.update(VALID.get(type_name, {}))
        return fields


# Fields whose values must agree among them for a receiver to take the
# message (a picture's size, encoding and bytes: malformed ones are
# dropped, test_camera.py).
VALID = {
    "camera_image_t": {"width": 16, "height": 16, "encoding": "rgb8",
                       "data": [(7 * i) % 256 for i in range(16 * 16 * 3)]},
}


def check_value(got, sent, field_type, where):
    if isinstance(sent, dict):
        check_message(got, sent, field_type, where)
    elif isinstance(sent, list) and sent and isinstance(sent[0], dict):
        assert len(got) == len(sent), where
        for i, (g, s) in enumerate(zip(got, sent)):
            check_message(g, s, field_type, "%s[%d]" % (where, i))
    elif field_type == "byte" and isinstance(sent, list):
        assert got == bytes(sent), where
    elif isinstance(sent, list) and sent and isinstance(sent[0], str):
        assert list(got) == sent, where
    elif isinstance(sent, list):
        assert isinstance(got, np.ndarray), where
        assert np.array_equal(got, np.array(sent)), where
    else:
        assert got == sent and type(got) is type(sent), (where, got, sent)


def check_message(got, sent, type_name, where=None):
    """Every field of type_name in `got` (a Message) as `sent` gave it."""
    where = where or type_name
    fields = TYPES[type_name]["fields"]
    assert isinstance(got, mrsim.Message), where
    assert set(vars(got)) >= {f["name"] for f in fields}, where
    for f in fields:
        name, value = f["name"], getattr(got, f["name"])
        at = "%s.%s" % (where, name)
        if name in length_members(type_name):
            sized = [g["name"] for g in fields if name in g["dims"]]
            assert value == len(sent[sized[0]]), at
        elif (type_name, name) in MEANING:
            expected = MEANING[(type_name, name)](sent[name])
            if isinstance(expected, np.ndarray):
                assert np.array_equal(value, expected), at
            else:
                assert value == expected, at
        else:
            check_value(value, sent[name], f["type"], at)


@pytest.fixture
def node():
    return mrsim.Node(url="memq://", name="py")


def test_the_bindings_know_every_message_type_and_field_of_the_lcm_files():
    assert sorted(TYPES) == sorted(STRUCTS)
    for name, struct in STRUCTS.items():
        got = [(f["name"], f["type"], list(f["dims"]), f["max"])
               for f in TYPES[name]["fields"]]
        want = [(m.name, m.type.rsplit(".", 1)[-1], m.dims, m.limit)
                for m in struct.members]
        assert got == want, name


@pytest.mark.parametrize("type_name", sorted(STRUCTS))
def test_every_field_of_every_message_type_reads_back(node, type_name):
    channel = "TEST_" + type_name
    node.listen(channel, type_name)
    sent = Values().message(type_name)
    node.publish(channel, type_name, sent)
    got = node.next_on(channel, type_name, timeout=1)
    check_message(got, sent, type_name)


@pytest.mark.parametrize("what", sorted(mrsim.node.CHANNELS))
def test_every_channel_of_the_table_carries_its_type(node, what):
    spec = mrsim.node.CHANNELS[what]
    robot = {"robot": "snake", "shard": "0a", "": None}[spec["suffix"]]
    channel = node.channel(what, robot)
    if what == "state":  # as fields; State objects: the test below
        node.listen(channel, spec["type"])
    else:
        node.subscribe(what, robot)
    sent = Values().message(spec["type"])
    node.send(what, sent, robot)
    if what == "state":
        got = node.next_on(channel, spec["type"], timeout=1)
    else:
        got = node.next_message(what, robot, timeout=1)
    check_message(got, sent, spec["type"])


def test_channels_are_the_lcm_files_patterns_with_their_prefixes(node):
    prefixed = mrsim.Node(url="memq://", prefix="LAB")
    assert node.channel("state", "snake") == "MRSIM_STATE_snake"
    assert prefixed.channel("gait_status", "s") == "LAB_GAIT_STATUS_s"
    assert prefixed.channel("sim_control") == "LAB_SIM_CONTROL"
    assert prefixed.channel("run") == "MRSIM_OPT_RUN"  # the farm's prefix
    assert node.channel("job", "0a") == "MRSIM_OPT_JOB_0a"
    assert mrsim.node.DEFAULT_PREFIX == "MRSIM"
    with pytest.raises(ValueError, match="robot"):
        node.channel("command")
    for spec in _core.channels():
        path = os.path.join(SOURCE, "lcmtypes", "mrsim",
                            spec["type"] + ".lcm")
        with open(path, encoding="utf-8") as f:
            assert "// channel: " + spec["pattern"] in f.read()


def test_the_docs_name_every_channel_of_the_table():
    def read(name):
        with open(os.path.join(SOURCE, name), encoding="utf-8") as f:
            return f.read()
    readme, farm = read("README.md"), read("docs/optimizer.md")
    for spec in _core.channels():
        if spec["default_prefix"] == mrsim.node.DEFAULT_PREFIX:
            name = spec["pattern"].replace("<prefix>", spec["default_prefix"])
            assert "`%s`" % name in readme, name  # README's channel table
        else:  # docs/optimizer.md, "Farm"
            assert ("`%s" % spec["infix"] in farm or
                    spec["default_prefix"] + spec["infix"] in farm), spec


def test_consts_of_the_lcm_files_are_exposed():
    assert TYPES["sim_control_t"]["consts"]["DETACH"] == mrsim.node.DETACH
    assert TYPES["gait_status_t"]["consts"] == {
        "NONE": 0, "APPLIED": 1, "REJECTED": 2, "QUEUED": 3}


def test_a_state_subscription_still_hands_state_objects(node):
    node.subscribe("state", "snake")
    sent = Values().message("robot_state_t")
    node.send("state", sent, "snake")
    state = node.next_state("snake", timeout=1)
    assert isinstance(state, mrsim.State)
    assert state.seq == sent["seq"]


@pytest.mark.parametrize("fields, error, words", [
    ({"robot": 3}, TypeError, "joint_command_t.robot: expected str"),
    ({"robot": "x" * 257}, ValueError, "joint_command_t.robot: 257 bytes"),
    ({"target": [0.0] * 4097}, ValueError, "joint_command_t.target: 4097"),
    ({"num_joints": 3, "target": [1.0]}, ValueError, "num_joints: 3"),
    ({"seq": 1.5}, TypeError, "joint_command_t.seq: expected an integer"),
    ({"targets": [1.0]}, ValueError, "no field 'targets'"),
])
def test_a_field_receivers_would_drop_is_refused_naming_it(node, fields,
                                                           error, words):
    with pytest.raises(error, match=words.replace("[", r"\[")):
        node.publish("X", "joint_command_t", fields)


def test_a_fixed_array_of_the_wrong_size_and_a_nested_field_are_named(node):
    with pytest.raises(ValueError, match=r"pose_t.position: expected 3"):
        node.publish("X", "pose_t", {"position": [1.0, 2.0]})
    with pytest.raises(TypeError,
                       match=r"robot_state_t.joints\[1\].world.position\[0\]"):
        node.publish("X", "robot_state_t", {"joints": [
            {}, {"world": {"position": ["a", 0, 0]}}]})
