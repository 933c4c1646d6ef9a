#!/usr/bin/env python3
"""A new gait in twenty lines, compared with the forward preset.

    PYTHONPATH=build/python python3 examples/python/new_gait.py [--seconds 10] [--out out/python]

Runs both on scenarios/snake11.xml in process and plots the centre of
mass's forward travel against time (matplotlib; without it, a table).
"""
import argparse
import os

import numpy as np

import mrsim

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


# --- the new gait: a travelling wave with flattened crests ---------------
class SquareWave:
    """theta_i = A tanh(k sin(2 pi t / T + i phi)) / tanh(k), ramped in."""

    def __init__(self, amplitude=0.9, phase=2.2, period=3.0, sharpness=3.0):
        self.a, self.phi, self.T, self.k = amplitude, phase, period, sharpness

    def __call__(self, t, state):
        i = np.arange(len(state.joint_angle))
        wave = np.sin(2 * np.pi * t / self.T + i * self.phi)
        ramp = min(1.0, t / self.T)  # no jump at the start
        return ramp * self.a * np.tanh(self.k * wave) / np.tanh(self.k)
# ---------------------------------------------------------------------------


def travel(controller, seconds):
    """(time, forward CoM travel) of one run of the controller."""
    sim = mrsim.Simulation(os.path.join(ROOT, "scenarios", "snake11.xml"))
    sim.set_controller(controller)
    start = sim.state().com[0]
    times, xs = [], []
    for _ in range(int(round(seconds / 0.1))):
        sim.run(0.1)
        times.append(sim.time)
        xs.append(sim.state().com[0] - start)
    return np.array(times), np.array(xs)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--seconds", type=float, default=10.0)
    p.add_argument("--out", default="out/python")
    args = p.parse_args()
    runs = {"forward (preset)": travel(mrsim.Gait("forward"), args.seconds),
            "square wave (new)": travel(SquareWave(), args.seconds)}
    for name, (t, x) in runs.items():
        print("%-18s %5.1f s: %+.3f m (%.3f m/s)" %
              (name, t[-1], x[-1], x[-1] / t[-1]))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("(no matplotlib: sudo apt-get install python3-matplotlib "
              "for the plot)")
        return
    os.makedirs(args.out, exist_ok=True)
    fig, ax = plt.subplots(figsize=(6, 3.5))
    for name, (t, x) in runs.items():
        ax.plot(t, x, label=name)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("forward travel of the CoM (m)")
    ax.legend()
    fig.tight_layout()
    path = os.path.join(args.out, "new_gait.png")
    fig.savefig(path, dpi=100)
    print("plot: %s" % os.path.abspath(path))


if __name__ == "__main__":
    main()
