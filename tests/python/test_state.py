"""The State arrays are the C++ state bit for bit."""

import os
import subprocess

import numpy as np

import mrsim
from conftest import BINARY_DIR, source

REFERENCE = os.path.join(BINARY_DIR, "tests", "python", "python_state_reference")


def reference_state(scenario, periods):
    out = subprocess.run([REFERENCE, scenario, str(periods)], check=True,
                         capture_output=True, text=True).stdout
    values = {}
    for line in out.splitlines():
        name, index, value = line.split()
        values.setdefault(name, {})[int(index)] = float.fromhex(value)
    return {k: np.array([v[i] for i in sorted(v)]) for k, v in values.items()}


def test_state_arrays_equal_the_cpp_state_bit_for_bit():
    scenario = source("scenarios/case_study.xml")
    periods = 37
    sim = mrsim.Simulation(scenario)
    n = sim.joint_count()
    for k in range(periods):
        sim.set_joint_targets([((k * 7 + j * 3) % 11 - 5) * 0.1
                               for j in range(n)])
        sim.step(5)
    s = sim.state()
    want = reference_state(scenario, periods)
    assert s.time == want["time"][0]
    for name in ("joint_angle", "joint_speed", "joint_torque", "com",
                 "com_velocity", "orientation"):
        assert np.array_equal(getattr(s, name), want[name]), name
    for name in ("joint_pose", "module_pose", "frame_pose", "sensor_pose"):
        assert np.array_equal(getattr(s, name).ravel(), want[name]), name
    assert np.array_equal(s.sensor_force, want["sensor_force"], equal_nan=True)
    for i, d in enumerate(s.sensor_distance):
        assert np.array_equal(d, want.get("sensor_distance%d" % i,
                                          np.array([]))), i
    assert s.heading == want["heading"][0]
    assert s.joint_speed.any(), "the robot moved"


def test_columns_are_the_loggers_csv_row():
    sim = mrsim.Simulation(source("scenarios/case_study.xml"))
    sim.step(50)
    s = sim.state()
    c = s.columns()
    names = list(c)
    assert names[:4] == ["time", "seq", "robot", "sim_time"]
    assert c["robot"] == "case_study"
    assert c["sim_time"] == s.time
    assert c["module2.joint.angle"] == s.joint_angle[2]
    assert c["module4.qz"] == s.module_pose[4, 6]
    assert c["module1.frame1.y"] == s.frame_pose[3, 1]
    assert c["sensor_module0.force"] == s.sensor_force[0]
    assert c["com_velocity.z"] == s.com_velocity[2]
    assert c["orientation.qw"] == s.orientation[0]
    assert c["orientation.qz"] == s.orientation[3]
    assert c["heading"] == s.heading
    assert any(n.startswith("lock.") and n.endswith(".attached") for n in names)
    assert mrsim.POSE_FIELDS == ("x", "y", "z", "qw", "qx", "qy", "qz")


def test_arrays_hold_every_part():
    sim = mrsim.Simulation(source("scenarios/snake11.xml"))
    a = sim.state().arrays()
    assert a["joint_angle"].shape == (11,)
    assert a["module_pose"].shape == (11, 7)
    assert a["frame_pose"].shape == (22, 7)
    assert a["com"].shape == (3,)
