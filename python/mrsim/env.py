"""mrsim.env.ChainEnv: a chain robot as a Gymnasium-style environment.

``reset(seed=None, options=None) -> (obs, info)`` and
``step(action) -> (obs, reward, terminated, truncated, info)`` as Gymnasium
defines them; ``observation_space`` and ``action_space`` have ``shape``,
``low``, ``high`` and ``sample()``. Works without the ``gymnasium``
package; when it is installed, ChainEnv is a ``gymnasium.Env`` with
``gymnasium.spaces.Box`` spaces and is registered as ``mrsim/Chain-v0``.
"""

from __future__ import annotations

from typing import Any, Callable, Dict, Optional, Tuple, Union

import numpy as np

from . import _core

try:  # optional: not a Debian package
    import gymnasium as _gym
except ImportError:  # pragma: no cover - depends on the machine
    _gym = None


class Box:
    """A box of float64 vectors, or of uint8 pixels
    (gymnasium.spaces.Box's interface)."""

    def __init__(self, low, high, seed: Optional[int] = None,
                 dtype: Any = np.float64) -> None:
        self.dtype = np.dtype(dtype)
        self.low = np.asarray(low, dtype=self.dtype)
        self.high = np.asarray(high, dtype=self.dtype)
        if self.low.shape != self.high.shape:
            raise ValueError("low and high: expected the same shape")
        self.shape = self.low.shape
        self._rng = np.random.default_rng(seed)

    def seed(self, seed: Optional[int] = None) -> None:
        """Seeds sample()."""
        self._rng = np.random.default_rng(seed)

    def sample(self) -> np.ndarray:
        """A uniform sample (infinite bounds: standard normal)."""
        if self.dtype == np.uint8:
            return self._rng.integers(self.low, self.high, endpoint=True,
                                      dtype=np.uint8)
        finite = np.isfinite(self.low) & np.isfinite(self.high)
        out = self._rng.standard_normal(self.shape)
        out[finite] = self._rng.uniform(self.low[finite], self.high[finite])
        return out

    def contains(self, x) -> bool:
        """True when x has the shape and lies within the bounds."""
        x = np.asarray(x)
        if self.dtype == np.uint8 and x.dtype != np.uint8:
            return False
        x = x.astype(self.dtype, copy=False)
        return x.shape == self.shape and bool(
            np.all(x >= self.low) and np.all(x <= self.high))

    def __repr__(self) -> str:
        return "Box(%s, %s, %s)" % (self.low.min(initial=0),
                                    self.high.max(initial=0), self.shape)


def _box(low, high, dtype: Any = np.float64):
    if _gym is not None:
        return _gym.spaces.Box(np.asarray(low, dtype=dtype),
                               np.asarray(high, dtype=dtype), dtype=dtype)
    return Box(low, high, dtype=dtype)


_Base = _gym.Env if _gym is not None else object

#: Observations: "joints" (angles and speeds), "full" (also the centre of
#: mass, its velocity and the module orientations), "camera" (the pixels
#: of the robot's first camera: uint8 (H, W, 3)).
OBSERVATIONS = ("joints", "full", "camera")
#: Rewards: "forward" (centre-of-mass travel along +x per step), "net"
#: (horizontal travel in any direction), "up" (rise along +z), or a
#: callable reward(previous_state, state, action) -> float.
REWARDS = ("forward", "net", "up")


class ChainEnv(_Base):  # type: ignore[misc, valid-type]
    """A chain robot in a mrsim.Simulation; actions are joint targets."""

    metadata: Dict[str, Any] = {"render_modes": []}

    def __init__(self, scenario: Union[str, "_core.Scenario", None] = None,
                 robot: Union[int, str] = 0, episode_seconds: float = 10.0,
                 control_period: float = 0.05,
                 observation: str = "joints",
                 reward: Union[str, Callable[..., float], None] = None,
                 render_mode: Optional[str] = None,
                 task: Optional[str] = None,
                 allow_overlap: bool = False) -> None:
        """scenario: a Scenario, a scenario file, or None for an 8-module
        pitch-yaw chain; task: a task of the suite instead (docs/tasks.md:
        its world, and its fitness as the default reward). reward: default
        "forward" (a task's own: "forward" or "up"). An action holds joint targets (rad), applied for
        control_period s; an episode is truncated after episode_seconds.
        A simulation that becomes unstable terminates the episode.
        observation: "joints", "full" or "camera" (what the robot's first
        camera sees, rendered in process; ValueError when the robot has
        no camera). A scenario whose parts overlap at the start raises
        mrsim.OverlapError naming them, as mrsim.Simulation does, unless
        allow_overlap=True; a task's world is built to its own rules (the
        pole task squeezes the pole on purpose) and is not checked, as
        mrsim-opt --task does not check it."""
        if observation not in OBSERVATIONS:
            raise ValueError("observation: expected one of %s, got %r" %
                             (", ".join(OBSERVATIONS), observation))
        if task is not None:
            if scenario is not None:
                raise ValueError("give a scenario or a task, not both")
            scenario = _core.Scenario.task(task)
            allow_overlap = True
            if reward is None:
                reward = _core.task_info(task)["fitness"]
        if reward is None:
            reward = "forward"
        if not callable(reward) and reward not in REWARDS:
            raise ValueError("reward: expected one of %s or a callable, "
                             "got %r" % (", ".join(REWARDS), reward))
        if not episode_seconds > 0:
            raise ValueError("episode_seconds: expected a time > 0")
        if scenario is None:
            scenario = _core.Scenario.chain(modules=8, pattern="pitch-yaw",
                                            friction=0.8)
        self.render_mode = render_mode
        self.sim = _core.Simulation(scenario, allow_overlap=allow_overlap)
        self.robot = robot
        self.episode_seconds = float(episode_seconds)
        steps = control_period / self.sim.timestep
        if steps < 1 or abs(steps - round(steps)) > 1e-9:
            raise ValueError("control_period: expected a whole number of "
                             "timesteps (%g s)" % self.sim.timestep)
        self.steps_per_action = int(round(steps))
        self.control_period = control_period
        self.observation = observation
        self.reward = reward
        low, high = self.sim.joint_limits(robot)
        self.action_space = _box(low, high)
        n = len(low)
        if observation == "camera":
            cameras = self.sim.cameras(robot)
            if not cameras:
                name = robot if isinstance(robot, str) else \
                    self.sim.robots[robot]
                raise ValueError(
                    "observation='camera': robot %r of the scenario has no "
                    "camera (add a <Camera> to a sensor module's <cameras>, "
                    "docs/camera.md)" % name)
            shape = (cameras[0]["height"], cameras[0]["width"], 3)
            self.observation_space = _box(np.zeros(shape),
                                          np.full(shape, 255), np.uint8)
        else:
            size = 2 * n if observation == "joints" else \
                2 * n + 6 + 4 * len(self.sim.state(robot).module_pose)
            self.observation_space = _box(np.full(size, -np.inf),
                                          np.full(size, np.inf))
        self._state = None
        self.np_random = np.random.default_rng()

    def _obs(self, s) -> np.ndarray:
        if self.observation == "camera":
            return self.sim.camera_image(self.robot, 0)
        parts = [s.joint_angle, s.joint_speed]
        if self.observation == "full":
            parts += [s.com, s.com_velocity, s.module_pose[:, 3:].ravel()]
        return np.concatenate(parts)

    def _reward(self, prev, s, action) -> float:
        if callable(self.reward):
            return float(self.reward(prev, s, action))
        d = s.com - prev.com
        if self.reward == "forward":
            return float(d[0])
        if self.reward == "up":
            return float(d[2])
        return float(np.hypot(d[0], d[1]))

    def reset(self, *, seed: Optional[int] = None,
              options: Optional[Dict[str, Any]] = None
              ) -> Tuple[np.ndarray, Dict[str, Any]]:
        """Back to the scenario's start; returns (observation, info). The
        physics is deterministic; seed seeds np_random and the spaces."""
        if seed is not None:
            self.np_random = np.random.default_rng(seed)
            self.action_space.seed(seed)
            self.observation_space.seed(seed)
        self.sim.reset()
        self._state = self.sim.state(self.robot)
        return self._obs(self._state), {"time": self._state.time}

    def step(self, action) -> Tuple[np.ndarray, float, bool, bool,
                                    Dict[str, Any]]:
        """Applies the joint targets (clipped to the limits) for one control
        period; returns (obs, reward, terminated, truncated, info)."""
        if self._state is None:
            raise RuntimeError("step: call reset() first")
        a = np.asarray(action, dtype=np.float64)
        if a.shape != self.action_space.shape:
            raise ValueError("action: expected shape %s, got %s" %
                             (self.action_space.shape, a.shape))
        if not np.all(np.isfinite(a)):
            raise ValueError("action: expected finite joint targets")
        a = np.clip(a, self.action_space.low, self.action_space.high)
        self.sim.set_joint_targets(a, self.robot)
        prev = self._state
        info: Dict[str, Any] = {}
        try:
            self.sim.step(self.steps_per_action)
        except _core.PhysicsError as e:
            info["error"] = str(e)
            return self._obs(prev), 0.0, True, False, info
        self._state = self.sim.state(self.robot)
        info["time"] = self._state.time
        truncated = self._state.time >= self.episode_seconds - 1e-9
        return (self._obs(self._state), self._reward(prev, self._state, a),
                False, truncated, info)

    def render(self) -> None:
        """No rendering in process (use mrsim-view on a live simulation)."""
        return None

    def close(self) -> None:
        """Nothing to release beyond the simulation."""


if _gym is not None:  # pragma: no cover - depends on the machine
    try:
        _gym.register(id="mrsim/Chain-v0", entry_point="mrsim.env:ChainEnv")
    except Exception:  # already registered (module reloaded)
        pass
