#!/usr/bin/env python3
"""Analysing a run's logs with numpy: mrsim-log's CSV folder or an
lcm-logger log.

    PYTHONPATH=build/python python3 examples/python/log_analysis.py out/demo/csv
    PYTHONPATH=build/python python3 examples/python/log_analysis.py run.lcmlog

Prints, per robot, the distance travelled, mean speed, the joint that
worked hardest and the range of each force and distance sensor.
"""
import argparse
import os

import numpy as np

import mrsim


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("log", nargs="?", default="out/demo/csv",
                   help="a CSV folder or an lcm-logger file")
    args = p.parse_args()
    logs = (mrsim.read_csv_folder(args.log) if os.path.isdir(args.log)
            else mrsim.read_lcm_log(args.log))
    for channel, cols in sorted(logs.items()):
        if "_STATE_" not in channel:
            continue
        t = cols["time"]
        com = np.stack([cols["com.x"], cols["com.y"]], axis=1)
        d = com[-1] - com[0]
        print("%s: %d states over %.2f s" % (channel, len(t), t[-1] - t[0]))
        print("  travelled %.3f m (dx %+.3f, dy %+.3f), mean speed %.3f m/s" %
              (np.hypot(*d), d[0], d[1], np.hypot(*d) / max(t[-1] - t[0], 1e-9)))
        torques = {k: np.abs(v).mean() for k, v in cols.items()
                   if k.endswith(".joint.torque")}
        if torques:
            k = max(torques, key=torques.get)
            print("  hardest joint: %s (mean |torque| %.3f N m)" %
                  (k[:-len(".torque")], torques[k]))
        for k, v in cols.items():
            if k.endswith(".force") or ".distance" in k:
                print("  %-26s %8.3f .. %8.3f" % (k, np.nanmin(v), np.nanmax(v)))


if __name__ == "__main__":
    main()
