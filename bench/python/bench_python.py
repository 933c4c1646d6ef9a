"""BENCH lines of the Python package (see bench/python/CMakeLists.txt)."""

import argparse
import math
import os
import re
import resource
import subprocess
import sys
import tempfile
import time

import mrsim

PORT = 7570 + int(os.environ.get("MRSIM_BENCH_PORT_OFFSET", "0"))


def state_us(scenario, calls):
    """Mean microseconds to read the full state into numpy arrays."""
    sim = mrsim.Simulation(scenario)
    sim.step(100)
    start = time.perf_counter()
    for _ in range(calls):
        sim.state().arrays()
    return (time.perf_counter() - start) / calls * 1e6


def ask_tell_us(genes, population, generations):
    """Microseconds per individual of Optimizer.ask() and tell() from
    Python, CMA-ES, with a trivial objective (numpy's sum of squares): what
    putting a Python objective on mrsim's algorithms costs."""
    opt = mrsim.Optimizer("cmaes", genes=[("x%d" % i, -5, 5, 4)
                                          for i in range(genes)],
                          seed=1, population=population)
    start = time.perf_counter()
    for _ in range(generations):
        g = opt.ask()
        opt.tell(-(g * g).sum(axis=1))
    return (time.perf_counter() - start) / (generations * population) * 1e6


def median_and_spread(values):
    """Median, and the width of its distribution-free 95 % confidence
    interval (order statistics n/2 -+ 0.98 sqrt(n)) over it, as
    bench/common/paired_ratio.h reports spreads."""
    v = sorted(values)
    n = len(v)
    median = (v[(n - 1) // 2] + v[n // 2]) / 2
    half = 0.98 * math.sqrt(n)
    lo = v[max(0, int(math.floor(n / 2 - half)))]
    hi = v[min(n - 1, int(math.ceil(n / 2 + half)))]
    return median, (hi - lo) / median


def camera_python(source_dir, rounds):
    """(Python ms, C++ ms, pair ratios) of one 160x120 picture of an
    in-process Simulation: Simulation.camera_image() (render, copy into
    numpy, GIL released and taken back) against the same render timed
    inside C++, interleaved round by round (A B, then B A)."""
    sys.path.insert(0, os.path.join(source_dir, "tests", "python"))
    from camera_scenario import camera_snake
    sim = mrsim.Simulation(camera_snake(width=160, height=120))
    sim.camera_image()  # the GL context and the renderer, made once
    py, cpp = [], []
    for r in range(rounds):
        for which in ((0, 1) if r % 2 == 0 else (1, 0)):
            if which == 0:
                start = time.perf_counter()
                sim.camera_image()
                py.append(time.perf_counter() - start)
            else:
                cpp.append(mrsim._core._time_cpp_camera(sim))
    return py, cpp


def real_time_factor(output):
    m = re.findall(r"real-time factor ([0-9.eE+-]+)", output)
    if not m:
        raise RuntimeError("no real-time factor in: " + output)
    return float(m[-1])


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def lockstep(binary_dir, scenario, duration, python, work):
    """(real-time factor, sim s per CPU s of simulator and controller) of
    mrsim-sim in pipelined lockstep with mrsim-gait or with a Python
    controller (this process)."""
    url = "udpm://239.255.76.67:%d?ttl=0" % PORT
    name = "py" if python else "gait"
    sim_args = [os.path.join(binary_dir, "bin", "mrsim-sim"), scenario,
                "--lcm-url", url, "--clock", "lockstep", "--controllers",
                name, "--rate", "100", "--duration", str(duration),
                "--lockstep-timeout", "30", "--actuation-delay", "1"]
    log = os.path.join(work, "sim.out")
    cpu_children = children_cpu()
    cpu_self = time.process_time()
    controller = None
    node = None
    if python:
        node = mrsim.Node(url=url, name=name)
    else:
        controller = subprocess.Popen(
            [os.path.join(binary_dir, "bin", "mrsim-gait"), "--robot",
             "snake", "--scenario", scenario, "--gait", "forward",
             "--lcm-url", url, "--name", name, "--exit-with-sim"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(log, "w") as out:
        sim = subprocess.Popen(sim_args, stdout=out, stderr=subprocess.STDOUT)
        if python:
            gait = mrsim.Gait("forward", axes="pitch")
            for state in node.states("snake", timeout=5):
                node.send_targets("snake", gait.targets(state.time, state),
                                  state)
                if sim.poll() is not None:
                    break
        sim.wait(300)
    if controller is not None:
        controller.wait(60)
    cpu = (children_cpu() - cpu_children) + (
        time.process_time() - cpu_self if python else 0.0)
    with open(log) as f:
        return real_time_factor(f.read()), duration / cpu


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--binary-dir", required=True)
    p.add_argument("--source-dir", required=True)
    p.add_argument("--duration", type=float, default=6.0)
    p.add_argument("--runs", type=int, default=5)
    args = p.parse_args()
    scenario = os.path.join(args.source_dir, "scenarios", "snake11.xml")

    # Pairs alternated call by call on one simulation, so both halves of a
    # pair see the same machine; the median of the pairs' ratios (on a
    # shared machine a best-of picks one lucky slice of either side).
    sim = mrsim.Simulation(scenario)
    sim.set_joint_targets([0.3] * sim.joint_count())
    cpp, py = [], []
    for _ in range(40):
        cpp.append(mrsim._core._time_cpp_step(sim, 1000))
        start = time.perf_counter()
        sim.step(1000)
        py.append(time.perf_counter() - start)
    ratios = sorted(c / p for c, p in zip(cpp, py))
    print("step(1000): C++ %.4f s, Python %.4f s (best of 40 each)" %
          (min(cpp), min(py)))
    print("BENCH python_step_ratio %.3f ratio" % ratios[len(ratios) // 2])
    print("BENCH python_state_us %.1f us" % state_us(scenario, 2000))
    # Median of 5 runs of 200 generations: 10 genes, population 16.
    runs = sorted(ask_tell_us(10, 16, 200) for _ in range(5))
    print("ask/tell (CMA-ES, 10 genes, population 16): %s us per individual"
          % " ".join("%.2f" % r for r in runs))
    print("BENCH ask_tell_overhead_us %.2f us" % runs[len(runs) // 2])

    py, cpp = camera_python(args.source_dir, 200)
    ms, spread = median_and_spread([1e3 * v for v in py])
    ratio, ratio_spread = median_and_spread(
        [p / c for p, c in zip(py, cpp) if c > 0])
    print("camera_image 160x120: Python %.2f ms, C++ render %.2f ms "
          "(medians of 200 interleaved pairs)" %
          (ms, 1e3 * median_and_spread(cpp)[0]))
    print("BENCH camera_python_ms %.2f ms" % ms)
    print("BENCH camera_python_ms_spread %.1f %%" % (100 * spread))
    print("BENCH camera_python_ratio %.3f ratio" % ratio)
    print("BENCH camera_python_ratio_spread %.1f %%" % (100 * ratio_spread))

    with tempfile.TemporaryDirectory() as work:
        gait, python = [], []
        for _ in range(args.runs):
            gait.append(lockstep(args.binary_dir, scenario, args.duration,
                                 False, work))
            python.append(lockstep(args.binary_dir, scenario, args.duration,
                                   True, work))
    print("pipelined lockstep real-time factor: mrsim-gait %s, Python %s" %
          (" ".join("%.2f" % v for v, _ in gait),
           " ".join("%.2f" % v for v, _ in python)))
    print("BENCH python_lockstep_ratio %.3f ratio" %
          (max(v for v, _ in python) / max(v for v, _ in gait)))
    # Sim seconds per CPU second of simulator and controller together: what
    # a controller costs, whatever share of the machine the runs got.
    print("BENCH python_lockstep_ratio_cpu %.3f ratio" %
          (max(c for _, c in python) / max(c for _, c in gait)))


if __name__ == "__main__":
    main()
