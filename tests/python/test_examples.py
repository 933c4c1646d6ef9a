"""The examples in examples/python run as docs/python.md shows them."""

import os
import subprocess
import sys

from conftest import lcm_url, program, source

ENV = dict(os.environ, MPLBACKEND="Agg")


def run(args, **kw):
    return subprocess.run([sys.executable] + args, capture_output=True,
                          text=True, env=ENV, timeout=240, **kw)


def test_new_gait_compares_with_the_preset(tmp_path):
    r = run([source("examples/python/new_gait.py"), "--seconds", "2",
             "--out", str(tmp_path)])
    assert r.returncode == 0, r.stderr
    assert "forward (preset)" in r.stdout and "square wave (new)" in r.stdout


def test_random_search_reports_the_best(tmp_path):
    r = run([source("examples/python/random_search.py"), "--trials", "3",
             "--seconds", "0.5"])
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines()[-1].startswith("best: ")


def test_log_analysis_reads_a_csv_folder(tmp_path):
    (tmp_path / "MRSIM_STATE_snake.csv").write_text(
        "time,seq,robot,com.x,com.y,module0.joint.torque,"
        "sensor_module0.force\n"
        "0,0,snake,0,0,0.5,1\n1,1,snake,0.3,0.4,-0.5,2\n")
    r = run([source("examples/python/log_analysis.py"), str(tmp_path)])
    assert r.returncode == 0, r.stderr
    assert "travelled 0.500 m" in r.stdout
    assert "hardest joint: module0.joint" in r.stdout


def test_controller_drives_a_lockstep_simulator(tmp_path, children):
    url = lcm_url(7565)
    sim = children.start([program("mrsim-sim"), source("scenarios/snake11.xml"),
                          "--lcm-url", url, "--clock", "lockstep",
                          "--controllers", "py", "--duration", "1.5",
                          "--lockstep-timeout", "30"],
                         str(tmp_path / "sim.log"))
    r = run([source("examples/python/controller.py"), "--name", "py",
             "--lcm-url", url])
    assert r.returncode == 0, r.stderr
    assert sim.wait(30) == 0, sim.output()
    assert "t= 1.00 s" in r.stdout
    assert "the simulator stopped" in r.stdout
