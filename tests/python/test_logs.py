"""Logs into dicts of numpy arrays: CSV folders and lcm-logger logs."""

import os
import signal

import numpy as np
import pytest

import mrsim
from conftest import lcm_url, program, wait_until


def test_csv_folder_reads_columns_and_joins_parts(tmp_path):
    (tmp_path / "MRSIM_STATE_snake.csv").write_text(
        "time,seq,robot,com.x\n0.01,0,snake,1.5\n0.02,1,snake,1.25\n")
    (tmp_path / "MRSIM_STATE_snake.part2.csv").write_text(
        "time,seq,robot,com.x,lock.a.attached\n0.03,2,snake,1,0\n")
    logs = mrsim.read_csv_folder(str(tmp_path))
    s = logs["MRSIM_STATE_snake"]
    assert np.array_equal(s["time"], [0.01, 0.02, 0.03])
    assert s["robot"] == ["snake"] * 3
    assert np.array_equal(s["lock.a.attached"], [np.nan, np.nan, 0],
                          equal_nan=True)


def test_malformed_csv_raises_log_error(tmp_path):
    bad = tmp_path / "x.csv"
    bad.write_text("a,b\n1,2\n3\n")
    with pytest.raises(mrsim.LogError) as e:
        mrsim.read_csv(str(bad))
    assert "x.csv:3" in str(e.value)
    with pytest.raises(mrsim.LogError):
        mrsim.read_csv_folder(str(tmp_path / "none"))
    with pytest.raises(mrsim.LogError):
        mrsim.read_lcm_log(str(bad))


def test_lcm_log_reads_like_the_loggers_csv(tmp_path, children):
    path = str(tmp_path / "snake.xml")
    mrsim.Scenario.chain(modules=4, pattern="pitch").save(path)
    url = lcm_url(7564)
    log = str(tmp_path / "run.lcmlog")
    logger = children.start(["lcm-logger", "--lcm-url=" + url, "--flush-interval=10", "-q", log],
                            str(tmp_path / "logger.log"))
    sim = children.start([program("mrsim-sim"), path, "--lcm-url", url,
                          "--paused"],
                         str(tmp_path / "sim.log"))
    node = mrsim.Node(url=url, name="logs")
    node.next_message("sim_status", timeout=30)
    # The logger listens once the paused simulator's statuses reach its
    # file (it flushes every 10 ms).
    wait_until(lambda: node.spin_once(0.05) >= 0 and os.path.exists(log)
               and os.path.getsize(log) > 0, 30, "the logger's first message")
    node.step(50, timeout=30)
    node.quit(timeout=30)
    assert sim.wait(60) == 0, sim.output()
    logger.proc.send_signal(signal.SIGINT)
    logger.wait(20)
    logs = mrsim.read_lcm_log(log)
    state = logs.get("MRSIM_STATE_snake")
    assert state is not None, list(logs)
    assert "module3.joint.angle" in state and "com.x" in state
    # Real time, so no burst overflows the logger's socket on a busy host.
    assert len(state["time"]) >= 25
    assert np.all(np.diff(state["seq"]) > 0)
    only = mrsim.read_lcm_log(log, channels="MRSIM_SIM_STATUS")
    assert list(only) == ["MRSIM_SIM_STATUS"]


def test_mcap_reads_as_many_states_as_the_csv_logger_wrote(tmp_path, children):
    path = str(tmp_path / "snake.xml")
    mrsim.Scenario.chain(modules=4, pattern="pitch").save(path)
    url = lcm_url(7568)
    mcap = str(tmp_path / "run.mcap")
    as_json = str(tmp_path / "json.mcap")
    loggers = [children.start([program("mrsim-log"), "--lcm-url", url] + how +
                              ["--exit-with-sim"], str(tmp_path / name))
               for name, how in (("csv.log", ["--out", str(tmp_path / "csv")]),
                                 ("mcap.log", ["--mcap", mcap]),
                                 ("json.log", ["--mcap", as_json,
                                               "--mcap-encoding", "json"]))]
    for logger in loggers:
        wait_until(lambda: "recording channels" in logger.output(), 30,
                   "mrsim-log to listen")
    sim = children.start([program("mrsim-sim"), path, "--lcm-url", url,
                          "--duration", "0.5", "--clock", "fast"],
                         str(tmp_path / "sim.log"))
    assert sim.wait(60) == 0, sim.output()
    for logger in loggers:
        assert logger.wait(60) == 0, logger.output()
    csv = mrsim.read_csv_folder(str(tmp_path / "csv"))["MRSIM_STATE_snake"]
    state = mrsim.read_mcap(mcap)["MRSIM_STATE_snake"]
    assert len(state["seq"]) == len(csv["seq"]) > 0
    assert np.array_equal(state["seq"], csv["seq"])
    assert np.allclose(state["modules.3.position.0"], csv["module3.x"])
    assert np.all(np.diff(state["log_time"]) >= 0)
    # The protobuf file (the default) reads as the JSON one of the same run.
    json_state = mrsim.read_mcap(as_json)["MRSIM_STATE_snake"]
    assert np.array_equal(json_state["seq"], state["seq"])
    assert set(json_state) == set(state)
    for column, values in state.items():
        if isinstance(values, list):
            assert values == json_state[column], column
        elif column != "log_time":
            assert np.array_equal(values, json_state[column], equal_nan=True), \
                column
    only = mrsim.read_mcap(mcap, channels="MRSIM_SIM_STATUS")
    assert list(only) == ["MRSIM_SIM_STATUS"]


def test_mcap_cut_off_reads_its_whole_chunks_and_warns(tmp_path):
    path = tmp_path / "cut.mcap"
    source = os.path.join(os.path.dirname(__file__), "..", "..", "fuzz",
                          "corpus", "mcap_reader", "cut_off.mcap")
    with open(source, "rb") as f:
        path.write_bytes(f.read())
    with pytest.warns(UserWarning, match="last whole chunk"):
        mrsim.read_mcap(str(path))
    bad = tmp_path / "bad.mcap"
    bad.write_bytes(b"not an mcap file")
    with pytest.raises(mrsim.LogError, match="not an MCAP file"):
        mrsim.read_mcap(str(bad))
