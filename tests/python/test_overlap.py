"""Parts overlapping at the start (REQ-1.2.8): Python refuses them as
mrsim-sim does, with its words, unless allow_overlap=True."""

import glob
import subprocess

import numpy as np
import pytest

import mrsim
from camera_scenario import camera_snake
from conftest import lcm_url, program, source
from mrsim.env import ChainEnv


def ball_in_the_snake():
    """A static ball on the ground where modules 1 and 2 lie."""
    return camera_snake(ball=(-0.2, 0.0), camera=False)


@pytest.fixture
def overlapping_file(tmp_path):
    path = str(tmp_path / "ball_in_snake.xml")
    ball_in_the_snake().save(path)
    return path


def test_an_overlapping_file_is_refused_naming_both_parts(overlapping_file):
    with pytest.raises(mrsim.OverlapError) as refused:
        mrsim.Simulation(overlapping_file)
    text = str(refused.value)
    assert "robot 'snake' module 1 back frame overlaps scene object 'ball'" \
        in text
    assert text.startswith(overlapping_file + ":")
    assert "allow_overlap=True" in text
    error = refused.value
    assert isinstance(error, mrsim.ScenarioError)
    assert isinstance(error, ValueError)
    # Where the deepest pair's first part is, as ScenarioError names it.
    assert error.file == overlapping_file and error.line > 0
    assert error.path == error.overlaps[0]["first_path"]
    assert error.path.startswith("Scenario/robot[1]/modules/Module[")
    assert error.overlaps[0]["second"] == "scene object 'ball'"
    assert error.overlaps[0]["first"].startswith("robot 'snake' module ")
    assert error.overlaps[0]["depth"] > 0.001


def test_the_refusal_says_what_mrsim_sim_says(overlapping_file):
    with pytest.raises(mrsim.OverlapError) as refused:
        mrsim.Simulation(overlapping_file)
    sim = subprocess.run(
        [program("mrsim-sim"), overlapping_file, "--lcm-url", lcm_url(7569),
         "--duration", "0.1"],
        capture_output=True, text=True, timeout=120)
    assert sim.returncode == 2
    said = sim.stderr.strip()
    assert said.startswith("mrsim-sim: ")
    expected = said[len("mrsim-sim: "):].replace("--allow-overlap",
                                                  "allow_overlap=True")
    assert str(refused.value) == expected


def test_an_overlapping_scenario_object_is_refused_too():
    with pytest.raises(mrsim.OverlapError, match="scene object 'ball'"):
        mrsim.Simulation(ball_in_the_snake())


def test_allow_overlap_runs_it(overlapping_file):
    for scenario in (overlapping_file, ball_in_the_snake()):
        sim = mrsim.Simulation(scenario, allow_overlap=True)
        sim.step(10)
        assert sim.time == pytest.approx(10 * sim.timestep)


def test_every_shipped_scenario_still_loads():
    shipped = [f for f in glob.glob(source("scenarios/*.xml"))
               if not f.endswith(".genome.xml")
               and not f.endswith("mrsim_original.xml")]
    assert len(shipped) >= 5
    for path in shipped:
        mrsim.Simulation(path).step(1)
    original = mrsim.Scenario.load(source("scenarios/mrsim_original.xml"),
                                   frame="original")
    mrsim.Simulation(original).step(1)


def test_run_episode_refuses_an_overlap_unless_allowed():
    scenario = ball_in_the_snake()
    gait = mrsim.Gait("forward")
    with pytest.raises(mrsim.OverlapError, match="scene object 'ball'"):
        mrsim.run_episode(scenario, gait, duration=0.1)
    r = mrsim.run_episode(scenario, gait, duration=0.1, allow_overlap=True)
    assert "fitness" in r


def test_chain_env_refuses_an_overlap_unless_allowed(overlapping_file):
    with pytest.raises(mrsim.OverlapError):
        ChainEnv(scenario=overlapping_file)
    env = ChainEnv(scenario=overlapping_file, allow_overlap=True,
                   episode_seconds=0.1)
    env.reset(seed=1)
    env.step(np.zeros(env.action_space.shape))


def test_a_tasks_world_is_not_checked():
    # The pole task squeezes the pole between the modules on purpose, as
    # mrsim-opt --task knows.
    with pytest.raises(mrsim.OverlapError):
        mrsim.Simulation(mrsim.Scenario.task("pole"))
    ChainEnv(task="pole", episode_seconds=0.1)



def test_optimize_refuses_an_overlapping_file_unless_allowed(
        overlapping_file, tmp_path):
    with pytest.raises(RuntimeError, match="scene object 'ball'"):
        mrsim.optimize(overlapping_file, genes="sine",
                       out_dir=str(tmp_path / "refused"), generations=1,
                       population=2, episode=0.2, workers=1)
    result = mrsim.optimize(overlapping_file, genes="sine",
                            out_dir=str(tmp_path / "allowed"), generations=1,
                            population=2, episode=0.2, workers=1,
                            allow_overlap=True)
    assert len(result["generations"]["best"]) == 1
