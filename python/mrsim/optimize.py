"""Running mrsim's optimiser (mrsim-opt) from Python and reading its files.

``optimize(...)`` runs ``mrsim-opt`` (the C++ optimiser, locally on this
machine's cores or, with ``farm=True``, on mrsim-worker processes) on a
scenario file or a task of the suite (``task="pole"``) and
calls ``progress(row)`` with each generation's row of ``generations.csv``
as it is written. ``read_generations(out_dir)`` reads a run's files.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from typing import Any, Callable, Dict, Optional

import numpy as np

from . import _core


def _program(name: str) -> str:
    """A program of the build tree (beside build/python) or of PATH."""
    here = os.path.dirname(os.path.abspath(__file__))
    for d in (os.environ.get("MRSIM_BIN_DIR"),
              os.path.join(here, "..", "..", "bin")):
        if d and os.access(os.path.join(d, name), os.X_OK):
            return os.path.join(d, name)
    found = shutil.which(name)
    if not found:
        raise FileNotFoundError(
            "%s: not found (put mrsim's build/bin or install bin on PATH, "
            "or set MRSIM_BIN_DIR)" % name)
    return found


def read_generations(out_dir: str) -> Dict[str, Any]:
    """A run's results: {'generations': {column: array} of generations.csv,
    'evaluations': ... of evaluations.csv (when present), 'best_gait':
    mrsim.Gait of best_gait.xml (when present)}."""
    out: Dict[str, Any] = {}
    for name in ("generations", "evaluations"):
        path = os.path.join(out_dir, name + ".csv")
        if os.path.exists(path):
            out[name] = _core.read_csv(path)
    gait = os.path.join(out_dir, "best_gait.xml")
    if os.path.exists(gait):
        out["best_gait"] = _core.Gait.load(gait)
    return out


def optimize(scenario: Optional[str] = None, genome: Optional[str] = None,
             out_dir: Optional[str] = None,
             algorithm: Optional[str] = None,
             generations: Optional[int] = None,
             population: Optional[int] = None, seed: Optional[int] = None,
             episode: Optional[float] = None, gait: Optional[str] = None,
             farm: bool = False, workers: Optional[int] = None,
             progress: Optional[Callable[[Dict[str, float]], None]] = None,
             extra_args: tuple = (), task: Optional[str] = None,
             genes: Optional[str] = None,
             controller: Optional[str] = None,
             allow_overlap: bool = False) -> Dict[str, Any]:
    """Runs mrsim-opt on a scenario file and a genome file into out_dir
    (resumed when out_dir holds a checkpoint of the same problem).

    task: a task of the suite (``mrsim.task_names()``, docs/tasks.md)
    instead of a scenario: its world, its fitness (forward or up) and,
    unless ``gait`` names one, its gait. genes: a built-in genome instead
    of a genome file, "sine" (the seven gait genes) or "cpg" (those and
    the CPG's). Exactly one of scenario and task, and one of genome and
    genes; a task name that is not in the suite raises ValueError naming
    the known ones before anything runs.

    A scenario file that carries its optimisation setup (<optimization>,
    docs/optimizer.md "The setup in the design file") gives every setting
    left as None here, its genes too (then give neither genome nor genes);
    an argument given overrides the file. Without a setup in the file the
    settings left as None are mrsim-opt's defaults (ga, 20 generations).

    controller: what the genes drive (mrsim-opt --controller,
    docs/optimizer.md): "gait" (default), "cpg", "lua:FILE" (a Lua
    script whose declared params are the genes) or "mlp:H" / "mlp:H1,H2"
    (a neural network's weights). A Lua script or a network brings its
    own genes: give no ``genes``, and a ``genome`` file only for body
    genes. The best controller is written to out_dir (best_controller.lua,
    best_network.xml).

    allow_overlap: optimise a scenario whose parts overlap at the start
    (mrsim-opt --allow-overlap); otherwise mrsim-opt refuses it, naming
    the overlapping parts, and this raises RuntimeError with its message.

    workers: local threads (default: one per core; not with farm, whose
    mrsim-worker processes join by themselves). progress(row) is called with each new row of generations.csv (a dict
    generation, best, mean, worst, best_so_far, failed and the genes).
    Returns read_generations(out_dir). Raises RuntimeError with mrsim-opt's
    message when it fails (bad input: its exit status 2)."""
    if out_dir is None:
        raise TypeError("optimize: out_dir is required")
    if (scenario is None) == (task is None):
        raise TypeError("optimize: give exactly one of scenario and task")
    own_genes = controller is not None and controller.split(":")[0] in (
        "lua", "mlp")
    if own_genes:
        if genes is not None:
            raise TypeError("optimize: controller %s brings its own genes; "
                            "give a genome file only for body genes"
                            % controller)
    elif genome is not None and genes is not None:
        raise TypeError("optimize: give one of genome and genes, not both")
    elif task is not None and genome is None and genes is None:
        # A scenario file may carry its genes; a task has none of its own.
        raise TypeError("optimize: give exactly one of genome and genes")
    if task is not None and task.replace("_", "-") not in _core.task_names():
        raise ValueError("optimize: unknown task '%s': expected one of %s" %
                         (task, ", ".join(_core.task_names())))
    if genes is not None and genes not in ("sine", "cpg"):
        raise ValueError("optimize: unknown genes '%s': expected sine or cpg"
                         % genes)
    args = [_program("mrsim-opt")]
    args += (["--task", task] if task is not None
             else [os.fspath(scenario)])  # type: ignore[arg-type]
    if genes is not None:
        args += ["--genes", genes]
    elif genome is not None:
        args += ["--genome", os.fspath(genome)]
    if controller is not None:
        args += ["--controller", controller]
    args += ["--out", os.fspath(out_dir), "--quiet"]
    if algorithm is not None:
        args += ["--algorithm", algorithm]
    if generations is not None:
        args += ["--generations", str(int(generations))]
    if workers is not None and not farm:
        args += ["--workers", "local:%d" % workers]
    for flag, value in (("--population", population), ("--seed", seed),
                        ("--episode", episode), ("--gait", gait)):
        if value is not None:
            args += [flag, str(value)]
    if farm:
        args.append("--farm")
    if allow_overlap:
        args.append("--allow-overlap")
    args += list(extra_args)
    csv = os.path.join(os.fspath(out_dir), "generations.csv")
    seen = 0
    proc = subprocess.Popen(args, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)

    def report() -> None:
        nonlocal seen
        if progress is None or not os.path.exists(csv):
            return
        try:
            table = _core.read_csv(csv)
        except _core.LogError:
            return  # a row being written; read again next time
        rows = len(table.get("generation", ()))
        for i in range(seen, rows):
            progress({k: (v[i] if not isinstance(v, np.ndarray) else float(v[i]))
                      for k, v in table.items()})
        seen = rows

    try:
        while proc.poll() is None:
            report()
            try:
                proc.wait(timeout=0.5)
            except subprocess.TimeoutExpired:
                pass
    except KeyboardInterrupt:
        proc.terminate()  # mrsim-opt stops cleanly and keeps its checkpoint
        proc.wait()
        raise
    out, err = proc.communicate()
    report()
    if proc.returncode != 0:
        raise RuntimeError("mrsim-opt failed (exit %d): %s" %
                           (proc.returncode, (err or out).strip()))
    return read_generations(out_dir)
