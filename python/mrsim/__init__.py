"""mrsim for Python: the modular-robot simulator as a library and an LCM node.

Everything here runs mrsim's C++ libraries (pybind11 bindings in
mrsim._core); nothing is implemented a second time in Python.

- Scenarios: ``Scenario.load(path)``, ``Scenario.chain(modules=11)``;
  bad files raise ``ScenarioError`` naming file, line and field.
- Simulation in process: ``sim = Simulation(scenario)``, ``sim.step(n)``
  (GIL released), ``sim.state()`` (numpy arrays), joint targets,
  parts overlapping at the start refused (``OverlapError``, as mrsim-sim)
  unless ``allow_overlap=True``,
  ``detach``/``attach``, checkpoints; ``sim.camera_image()`` renders a
  robot's camera as an (H, W, 3) uint8 array (``sim.camera_image("scene")``
  a scene object's), ``sim.cameras()`` lists them.
- Gaits: ``Gait("forward")``, ``gait.targets(t, state)``,
  ``sim.set_controller(gait); sim.run(10)``.
- Episodes and the optimiser: ``run_episode``, ``run_task("pole")``,
  ``mrsim.optimize`` (a scenario file or ``task="pole"``).
- mrsim-opt's algorithms on a Python objective: ``Optimizer("cmaes",
  genes=[("x", -5, 5)], seed=1)``, ``ask()``, ``tell(fitness)``, ``best``.
- Logs: ``read_csv_folder``, ``read_lcm_log``, ``read_mcap`` (dicts of numpy arrays).
- LCM: ``Node`` (states, camera pictures as numpy arrays, commands,
  lockstep, simulator control; signed
  with a key file, ``KeyFileError`` when it cannot be used).
- Gymnasium-style environment: ``mrsim.env.ChainEnv`` (``task="pole"``:
  a task of the suite, ``task_names()``, ``Scenario.task(name)``;
  ``observation="camera"``: pixels).
"""

from ._core import (  # noqa: F401
    CheckpointError,
    Gait,
    GaitError,
    GenomeError,
    KeyFileError,
    LogError,
    Optimizer,
    OverlapError,
    PhysicsError,
    Scenario,
    ScenarioError,
    Simulation,
    State,
    __version__,
    gait_parameter_names,
    gait_presets,
    run_episode,
    run_task,
    task_info,
    task_names,
)
from .logs import read_csv, read_csv_folder, read_lcm_log, read_mcap  # noqa: F401
from .node import ControlError, Message, Node  # noqa: F401
from .optimize import optimize, read_generations  # noqa: F401

#: Column order of every pose array (as the logger's CSV columns).
POSE_FIELDS = ("x", "y", "z", "qw", "qx", "qy", "qz")


def load_scenario(path, frame=None, length_scale=1.0):
    """Reads and validates a scenario file (see Scenario.load)."""
    return Scenario.load(path, frame=frame, length_scale=length_scale)


__all__ = [
    "CheckpointError", "ControlError", "Gait", "GaitError", "GenomeError",
    "KeyFileError", "LogError", "Message", "Node", "Optimizer", "OverlapError", "POSE_FIELDS", "PhysicsError", "Scenario",
    "ScenarioError", "Simulation", "State", "gait_parameter_names",
    "gait_presets", "load_scenario", "optimize", "read_csv",
    "read_csv_folder", "read_generations", "read_lcm_log", "read_mcap",
    "run_episode",
    "run_task", "task_info", "task_names",
]
