"""mrsim.Node in a signed session: the key files and signing of the C++
programs (process tests, own LCM ports)."""

import os
import subprocess

import pytest

import mrsim
from conftest import lcm_url, program, wait_until


def write_snake(tmp_path):
    path = str(tmp_path / "snake.xml")
    mrsim.Scenario.chain(modules=6, pattern="pitch-yaw").save(path)
    return path


def keygen(path):
    subprocess.run([program("mrsim"), "keygen", path], check=True,
                   stdout=subprocess.DEVNULL)
    return path


def next_status(node, accept=lambda s: True, timeout=20):
    """The next simulator status for which accept(status) holds."""
    for status in node.messages("sim_status", timeout=timeout):
        if accept(status):
            return status
    raise AssertionError("no such simulator status within %s s" % timeout)


def test_signed_node_steers_the_simulator_and_an_unkeyed_one_is_ignored(
        tmp_path, children, monkeypatch):
    monkeypatch.delenv("MRSIM_KEY_FILE", raising=False)
    key = keygen(str(tmp_path / "lab.key"))
    url = lcm_url(7566)
    sim = children.start([program("mrsim-sim"), write_snake(tmp_path),
                          "--lcm-url", url, "--key-file", key],
                         str(tmp_path / "sim.log"))
    node = mrsim.Node(url=url, key_file=key, name="signed")
    assert node.signing

    # States arrive, checked and with the trailer cut off.
    state = node.next_state("snake", timeout=30)
    assert state.robot == "snake" and len(state.joint_angle) > 0
    assert node.auth_counts()["accepted"] > 0

    # Its joint commands are applied.
    def applied():
        node.send_targets("snake", [0.2] * len(state.joint_angle))
        return next_status(node).commands_applied > 0
    wait_until(applied, 30, "the signed joint commands to be applied")

    # A node without the key reads the signed statuses, but its pause is
    # dropped: the simulator says so and keeps running.
    intruder = mrsim.Node(url=url, name="intruder")
    assert not intruder.signing
    assert intruder.auth_counts() == {"accepted": 0, "unsigned": 0,
                                      "forged": 0, "replayed": 0}
    next_status(intruder)
    intruder.pause(wait=False)
    wait_until(lambda: intruder.spin_once(0.1) >= 0 and
               "unsigned message on MRSIM_SIM_CONTROL" in sim.output(),
               30, "mrsim-sim to drop the unsigned pause")
    first = next_status(intruder)
    later = next_status(intruder, lambda s: s.time > first.time)
    assert first.mode == later.mode == "running"

    # What the intruder, or a node with another key, sends to the signed
    # node is counted and dropped.
    forger = mrsim.Node(url=url, name="forger",
                        key_file=keygen(str(tmp_path / "other.key")))
    state.seq += 1000

    def dropped():
        intruder.publish_state(state)
        forger.publish_state(state)
        node.spin_once(0.1)
        counts = node.auth_counts()
        return counts["unsigned"] > 0 and counts["forged"] > 0
    wait_until(dropped, 30, "the signed node to drop the foreign states")
    assert node.next_state("snake", timeout=10).seq < state.seq

    # The signed node's pause is applied.
    assert node.pause(timeout=20).mode == "paused"
    node.quit(timeout=20)
    assert sim.wait(30) == 0, sim.output()


def test_key_file_falls_back_to_the_environment(tmp_path, monkeypatch):
    key = keygen(str(tmp_path / "env.key"))
    monkeypatch.setenv("MRSIM_KEY_FILE", key)
    assert mrsim.Node(url=lcm_url(7567)).signing
    missing = str(tmp_path / "gone.key")
    monkeypatch.setenv("MRSIM_KEY_FILE", missing)
    with pytest.raises(mrsim.KeyFileError) as e:
        mrsim.Node(url=lcm_url(7567))
    assert e.value.path == missing and missing in str(e.value)


def test_unusable_key_files_raise_naming_the_file(tmp_path, monkeypatch):
    monkeypatch.delenv("MRSIM_KEY_FILE", raising=False)
    readable = keygen(str(tmp_path / "readable.key"))
    os.chmod(readable, 0o644)
    garbled = str(tmp_path / "garbled.key")
    with open(garbled, "w") as f:
        f.write("not a key\n")
    os.chmod(garbled, 0o600)
    for path in (str(tmp_path / "missing.key"), readable, garbled):
        with pytest.raises(ValueError) as e:
            mrsim.Node(url=lcm_url(7567), key_file=path)
        assert isinstance(e.value, mrsim.KeyFileError)
        assert path in str(e.value) and e.value.path == path
