#!/usr/bin/env python3
"""Random search over mrsim.env.ChainEnv: open-loop sinusoid policies.

    PYTHONPATH=build/python python3 examples/python/random_search.py [--trials 20] [--seed 1]

Each trial draws pitch and yaw amplitudes, a phase step and a period,
runs one episode of the environment (an 8-module pitch-yaw chain, 5 s)
with that travelling wave as actions, and keeps the one that travels furthest (the sum of the
rewards is the forward travel of the centre of mass).
"""
import argparse

import numpy as np

from mrsim.env import ChainEnv


def episode(env, a_pitch, a_yaw, phase, period):
    obs, info = env.reset()
    n = env.action_space.shape[0]
    amplitude = np.where(np.arange(n) % 2 == 0, a_pitch, a_yaw)
    total, t, done = 0.0, 0.0, False
    while not done:
        action = amplitude * np.sin(2 * np.pi * t / period + phase * np.arange(n))
        obs, reward, terminated, truncated, info = env.step(action)
        total += reward
        t = info.get("time", t)
        done = terminated or truncated
    return total


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--trials", type=int, default=20)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--seconds", type=float, default=5.0)
    args = p.parse_args()
    env = ChainEnv(episode_seconds=args.seconds, control_period=0.02)
    rng = np.random.default_rng(args.seed)
    best = (-np.inf, None)
    for trial in range(args.trials):
        params = (rng.uniform(0.2, 1.2), rng.uniform(0.0, 0.8),
                  rng.uniform(0.3, 3.0), rng.uniform(1.0, 5.0))
        travel = episode(env, *params)
        if travel > best[0]:
            best = (travel, params)
            print("trial %2d: %+.3f m  A_pitch=%.2f A_yaw=%.2f phi=%.2f "
                  "T=%.2f  (best)" %
                  ((trial, travel) + params))
    print("best: %+.3f m with A_pitch=%.2f rad, A_yaw=%.2f rad, "
          "phi=%.2f rad, T=%.2f s" %
          ((best[0],) + best[1]))


if __name__ == "__main__":
    main()
