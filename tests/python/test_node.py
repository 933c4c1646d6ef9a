"""mrsim.Node against the real programs (process tests, own LCM ports)."""

import numpy as np
import pytest

import mrsim
from conftest import lcm_url, program


def write_snake(tmp_path):
    path = str(tmp_path / "snake.xml")
    mrsim.Scenario.chain(modules=6, pattern="pitch-yaw",
                         friction=0.8).save(path)
    return path


def sim_args(scenario, url, controller, checkpoint, delay=0):
    return [program("mrsim-sim"), scenario, "--lcm-url", url, "--clock",
            "lockstep", "--controllers", controller, "--duration", "2",
            "--actuation-delay", str(delay), "--lockstep-timeout", "30",
            "--checkpoint-on-exit", checkpoint]


@pytest.mark.parametrize("delay", [0, 1])
def test_python_controller_in_lockstep_equals_mrsim_gait(tmp_path, children,
                                                         delay):
    scenario = write_snake(tmp_path)
    url = lcm_url(7560 + delay)

    # mrsim-gait drives the robot.
    gait_run = str(tmp_path / "gait.checkpoint")
    children.start([program("mrsim-gait"), "--robot", "snake", "--scenario",
                    scenario, "--gait", "turn-sharp", "--lcm-url", url,
                    "--name", "g", "--exit-with-sim"],
                   str(tmp_path / "gait.log"))
    sim = children.start(sim_args(scenario, url, "g", gait_run, delay),
                         str(tmp_path / "sim_gait.log"))
    assert sim.wait(120) == 0, sim.output()

    # The same gait from Python.
    py_run = str(tmp_path / "python.checkpoint")
    node = mrsim.Node(url=url, name="py")
    gait = mrsim.Gait("turn-sharp", axes="pitch-yaw")
    sim = children.start(sim_args(scenario, url, "py", py_run, delay),
                         str(tmp_path / "sim_py.log"))
    first = node.next_state("snake", timeout=60)
    node.send_targets("snake", gait.targets(first.time, first), first)
    received = [first]
    for state in node.states("snake", timeout=5):
        received.append(state)
        node.send_targets("snake", gait.targets(state.time, state), state)
    assert sim.wait(60) == 0, sim.output()
    assert len(received) >= 200
    assert [s.seq for s in received] == list(range(len(received)))

    a = mrsim.Simulation.load_checkpoint(gait_run)
    b = mrsim.Simulation.load_checkpoint(py_run)
    assert a.time == b.time == pytest.approx(2.0)
    assert a.save_state() == b.save_state()
    assert np.array_equal(a.state().joint_angle, b.state().joint_angle)

    if delay == 0:
        # Strict lockstep is also the in-process run, period by period.
        local = mrsim.Simulation(scenario)
        local.set_controller(mrsim.Gait("turn-sharp"))
        for s in received[:50]:
            mine = local.state()
            assert mine.time == s.time
            assert np.array_equal(mine.joint_angle, s.joint_angle)
            assert np.array_equal(mine.module_pose, s.module_pose)
            local.run(0.01)


def test_controls_are_acknowledged_and_refusals_raise(tmp_path, children):
    scenario = write_snake(tmp_path)
    url = lcm_url(7562)
    sim = children.start([program("mrsim-sim"), scenario, "--lcm-url", url,
                          "--paused"], str(tmp_path / "sim.log"))
    node = mrsim.Node(url=url, name="ctl")
    statuses, states = [], []
    node.on_sim_status(statuses.append)
    node.on_state("snake", states.append)
    status = node.pause(timeout=20)
    assert status.mode == "paused"
    node.step(3)
    state = node.next_state("snake", timeout=10)
    assert state.robot == "snake"
    assert statuses and statuses[-1].mode == "paused"
    assert states and states[0] is state  # callbacks see what iterators get
    with pytest.raises(mrsim.ControlError):
        node.detach("snake", "no-such-lock")
    with pytest.raises(mrsim.ControlError):
        node.load_checkpoint(str(tmp_path / "missing.checkpoint"))
    node.quit()
    assert sim.wait(30) == 0, sim.output()


def test_bad_node_arguments_raise():
    with pytest.raises(mrsim.KeyFileError):
        mrsim.Node(url=lcm_url(7563), key_file="no-such.key")
    with pytest.raises(ValueError):
        mrsim.Node(url=lcm_url(7563), prefix="")
    node = mrsim.Node(url=lcm_url(7563))
    with pytest.raises(TimeoutError):
        node.next_state("nobody", timeout=0.2)
    with pytest.raises(ValueError):
        node.subscribe("weather")
    with pytest.raises(ValueError):
        node.subscribe("state")
    assert list(node.states("nobody", timeout=0.1)) == []
