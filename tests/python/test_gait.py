"""Gaits from Python: presets, parameters, targets and controllers."""

import numpy as np
import pytest

import mrsim


def test_presets_and_parameters():
    assert "forward" in mrsim.gait_presets()
    g = mrsim.Gait("forward")
    assert g.kind == "linear"
    assert set(mrsim.gait_parameter_names()) <= set(g.parameters)
    faster = g.with_parameters(T=2.0)
    assert faster.parameters["T"] == 2.0
    assert g.parameters["T"] != 2.0


def test_bad_gaits_raise():
    with pytest.raises(mrsim.GaitError):
        mrsim.Gait("moonwalk")
    with pytest.raises(ValueError):
        mrsim.Gait.from_parameters({"T": 0.0})
    with pytest.raises(KeyError):
        mrsim.Gait("forward").with_parameters(speed=3)
    with pytest.raises(ValueError):
        mrsim.Gait("forward").set_motion("jump")
    with pytest.raises(ValueError):
        mrsim.Gait("forward").targets(0.0)
    with pytest.raises(ValueError):
        mrsim.Gait("forward").targets(float("nan"), joint_count=5)


def test_gait_file_round_trip(tmp_path):
    g = mrsim.Gait.from_parameters({"A_pitch": 0.7, "phi_pitch": 1.2, "T": 3})
    path = str(tmp_path / "mine.xml")
    g.save(path)
    again = mrsim.Gait.load(path)
    assert again.parameters == g.parameters


def test_python_controller_equals_the_gait_run_in_cpp():
    scenario = mrsim.Scenario.chain(modules=6, pattern="pitch-yaw",
                                    friction=0.8)
    a = mrsim.Simulation(scenario)
    a.set_controller(mrsim.Gait("turn-sharp"))
    a.run(1.0)

    b = mrsim.Simulation(scenario)
    gait = mrsim.Gait("turn-sharp")
    b.set_controller(lambda t, state: gait.targets(t, state))
    b.run(1.0)
    assert a.time == b.time
    sa, sb = a.state(), b.state()
    assert np.array_equal(sa.joint_angle, sb.joint_angle)
    assert np.array_equal(sa.module_pose, sb.module_pose)
    assert np.abs(sa.joint_angle).max() > 0.1


def test_episode_scores_a_gait_deterministically():
    scenario = mrsim.Scenario.chain(modules=6, pattern="pitch-yaw",
                                    friction=0.8)
    r1 = mrsim.run_episode(scenario, mrsim.Gait("forward"), duration=2.0)
    r2 = mrsim.run_episode(scenario, mrsim.Gait("forward"), duration=2.0)
    assert r1 == r2
    assert not r1["failed"]
    assert set(r1) >= {"fitness", "distance", "speed", "energy", "drift",
                       "fell"}
    with pytest.raises(ValueError):
        mrsim.run_episode(scenario, mrsim.Gait("forward"), duration=-1)


def test_unknown_axes_warn_and_default_to_pitch_yaw():
    g = mrsim.Gait("forward")
    explicit = mrsim.Gait("forward", axes="pitch-yaw")
    with pytest.warns(UserWarning, match="pitch-yaw"):
        g.targets(0.0, joint_count=4)
    explicit.targets(0.0, joint_count=4)
    for t in (0.5, 1.0):
        a = g.targets(t, joint_count=4)
        b = explicit.targets(t, joint_count=4)
    assert np.array_equal(a, b)
    assert np.abs(a).max() > 0
