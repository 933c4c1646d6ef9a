"""Shared fixtures of the Python package's tests (run by ctest with
PYTHONPATH=<build>/python, MRSIM_SOURCE_DIR and MRSIM_BINARY_DIR set)."""

import os
import subprocess
import time

import pytest

SOURCE_DIR = os.environ.get(
    "MRSIM_SOURCE_DIR",
    os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
BINARY_DIR = os.environ.get("MRSIM_BINARY_DIR",
                            os.path.join(SOURCE_DIR, "build"))


def source(path):
    """A file of the source tree."""
    return os.path.join(SOURCE_DIR, path)


def program(name):
    """A program of the build tree (build/bin/NAME)."""
    return os.path.join(BINARY_DIR, "bin", name)


def lcm_url(port):
    """Each process test's own LCM URL (ttl=0), shifted by
    MRSIM_TEST_PORT_OFFSET as the C++ tests' TestLcmUrl."""
    port += int(os.environ.get("MRSIM_TEST_PORT_OFFSET", "0"))
    return "udpm://239.255.76.67:%d?ttl=0" % port


class Child:
    """A program run for a test, its output in a file; killed at the end."""

    def __init__(self, args, log_path):
        self.log_path = log_path
        self._log = open(log_path, "w")
        self.proc = subprocess.Popen(args, stdout=self._log,
                                     stderr=subprocess.STDOUT)

    def wait(self, timeout):
        """The exit status, waiting at most timeout s."""
        return self.proc.wait(timeout=timeout)

    def output(self):
        with open(self.log_path) as f:
            return f.read()

    def stop(self):
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self._log.close()


@pytest.fixture
def children():
    """Start programs with children.start(args, name); all stopped after."""
    started = []

    class Starter:
        def start(self, args, log_path):
            c = Child(args, log_path)
            started.append(c)
            return c

    yield Starter()
    for c in started:
        c.stop()


def wait_until(predicate, timeout, what):
    """Polls predicate (which waits itself, e.g. on LCM) until it holds."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if predicate():
            return
    raise AssertionError("timed out waiting for " + what)
