"""python3 -m mrsim [--version]: the package's version and where it is."""

import argparse
import os
import sys

from . import __version__, gait_presets


def main(argv=None) -> int:
    """Prints the version (--version) or a short description."""
    parser = argparse.ArgumentParser(
        prog="python3 -m mrsim",
        description="mrsim's Python package: simulation, gaits, logs and "
        "LCM from Python (docs/python.md).")
    parser.add_argument("--version", action="store_true",
                        help="print the version and exit")
    args = parser.parse_args(argv)
    if args.version:
        print("mrsim %s" % __version__)
        return 0
    print("mrsim %s from %s" % (__version__, os.path.dirname(__file__)))
    print("gait presets: %s" % ", ".join(gait_presets()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
