"""mrsim.env.ChainEnv behaves as Gymnasium defines reset/step/spaces."""

import numpy as np
import pytest

from mrsim.env import ChainEnv


def test_reset_step_and_spaces():
    env = ChainEnv(episode_seconds=0.5, control_period=0.05)
    obs, info = env.reset(seed=3)
    assert obs.shape == env.observation_space.shape
    a = env.action_space.sample()
    assert env.action_space.contains(a)
    steps = 0
    truncated = False
    while not truncated:
        obs, reward, terminated, truncated, info = env.step(a)
        assert not terminated
        assert isinstance(reward, float)
        steps += 1
    assert steps == 10
    assert info["time"] == pytest.approx(0.5)


def test_same_actions_same_observations():
    def rollout():
        env = ChainEnv(episode_seconds=0.3)
        env.reset(seed=1)
        rng = np.random.default_rng(7)
        out = []
        for _ in range(6):
            a = rng.uniform(env.action_space.low, env.action_space.high)
            out.append(env.step(a)[0])
        return np.array(out)
    assert np.array_equal(rollout(), rollout())


def test_bad_actions_and_options_raise():
    env = ChainEnv()
    with pytest.raises(RuntimeError):
        env.step(np.zeros(env.action_space.shape))
    env.reset()
    with pytest.raises(ValueError):
        env.step(np.zeros(3))
    with pytest.raises(ValueError):
        env.step(np.full(env.action_space.shape, np.nan))
    with pytest.raises(ValueError):
        ChainEnv(observation="pixels")
    with pytest.raises(ValueError):
        ChainEnv(control_period=0.003)


def test_full_observation_and_custom_reward():
    env = ChainEnv(observation="full",
                   reward=lambda prev, s, a: float(s.com[2]))
    obs, _ = env.reset()
    assert obs.shape == env.observation_space.shape
    _, r, _, _, _ = env.step(np.zeros(env.action_space.shape))
    assert r > 0


def test_a_task_gives_its_world_and_its_fitness_as_the_reward():
    import mrsim
    assert "pole" in mrsim.task_names()
    env = ChainEnv(task="pole", episode_seconds=0.2, control_period=0.05)
    assert env.reward == "up"
    assert mrsim.task_info("pole")["fitness"] == "up"
    obs, _ = env.reset(seed=1)
    assert obs.shape == (24,)
    _, reward, terminated, _, _ = env.step(np.zeros(12))
    assert not terminated
    assert abs(reward) < 0.1
    with pytest.raises(ValueError):
        ChainEnv(task="moon")
