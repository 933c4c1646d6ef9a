"""Simulation from Python: stepping, targets, locks, checkpoints, errors."""

import threading

import numpy as np
import pytest

import mrsim
from conftest import source


@pytest.fixture
def sim():
    return mrsim.Simulation(mrsim.Scenario.chain(modules=5, pattern="pitch-yaw",
                                                 friction=0.8))


def test_step_advances_time_by_whole_timesteps(sim):
    assert sim.time == 0.0
    sim.step(10)
    assert sim.time == pytest.approx(10 * sim.timestep)
    assert sim.robots == ["snake"]


def test_targets_move_the_joints_within_limits(sim):
    sim.set_joint_targets([0.5, -0.5, 0.5, -0.5, 0.5])
    sim.step(500)
    angles = sim.state().joint_angle
    assert np.allclose(angles, [0.5, -0.5, 0.5, -0.5, 0.5], atol=0.05)
    assert np.array_equal(sim.joint_targets(), [0.5, -0.5, 0.5, -0.5, 0.5])
    sim.set_joint_targets([3.0] * 5)  # clamped to the limits
    lo, hi = sim.joint_limits()
    assert np.array_equal(sim.joint_targets(), hi)


def test_bad_targets_and_robots_raise(sim):
    with pytest.raises(ValueError):
        sim.set_joint_targets([0.0] * 4)
    with pytest.raises(ValueError):
        sim.set_joint_targets([float("nan")] * 5)
    with pytest.raises(IndexError):
        sim.state(3)
    with pytest.raises(KeyError):
        sim.state("worm")
    with pytest.raises(ValueError):
        sim.step(-1)
    with pytest.raises(TypeError):
        sim.set_controller(42)
    with pytest.raises(ValueError):
        sim.set_controller(mrsim.Gait("forward"), period=0.003)


def test_bad_scenario_path_raises_scenario_error(tmp_path):
    with pytest.raises(mrsim.ScenarioError):
        mrsim.Simulation(str(tmp_path / "missing.xml"))


def test_detach_and_attach_a_lock(sim):
    locks = dict(sim.locks())
    name = next(iter(locks))
    assert locks[name] is True
    sim.detach(name)
    assert dict(sim.locks())[name] is False
    assert dict(sim.state().locks)[name] is False
    sim.step(10)
    sim.attach(name)
    assert dict(sim.locks())[name] is True
    with pytest.raises(mrsim.PhysicsError):
        sim.detach("no-such-lock")


def run_fixed(sim, periods):
    for k in range(periods):
        sim.set_joint_targets([((k + j) % 5 - 2) * 0.2 for j in range(5)])
        sim.step(5)


def test_checkpoint_resumes_bit_for_bit(sim, tmp_path):
    run_fixed(sim, 40)
    path = str(tmp_path / "run.checkpoint")
    sim.save_checkpoint(path)
    run_fixed(sim, 30)
    want = sim.state()
    again = mrsim.Simulation.load_checkpoint(path)
    assert again.time == pytest.approx(40 * 5 * sim.timestep)
    run_fixed(again, 30)
    got = again.state()
    assert got.time == want.time
    assert np.array_equal(got.joint_angle, want.joint_angle)
    assert np.array_equal(got.module_pose, want.module_pose)
    # The in-memory forms too.
    text = again.checkpoint_string()
    assert mrsim.Simulation.from_checkpoint_string(text).time == got.time
    raw = again.save_state()
    again.step(20)
    again.load_state(raw)
    assert again.time == got.time


def test_bad_checkpoints_raise_checkpoint_error(tmp_path):
    bad = tmp_path / "bad.checkpoint"
    bad.write_text("mrsim-checkpoint 1\nstate: !!!\n")
    with pytest.raises(mrsim.CheckpointError):
        mrsim.Simulation.load_checkpoint(str(bad))
    with pytest.raises(mrsim.CheckpointError):
        mrsim.Simulation.load_checkpoint(str(tmp_path / "none"))


def test_load_state_of_another_scenario_raises(sim):
    other = mrsim.Simulation(mrsim.Scenario.chain(modules=3))
    with pytest.raises(ValueError):
        sim.load_state(other.save_state())
    with pytest.raises(ValueError):
        sim.load_state(b"garbage")


def test_step_lets_other_threads_run(sim):
    """The GIL is released while stepping: this thread counts meanwhile."""
    inside = threading.Event()
    done = threading.Event()
    count = 0

    def worker():
        inside.set()
        sim.step(20000)
        done.set()

    t = threading.Thread(target=worker)
    t.start()
    inside.wait()
    while not done.is_set():
        count += 1
    t.join()
    assert count > 1000


def _with_loose_module(scenario):
    """The scenario with a loose sensor module 1 m beside the robot, 0.2 m
    up."""
    xml = scenario.to_xml()
    end = xml.rindex("</")
    loose = ("<sensorModules><SensorModule><guid>eye</guid>"
             "<position><x>0</x><y>1</y><z>0.2</z></position>"
             "</SensorModule></sensorModules>")
    return mrsim.Scenario.from_xml(xml[:end] + loose + xml[end:])


def test_loose_state_is_where_the_physics_moved_the_loose_parts(sim):
    assert sim.loose_state() is None  # no loose parts
    loose = mrsim.Simulation(_with_loose_module(
        mrsim.Scenario.chain(modules=3)))
    start = loose.loose_state()
    assert start.robot == "loose"
    assert start.sensor_pose[0][2] == pytest.approx(0.2)
    loose.step(1000)
    assert loose.loose_state().sensor_pose[0][2] == pytest.approx(
        0.025, abs=0.005)


def _with_loose_arm(scenario, servo):
    """A static loose base 1 m beside the robot and an arm on a loose hinge
    about the vertical, driven by a servo when `servo`."""
    xml = scenario.to_xml()
    end = xml.rindex("</")
    up = ("<quatRotation><x>0.7071067811865476</x><y>0</y><z>0</z>"
          "<w>0.7071067811865476</w></quatRotation>")
    frames = "".join(
        f"<Frame><guid>{guid}</guid><position><x>{x}</x><y>1</y>"
        f"<z>0.3</z></position>{up}<isStatic>{static}</isStatic></Frame>"
        for guid, x, static in (("base", 0, "true"), ("arm", 0.05, "false")))
    joint = ("<joints><Joint><guid>arm hinge</guid>"
             "<leftFrameGuid>base</leftFrameGuid>"
             "<rightFrameGuid>arm</rightFrameGuid><type>Hinge</type>"
             f"<servo>{'true' if servo else 'false'}</servo>"
             "</Joint></joints>")
    return mrsim.Scenario.from_xml(
        xml[:end] + "<frames>" + frames + "</frames>" + joint + xml[end:])


def test_loose_servo_takes_its_targets(sim):
    assert sim.loose_servo_count == 0
    arm = mrsim.Simulation(_with_loose_arm(
        mrsim.Scenario.chain(modules=3), True))
    assert arm.loose_servo_count == 1
    arm.set_loose_targets([0.5])
    assert list(arm.loose_targets()) == [0.5]
    arm.step(1000)
    assert arm.loose_state().joint_angle[0] == pytest.approx(0.5, abs=0.01)
    with pytest.raises(ValueError):
        arm.set_loose_targets([0.1, 0.2])
    passive = mrsim.Simulation(_with_loose_arm(
        mrsim.Scenario.chain(modules=3), False))
    with pytest.raises(ValueError):
        passive.set_loose_targets([0.5])
