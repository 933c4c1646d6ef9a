"""Cameras from Python: Simulation.camera_image renders in process (EGL,
no display), mrsim.Node and read_lcm_log hand pictures over as numpy
arrays (malformed ones counted and dropped), ChainEnv gives pixels, and
the steering example gets the snake closer to the red ball."""

import os
import subprocess
import sys
import threading

import numpy as np
import pytest

import mrsim
from camera_scenario import camera_snake
from conftest import source
from mrsim.env import ChainEnv


def red_columns(image):
    """Mean column of the clearly red pixels (None: none), and their share."""
    rgb = image.astype(int)
    red = (rgb[:, :, 0] > 120) & (rgb[:, :, 0] > 2 * rgb[:, :, 1]) & \
        (rgb[:, :, 0] > 2 * rgb[:, :, 2])
    if not red.any():
        return None, 0.0
    return np.nonzero(red)[1].mean(), red.mean()


@pytest.fixture(scope="module")
def sim():
    return mrsim.Simulation(camera_snake(ball=(0.6, 0.0)))


def test_cameras_lists_each_camera_with_its_size(sim):
    cameras = sim.cameras()
    assert len(cameras) == 1
    assert cameras[0]["name"] == "snake/sm0/camera"
    assert (cameras[0]["width"], cameras[0]["height"]) == (80, 60)
    assert sim.cameras("snake") == cameras


def test_a_red_ball_ahead_is_red_in_the_middle_of_the_picture(sim):
    image = sim.camera_image(robot=0, camera=0)
    assert image.shape == (60, 80, 3) and image.dtype == np.uint8
    column, share = red_columns(image)
    assert share > 0.01
    assert 30 < column < 50


def test_a_ball_to_the_left_is_left_in_the_picture():
    left = mrsim.Simulation(camera_snake(ball=(1.0, 0.3)))
    column, _ = red_columns(left.camera_image())
    assert column is not None and column < 30


def test_a_fixed_camera_on_a_scene_object_sees_the_ball():
    # A post 0.6 m beyond the ball, 0.2 m up, looking back at it.
    watched = mrsim.Simulation(camera_snake(ball=(0.6, 0.0),
                                            post=(1.2, 0.0, 0.2),
                                            post_tilt=12))
    cameras = watched.cameras("scene")
    assert len(cameras) == 1
    assert cameras[0]["name"] == "scene/obj1/camera"
    assert cameras[0]["owner"] == "scene"
    assert cameras[0]["scene_object"] == 1
    assert cameras[0]["sensor_module"] == -1
    assert len(watched.cameras()) == 1  # the robot's own
    image = watched.camera_image("scene", 0)
    assert image.shape == (60, 80, 3)
    column, share = red_columns(image)
    assert share > 0.01
    assert 30 < column < 50
    assert np.array_equal(image,
                          watched.camera_image("scene", "scene/obj1/camera"))
    with pytest.raises(IndexError, match="the scene objects have 1 camera"):
        watched.camera_image("scene", 3)
    with pytest.raises(IndexError, match="the loose sensor modules have no"):
        watched.camera_image("loose")


def test_the_same_state_gives_the_same_picture(sim):
    assert np.array_equal(sim.camera_image(), sim.camera_image())
    assert np.array_equal(sim.camera_image(camera="snake/sm0/camera"),
                          sim.camera_image(camera=0))


def test_pictures_can_be_taken_from_other_threads(sim):
    expected = sim.camera_image()
    other = mrsim.Simulation(camera_snake(ball=(0.6, 0.0)))
    got = []

    def take():
        got.append(sim.camera_image())
        got.append(other.camera_image())

    threads = [threading.Thread(target=take) for _ in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(got) == 6
    assert all(np.array_equal(g, expected) for g in got)


def test_the_picture_follows_the_simulation():
    moving = mrsim.Simulation(camera_snake(ball=(0.6, 0.0)))
    before = moving.camera_image()
    moving.set_controller(mrsim.Gait.from_parameters(
        {"A_yaw": 0.7, "phi_yaw": 0.8, "T": 1.5}, axes="yaw"), period=0.05)
    moving.run(1.0)
    assert not np.array_equal(before, moving.camera_image())


def test_a_bad_robot_or_camera_names_what_exists(sim):
    with pytest.raises(IndexError, match=r"1 robot"):
        sim.camera_image(robot=3)
    with pytest.raises(KeyError, match=r"robots: snake"):
        sim.camera_image(robot="eel")
    with pytest.raises(IndexError,
                       match=r"camera 2: robot 'snake' has 1 camera\(s\): "
                             r"0 'snake/sm0/camera' 80x60"):
        sim.camera_image(camera=2)
    with pytest.raises(IndexError, match=r"camera 'x'"):
        sim.camera_image(camera="x")
    blind = mrsim.Simulation(camera_snake(camera=False))
    assert blind.cameras() == []
    with pytest.raises(IndexError, match=r"robot 'snake' has no camera"):
        blind.camera_image()


# Pictures over LCM ---------------------------------------------------

def picture_fields(image, seq=1, **kw):
    h, w, _ = image.shape
    fields = {"utime": 1000 * seq, "seq": seq, "robot": "snake",
              "sender": "test", "camera": 0, "sensor_module": 0,
              "name": "snake/sm0/camera", "sim_time": seq * 0.1,
              "width": w, "height": h, "encoding": "rgb8",
              "data": image.tobytes()}
    fields.update(kw)
    return fields


def gradient(w=32, h=16):
    """A picture whose every pixel differs from its neighbours."""
    y, x = np.mgrid[0:h, 0:w]
    return np.stack([x * 7 % 256, y * 13 % 256, (x + y) % 256],
                    axis=2).astype(np.uint8)


def test_a_node_yields_pictures_as_arrays_and_drops_malformed_ones():
    node = mrsim.Node(url="memq://", name="py")
    image = gradient()
    node.subscribe("camera", "snake")
    channel = node.channel("camera", "snake")
    assert channel == "MRSIM_CAMERA_snake"
    node.publish(channel, "camera_image_t", picture_fields(image, seq=1))
    # Bytes that disagree with the size, and an unknown encoding.
    node.publish(channel, "camera_image_t",
                 picture_fields(image, seq=2, width=33))
    node.publish(channel, "camera_image_t",
                 picture_fields(image, seq=3, encoding="png"))
    node.publish(channel, "camera_image_t",
                 picture_fields(image[::-1].copy(), seq=4, camera=1))
    got = list(node.images("snake", timeout=0.5))
    assert [p.seq for p in got] == [1, 4]
    assert node.malformed == 2
    assert got[0].image.dtype == np.uint8
    assert np.array_equal(got[0].image, image)
    assert got[0].time == pytest.approx(0.1)
    assert np.array_equal(got[1].image, image[::-1])
    node.publish(channel, "camera_image_t", picture_fields(image, seq=5))
    node.publish(channel, "camera_image_t",
                 picture_fields(image, seq=6, camera=1))
    assert node.next_image("snake", camera=1, timeout=1).seq == 6


def test_read_lcm_log_decodes_pictures(tmp_path):
    log = tmp_path / "camera.lcmlog"
    writer = mrsim.Node(url="file://%s?mode=w" % log, name="py")
    channel = writer.channel("camera", "snake")
    image = gradient()
    writer.publish(channel, "camera_image_t", picture_fields(image, seq=1))
    writer.publish(channel, "camera_image_t",
                   picture_fields(image, seq=2, height=17))  # malformed
    writer.publish(channel, "camera_image_t",
                   picture_fields(255 - image, seq=3))
    writer.close()
    del writer
    logs = mrsim.read_lcm_log(str(log))
    pictures = logs[channel]
    assert np.array_equal(pictures["seq"], [1, 3])
    assert pictures["encoding"] == ["rgb8", "rgb8"]
    assert np.array_equal(pictures["width"], [32, 32])
    assert len(pictures["image"]) == 2
    assert np.array_equal(pictures["image"][0], image)
    assert np.array_equal(pictures["image"][1], 255 - image)
    assert len(pictures["log_time"]) == 2


# ChainEnv ------------------------------------------------------------

def test_chain_env_observes_pixels():
    env = ChainEnv(camera_snake(ball=(0.6, 0.0)), observation="camera",
                   episode_seconds=0.2, control_period=0.05)
    assert env.observation_space.shape == (60, 80, 3)
    assert env.observation_space.dtype == np.uint8
    obs, _ = env.reset(seed=1)
    assert obs.shape == (60, 80, 3) and obs.dtype == np.uint8
    assert env.observation_space.contains(obs)
    assert red_columns(obs)[1] > 0.01
    obs, _, terminated, _, _ = env.step(env.action_space.sample())
    assert not terminated and env.observation_space.contains(obs)


def test_chain_env_without_a_camera_says_so():
    with pytest.raises(ValueError, match=r"robot 'snake' .* has no camera"):
        ChainEnv(camera_snake(camera=False), observation="camera")


# The example ---------------------------------------------------------

def run_example(scenario):
    """(distance at the start, at the end) the steering example prints."""
    r = subprocess.run(
        [sys.executable, source("examples/python/camera_steering.py"),
         "--scenario", scenario, "--seconds", "10"],
        capture_output=True, text=True, timeout=240, env=dict(os.environ))
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    start = float(lines[0].split(": ")[1].split()[0])
    end = float(lines[-1].split(": ")[1].split()[0])
    assert "at the start" in lines[0] and "at the end" in lines[-1]
    return start, end


def test_the_steering_example_gets_a_yaw_snake_closer_to_the_ball(tmp_path):
    scenario = str(tmp_path / "camera_snake.xml")
    camera_snake(ball=(1.2, 0.5)).save(scenario)
    start, end = run_example(scenario)
    assert end < start - 0.2


def test_the_steering_example_gets_the_camera_snake_closer_to_the_ball():
    start, end = run_example(source("scenarios/camera_snake.xml"))
    assert end < start - 0.1
