#!/usr/bin/env python3
"""A Python controller for a running mrsim-sim, over LCM.

Lockstep (the simulator waits for this script every control period):

    mrsim-sim scenarios/snake11.xml --clock lockstep --controllers py --duration 10 &
    PYTHONPATH=build/python python3 examples/python/controller.py --name py

Real time (the simulator runs on; the script answers what it can):

    mrsim-sim scenarios/snake11.xml --duration 10 &
    PYTHONPATH=build/python python3 examples/python/controller.py

It runs the forward gait and, once a second, turns towards the side the
robot drifted to (a gait steered by feedback), printing where it is.
"""
import argparse

import mrsim


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--robot", default="snake")
    p.add_argument("--name", default="py", help="sender (--controllers)")
    p.add_argument("--lcm-url", default=None)
    p.add_argument("--prefix", default=mrsim.node.DEFAULT_PREFIX)
    p.add_argument("--axes", default="pitch", help="the robot's joint axes")
    args = p.parse_args()
    node = mrsim.Node(url=args.lcm_url, prefix=args.prefix, name=args.name)
    gait = mrsim.Gait("forward", axes=args.axes)
    start = None
    next_report = 0.0
    for state in node.states(args.robot, timeout=5):
        if start is None:
            start = state.com.copy()
            print("%s: %d joints, answering as %r" %
                  (args.robot, len(state.joint_angle), args.name))
        node.send_targets(args.robot, gait.targets(state.time, state), state)
        if state.time >= next_report:
            next_report += 1.0
            d = state.com - start
            gait.set_direction(1.0, max(-1.0, min(1.0, -5.0 * d[1])))
            print("t=%5.2f s  dx=%+.3f m  dy=%+.3f m" % (state.time, d[0], d[1]))
    print("no state for 5 s: the simulator stopped")


if __name__ == "__main__":
    main()
