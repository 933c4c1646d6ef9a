"""mrsim.Node's rules without sockets: LCM's in-process memq:// provider."""

import numpy as np
import pytest

import mrsim


@pytest.fixture
def node():
    return mrsim.Node(url="memq://", name="py")


@pytest.fixture
def state():
    return mrsim.Simulation(mrsim.Scenario.chain(modules=3)).state()


def publish(node, state, seq):
    state.seq = seq
    node.publish_state(state)


def test_each_state_is_handed_once_and_older_ones_are_dropped(node, state):
    node.subscribe("state", "snake")
    for seq in (0, 0, 1, 0, 2):
        publish(node, state, seq)
    got = list(node.states("snake", timeout=0.05))
    assert [s.seq for s in got] == [0, 1, 2]
    assert np.array_equal(got[0].joint_angle, state.joint_angle)


def test_a_resent_state_is_answered_again_with_the_same_command(node, state):
    commands = node._subscribe("MRSIM_COMMAND_snake", "joint_command")
    node.subscribe("state", "snake")
    publish(node, state, 7)
    s = node.next_state("snake", timeout=1)
    node.send_targets("snake", [0.1, 0.2, 0.3], s)
    publish(node, state, 7)  # the simulator waits for it: sends it again
    assert list(node.states("snake", timeout=0.05)) == []
    node.spin_once(0.05)
    sent = [node._queues[commands].popleft() for _ in range(2)]
    assert [c.state_seq for c in sent] == [7, 7]
    assert [c.seq for c in sent] == [1, 1]
    assert all(c.sender == "py" and c.robot == "snake" for c in sent)
    assert np.array_equal(sent[1].target, [0.1, 0.2, 0.3])
    assert node.repeated == 1


def test_messages_that_do_not_decode_are_counted_and_dropped(node, state):
    node.subscribe("state", "snake")
    node._lcm.publish_raw("MRSIM_STATE_snake", b"\x00" * 12)
    node._lcm.publish_raw("MRSIM_STATE_snake", b"")
    publish(node, state, 0)
    assert [s.seq for s in node.states("snake", timeout=0.05)] == [0]
    assert node.malformed == 2


def test_requests_carry_the_senders_fields(node):
    controls = node._subscribe("MRSIM_SIM_CONTROL", "sim_control")
    gaits = node._subscribe("MRSIM_GAIT_snake", "gait_command")
    node.detach("snake", "snake/lock1", wait=False)
    node.gait_command("snake", motion="turn-left", strength=0.5,
                      direction=(1.0, -0.5), wait=False)
    node.spin_once(0.05)
    c = node._queues[controls].popleft()
    assert (c.command, c.robot, c.lock, c.sender) == (
        mrsim.node.DETACH, "snake", "snake/lock1", "py")
    g = node._queues[gaits].popleft()
    assert (g.motion, g.strength, g.has_direction, g.forward, g.turn) == (
        "turn-left", 0.5, True, 1.0, -0.5)
    with pytest.raises(ValueError):
        node.gait_command("snake", parameters=[1, 2], wait=False)
