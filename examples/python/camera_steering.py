#!/usr/bin/env python3
"""Steers a yaw snake toward a red object from its head camera's pictures.

In process, no LCM: a mrsim.Simulation renders the camera
(Simulation.camera_image, an (H, W, 3) uint8 array) a few times a second;
the red pixels' centroid says where the object is across the picture;
with the head's own swing taken out (the head sweeps with the
undulation, so the bearing is measured against its mean heading), the yaw
offset of the gait is biased toward that side (lateral undulation for a
yaw snake, the vertical wave for a pitch-yaw one). It prints the distance from the head to the
object at the start and at the end:

    PYTHONPATH=build/python python3 examples/python/camera_steering.py \\
        --scenario scenarios/camera_snake.xml --seconds 20

The scenario needs a robot with yaw joints and a camera (a <Camera> of a
sensor module) and the object: --target names it (a scene object's guid;
default: the first whose materialName is red, else 'ball').
"""
import argparse
import sys
import xml.etree.ElementTree as ET

import numpy as np

import mrsim


def red_centroid(image):
    """(x in [-1, 1] across the picture, share of red pixels), or None
    when nothing red is seen."""
    rgb = image.astype(np.int32)
    r, g, b = rgb[:, :, 0], rgb[:, :, 1], rgb[:, :, 2]
    red = (r > 100) & (r > 2 * g) & (r > 2 * b)
    if not red.any():
        return None
    columns = np.nonzero(red)[1]
    width = image.shape[1]
    return (columns.mean() + 0.5) / width * 2 - 1, red.mean()


def yaw_of(pose):
    """Heading (rad) of a pose row x, y, z, qw, qx, qy, qz."""
    w, x, y, z = pose[3:7]
    return np.arctan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def target_position(scenario, guid=None):
    """(x, y) of the scene object named guid; without one, of the first
    whose material is red, else of the one named 'ball'."""
    def child(element, tag):
        # The file's lists carry xmlns="Assembly": match local names.
        for c in element:
            if c.tag.rsplit("}", 1)[-1] == tag:
                return c
        return None

    def text(element, tag):
        c = child(element, tag)
        return (c.text or "").strip() if c is not None else ""

    root = ET.fromstring(scenario.to_xml())
    objects = [o for o in root.iter()
               if o.tag.rsplit("}", 1)[-1] == "SceneObject"]
    wanted = [o for o in objects if text(o, "guid") == guid] if guid else (
        [o for o in objects if text(o, "materialName").lower() == "red"] or
        [o for o in objects if text(o, "guid") == "ball"])
    if not wanted:
        raise SystemExit("the scenario has no scene object %s" % (
            "named %r" % guid if guid else "whose material is red, nor "
            "one named 'ball'"))
    p = child(wanted[0], "position")
    return np.array([float(text(p, "x")), float(text(p, "y"))])


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scenario", default="scenarios/camera_snake.xml")
    p.add_argument("--robot", default="0", help="index or name")
    p.add_argument("--target", default=None,
                   help="guid of the object (default: the first red one)")
    p.add_argument("--seconds", type=float, default=20.0)
    p.add_argument("--look-every", type=float, default=0.2,
                   help="seconds between pictures")
    p.add_argument("--gain", type=float, default=0.3,
                   help="offset_yaw (rad) per rad of bearing")
    args = p.parse_args()
    robot = int(args.robot) if args.robot.isdigit() else args.robot

    scenario = mrsim.Scenario.load(args.scenario)
    sim = mrsim.Simulation(scenario)
    cameras = sim.cameras(robot)
    if not cameras:
        sys.exit("robot %r has no camera" % (robot,))
    cam = cameras[0]
    # tan of half the horizontal field of view: centroid x -> angle.
    half_width = np.tan(np.radians(cam["fovy"]) / 2) * cam["width"] / \
        cam["height"]
    target = target_position(scenario, args.target)
    if "pitch" in sim.joint_axes(robot):
        # A pitch-yaw snake crawls on the vertical wave; its yaw offset
        # bends the body into an arc the head then leaves on the other
        # side (measured: +offset_yaw turns it right).
        gait, turn = mrsim.Gait("forward"), -1.0
    else:
        # A yaw snake: lateral undulation; +offset_yaw turns it left.
        gait, turn = mrsim.Gait.from_parameters(
            {"A_yaw": 0.7, "phi_yaw": 0.8, "T": 1.5}), 1.0
    sim.set_controller(gait, robot, period=0.05)

    def distance():
        head = sim.state(robot).module_pose[0][:2]
        return float(np.linalg.norm(target - head))

    start = distance()
    print("distance to the object at the start: %.3f m" % start)
    offset, seen = 0.0, 0
    heading = None  # the head's mean heading (a running mean of its yaw)
    steps = int(round(args.seconds / args.look_every))
    for _ in range(steps):
        head_yaw = yaw_of(sim.state(robot).module_pose[0])
        if heading is None:
            heading = head_yaw
        # Mean of angles: step along the wrapped difference.
        heading += 0.15 * np.angle(np.exp(1j * (head_yaw - heading)))
        found = red_centroid(sim.camera_image(robot, 0))
        if found is not None:
            seen += 1
            x, _share = found
            # Left of the picture's centre is positive (x < 0).
            bearing = head_yaw - np.arctan(x * half_width) - heading
            bearing = np.angle(np.exp(1j * bearing))
            offset = 0.7 * offset + 0.3 * turn * args.gain * bearing
            gait.set_parameters({"offset_yaw": offset})
        sim.run(args.look_every)
    end = distance()
    print("saw the object in %d of %d pictures" % (seen, steps))
    print("distance to the object at the end: %.3f m" % end)


if __name__ == "__main__":
    main()
