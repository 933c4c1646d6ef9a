"""mrsim.Node: a Python program as an LCM process beside mrsim-sim.

A Node subscribes to the states, scene, simulator status and gait status
channels and publishes joint commands, simulator controls and gait
commands with the message types, sequence numbers and acknowledgements of
the C++ programs. It can publish and receive every message type the .lcm
files define (``listen``, ``publish``, ``send``), with every field: the
conversions and the channel table (``CHANNELS``) are generated from the
.lcm files. Messages are decoded by the C++ message types (with the
project's checked decoding; messages that do not decode are counted in
``Node.malformed`` and dropped).

With a key (``key_file``, else ``$MRSIM_KEY_FILE``, as the C++ programs)
the node signs what it publishes and drops unsigned, forged and replayed
messages with the C++ programs' transport; ``Node.auth_counts()`` counts
them (docs/security.md).

A controller in lockstep (``mrsim-sim --clock lockstep --controllers NAME``)::

    node = mrsim.Node(name="NAME")
    gait = mrsim.Gait("forward")
    for state in node.states("snake", timeout=5):
        node.send_targets("snake", gait.targets(state.time, state), state)

Like mrsim-gait, the node answers a state the simulator sends again (it
waits for it) with the same command, and never hands the same state twice.

Camera pictures (mrsim-camera, docs/camera.md) come as Messages whose
``image`` is an (H, W, 3) uint8 numpy array (JPEGs decoded), beside the
message's fields (``seq``, ``time``, ``camera``, ``name``, ...)::

    for picture in node.images("snake", timeout=5):
        red = picture.image[:, :, 0]

A picture whose sizes, bytes or JPEG disagree is counted in ``malformed``
and dropped, like any message that does not decode.
"""

from __future__ import annotations

import collections
import os
import time as _time
import types
from typing import (Any, Callable, Dict, Iterator, List, Optional, Sequence,
                    Tuple)

from . import _core

DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0"

# The channel prefix of the programs' --prefix default.
DEFAULT_PREFIX: str = _core.DEFAULT_CHANNEL_PREFIX

# Every message type of the .lcm files: {type: {"fields": [...], "consts"}}.
MESSAGE_TYPES: Dict[str, Dict[str, Any]] = _core.message_types()

# The channel of each message type by its short name ("state",
# "sim_status", "run", ...), from the .lcm files' '// channel:' lines.
CHANNELS: Dict[str, Dict[str, Any]] = {
    c["name"]: c for c in _core.channels()}

# sim_control_t commands (the consts of sim_control_t.lcm).
_COMMANDS = MESSAGE_TYPES["sim_control_t"]["consts"]
PAUSE: int = _COMMANDS["PAUSE"]
RESUME: int = _COMMANDS["RESUME"]
STEP: int = _COMMANDS["STEP"]
RESET: int = _COMMANDS["RESET"]
SAVE_CHECKPOINT: int = _COMMANDS["SAVE_CHECKPOINT"]
LOAD_CHECKPOINT: int = _COMMANDS["LOAD_CHECKPOINT"]
SET_SPEED: int = _COMMANDS["SET_SPEED"]
QUIT: int = _COMMANDS["QUIT"]
DETACH: int = _COMMANDS["DETACH"]
ATTACH: int = _COMMANDS["ATTACH"]

# Messages kept per channel for the iterators; older ones are dropped.
_QUEUE_LENGTH = 10000


class Message(types.SimpleNamespace):
    """A decoded message: its fields as attributes (numeric arrays as
    numpy, nested structs as Message, arrays of them as lists)."""


def _message(value: Any) -> Any:
    if isinstance(value, dict):
        return Message(**{k: _message(v) for k, v in value.items()})
    if isinstance(value, list):
        return [_message(v) for v in value]
    return value


def _type_name(kind: str) -> str:
    """An .lcm type name; "sim_status" is taken for "sim_status_t"."""
    if kind in MESSAGE_TYPES or kind == "state":
        return kind
    if kind + "_t" in MESSAGE_TYPES:
        return kind + "_t"
    raise ValueError("unknown message type %r (one of %s)" %
                     (kind, ", ".join(sorted(MESSAGE_TYPES))))


class ControlError(RuntimeError):
    """The simulator or a gait controller refused a request; str() says why."""


class Node:
    """An LCM node: subscribe to mrsim's channels, publish commands."""

    def __init__(self, url: Optional[str] = None,
                 prefix: str = DEFAULT_PREFIX,
                 key_file: Optional[str] = None,
                 name: Optional[str] = None,
                 accept_replays: bool = False) -> None:
        """Opens LCM.

        url: the LCM URL (default: $LCM_DEFAULT_URL, else mrsim's default
        udpm://239.255.76.67:7667?ttl=0). prefix: the channel prefix the
        programs were started with (--prefix; channels whose default prefix
        is another, the optimiser farm's, keep theirs). name: the sender
        name, what
        mrsim-sim --controllers lists (default python-<pid>).
        key_file: a key written by ``mrsim keygen``, as the programs'
        --key-file (None: $MRSIM_KEY_FILE, else unsigned): every message
        is signed, and received ones that are unsigned, forged or replayed
        are dropped and counted (auth_counts()). A key file that is
        missing, readable by group or others or not a key raises
        mrsim.KeyFileError (a ValueError) naming it. accept_replays: as
        --accept-replays, take signed messages whatever their timestamp
        (a log played back with lcm-logplayer).
        """
        if not prefix:
            raise ValueError("prefix: expected a non-empty channel prefix")
        url = url or os.environ.get("LCM_DEFAULT_URL") or DEFAULT_URL
        self.url = url
        self.prefix = prefix
        self.name = name or "python-%d" % os.getpid()
        self._lcm = _core.LcmTransport(url, key_file or "",
                                       bool(accept_replays))
        self._subscribed: Dict[Tuple[str, str], bool] = {}
        self._callbacks: Dict[Tuple[str, str],
                              List[Callable[[Any], None]]] = {}
        self._queues: Dict[Tuple[str, str], collections.deque] = {}
        self._heard: Dict[str, bool] = {}
        self._control_seq = 0
        self._gait_seq = 0

    # Channels -----------------------------------------------------------
    def channel(self, what: str, robot: Optional[str] = None) -> str:
        """The channel of `what`, a name of CHANNELS ('state', 'command',
        'gait', 'gait_status', 'scene', 'sim_control', 'sim_status', the
        farm's 'run', 'job', ...): <prefix><infix>[<robot>]; robot: the
        robot's name, for 'job' the shard (two hex digits)."""
        spec = CHANNELS.get(what)
        if spec is None:
            raise ValueError("expected one of %s, got %r" %
                             (", ".join(CHANNELS), what))
        prefix = (self.prefix if spec["default_prefix"] == DEFAULT_PREFIX
                  else spec["default_prefix"])
        if not spec["suffix"]:
            return prefix + spec["infix"]
        if not robot:
            raise ValueError("%s: give the %s" % (what, spec["suffix"]))
        return prefix + spec["infix"] + robot

    def state_channel(self, robot: str) -> str:
        """<prefix>_STATE_<robot>."""
        return self.channel("state", robot)

    def command_channel(self, robot: str) -> str:
        """<prefix>_COMMAND_<robot>."""
        return self.channel("command", robot)

    def _subscribe(self, channel: str, kind: str) -> Tuple[str, str]:
        """Subscribes `channel` as `kind` ('state': mrsim.State objects,
        else an .lcm type); returns the key of its queue."""
        kind = _type_name(kind)
        key = (channel, kind)
        if key not in self._subscribed:
            if kind == "state":
                self._lcm.subscribe(channel, "robot_state_t", True)
            else:
                self._lcm.subscribe(channel, kind)
            self._subscribed[key] = True
            self._queues[key] = collections.deque(maxlen=_QUEUE_LENGTH)
            self._callbacks[key] = []
        return key

    def _channel_of(self, what: str, robot: Optional[str]) -> Tuple[str, str]:
        kind = "state" if what == "state" else None
        channel = self.channel(what, robot)
        return self._subscribe(channel, kind or CHANNELS[what]["type"])

    def subscribe(self, what: str, robot: Optional[str] = None,
                  callback: Optional[Callable[[Any], None]] = None) -> None:
        """Listens to a channel of CHANNELS: 'state' (mrsim.State objects),
        'camera' (pictures: Messages with an image array) or 'gait_status'
        of a robot, 'scene', 'sim_status', or any other
        ('command', 'run', ...; a Message with every field);
        callback(message) is called from spin_once()."""
        key = self._channel_of(what, robot)
        if callback is not None:
            self._callbacks[key].append(callback)

    def listen(self, channel: str, type: str,
               callback: Optional[Callable[[Any], None]] = None) -> None:
        """Listens to any channel as any .lcm type (MESSAGE_TYPES): each
        message a Message with every field (a robot_state_t too); read with
        next_on() or on_... callbacks from spin_once()."""
        key = self._subscribe(channel, type)
        if callback is not None:
            self._callbacks[key].append(callback)

    def on_state(self, robot: str, callback: Callable[[Any], None]) -> None:
        """callback(state) for every new state of the robot (mrsim.State)."""
        self.subscribe("state", robot, callback)

    def on_scene(self, callback: Callable[[Any], None]) -> None:
        """callback(scene) for every scene message (object_index, poses)."""
        self.subscribe("scene", None, callback)

    def on_sim_status(self, callback: Callable[[Any], None]) -> None:
        """callback(status) for every simulator status."""
        self.subscribe("sim_status", None, callback)

    def on_image(self, robot: str, callback: Callable[[Any], None]) -> None:
        """callback(picture) for every camera picture of the robot (a
        Message; picture.image: (H, W, 3) uint8). robot "scene" ("loose"):
        the scene objects' (loose sensor modules') cameras."""
        self.subscribe("camera", robot, callback)

    def on_gait_status(self, robot: str,
                       callback: Callable[[Any], None]) -> None:
        """callback(status) for every gait status of the robot."""
        self.subscribe("gait_status", robot, callback)

    # Receiving ----------------------------------------------------------
    def spin_once(self, timeout: float = 0.1) -> int:
        """Waits up to timeout s for messages, dispatches them to the
        callbacks and iterators; returns how many were new."""
        got = self._lcm.handle(max(0, int(timeout * 1000)))
        delivered = 0
        for channel, kind, msg in got:
            # States come once each: the transport answers re-sent ones
            # again and drops older ones (mrsim-gait's rules).
            if kind != "state":
                msg = _message(msg)
            delivered += 1
            self._heard[channel] = True
            key = (channel, kind)
            queue = self._queues.get(key)
            if queue is not None:
                queue.append(msg)
            for cb in self._callbacks.get(key, ()):
                cb(msg)
        return delivered

    def spin(self, seconds: Optional[float] = None) -> None:
        """Dispatches messages for `seconds` (None: until interrupted)."""
        end = None if seconds is None else _time.monotonic() + seconds
        while end is None or _time.monotonic() < end:
            left = 0.1 if end is None else min(0.1, end - _time.monotonic())
            self.spin_once(max(0.0, left))

    def _next(self, key: Tuple[str, str], timeout: Optional[float],
              accept: Callable[[Any], bool] = lambda m: True) -> Any:
        queue = self._queues[key]
        channel = key[0]
        end = None if timeout is None else _time.monotonic() + timeout
        while True:
            while queue:
                m = queue.popleft()
                if accept(m):
                    return m
            left = 0.25 if end is None else end - _time.monotonic()
            if left <= 0:
                raise TimeoutError("nothing on %s within %s s" %
                                   (channel, timeout))
            self.spin_once(min(left, 0.25))

    def next_state(self, robot: str, timeout: Optional[float] = 5.0):
        """The next new state of the robot; raises TimeoutError."""
        return self._next(self._channel_of("state", robot), timeout)

    def states(self, robot: str,
               timeout: Optional[float] = 5.0) -> Iterator[Any]:
        """Iterates over the robot's new states (mrsim.State); ends when
        none comes within timeout s (None: waits forever)."""
        key = self._channel_of("state", robot)
        queue = self._queues[key]
        while True:
            while queue:  # the fast path of a controller keeping up
                yield queue.popleft()
            try:
                yield self._next(key, timeout)
            except TimeoutError:
                return

    def next_image(self, robot: str, camera: Optional[int] = None,
                   timeout: Optional[float] = 5.0) -> Message:
        """The next camera picture of the robot (of its camera `camera`
        when given; robot "scene" or "loose": of the scene objects' or the
        loose sensor modules' cameras): a Message with image ((H, W, 3)
        uint8), seq, time, camera, name, width, height, encoding; raises
        TimeoutError."""
        return self._next(self._channel_of("camera", robot), timeout,
                          lambda m: camera is None or m.camera == camera)

    def images(self, robot: str, camera: Optional[int] = None,
               timeout: Optional[float] = 5.0) -> Iterator[Message]:
        """Iterates over the robot's camera pictures (of camera `camera`
        when given) as next_image() gives them; ends when none comes
        within timeout s (None: waits forever)."""
        while True:
            try:
                yield self.next_image(robot, camera, timeout)
            except TimeoutError:
                return

    def next_message(self, what: str, robot: Optional[str] = None,
                     timeout: Optional[float] = 5.0):
        """The next message on a channel of CHANNELS ('scene',
        'sim_status', 'gait_status', ...); raises TimeoutError."""
        return self._next(self._channel_of(what, robot), timeout)

    def next_on(self, channel: str, type: str,
                timeout: Optional[float] = 5.0) -> Any:
        """The next message listen(channel, type) received; raises
        TimeoutError."""
        return self._next(self._subscribe(channel, type), timeout)

    def messages(self, what: str, robot: Optional[str] = None,
                 timeout: Optional[float] = 5.0) -> Iterator[Any]:
        """Iterates over 'scene', 'sim_status', 'gait_status' or 'state'
        messages; ends when none comes within timeout s."""
        key = self._channel_of(what, robot)
        while True:
            try:
                yield self._next(key, timeout)
            except TimeoutError:
                return

    # Publishing ---------------------------------------------------------
    def publish(self, channel: str, type: str,
                fields: Dict[str, Any]) -> None:
        """Publishes a message of any .lcm type (MESSAGE_TYPES) on any
        channel from a dict of its fields: left out ones are zero or empty,
        length members follow the arrays; a field of the wrong type or
        size, or beyond its // max:, raises TypeError or ValueError naming
        it. Signed when the node has a key."""
        self._lcm.publish(channel, _type_name(type), fields)

    def send(self, what: str, fields: Dict[str, Any],
             robot: Optional[str] = None) -> None:
        """Publishes a message on a channel of CHANNELS ('sim_control',
        'run', ...) as its type, from a dict of its fields (as publish)."""
        self.publish(self.channel(what, robot), CHANNELS[what]["type"],
                     fields)

    def send_targets(self, robot: str, targets: Sequence[float],
                     state: Any = None) -> None:
        """Publishes joint targets (rad, chain order) for the robot on
        <prefix>_COMMAND_<robot>. With `state`, the command answers it
        (state_seq; what lockstep waits for) and is sent again if the
        simulator sends that state again."""
        if state is not None:
            self._lcm.answer(self.command_channel(robot), robot, self.name,
                             state.seq, int(round(state.time * 1e6)), targets)
            return
        self._lcm.publish_joint_command(self.command_channel(robot), {
            "utime": int(_time.time() * 1e6), "robot": robot,
            "sender": self.name, "state_seq": -1, "target": targets})

    def sim_control(self, command: int, wait: bool = True,
                    timeout: float = 5.0, **fields: Any) -> Optional[Message]:
        """Sends a sim_control_t (PAUSE, RESUME, STEP, ...; fields steps,
        speed, path, robot, lock) and, with wait, returns the simulator's
        acknowledging status. Raises ControlError when the simulator
        refuses it, TimeoutError when it does not answer."""
        key = self._channel_of("sim_status", None)
        if wait and not self._heard.get(key[0]):
            # As mrsim-ctl: a request sent before the simulator listens is
            # lost, so the first one waits for its first status.
            self._next(key, timeout)
        self._control_seq += 1
        seq = self._control_seq
        msg = dict(fields, command=command, seq=seq, sender=self.name,
                   utime=int(_time.time() * 1e6))
        self.send("sim_control", msg)
        if not wait:
            return None
        status = self._next(
            key, timeout,
            lambda s: s.control_seq == seq and s.control_sender == self.name)
        if not status.control_ok:
            raise ControlError(status.last_error or "request refused")
        return status

    def pause(self, **kw: Any) -> Optional[Message]:
        """Pauses the simulator."""
        return self.sim_control(PAUSE, **kw)

    def resume(self, **kw: Any) -> Optional[Message]:
        """Resumes a paused simulator."""
        return self.sim_control(RESUME, **kw)

    def step(self, periods: int = 1, wait: bool = True,
             timeout: float = 5.0) -> Optional[Message]:
        """Runs `periods` control periods, then stays paused; with wait,
        returns the status once they ran (as mrsim-ctl step)."""
        ack = self.sim_control(STEP, wait=wait, timeout=timeout,
                               steps=int(periods))
        if ack is None:
            return None
        want = ack.state_seq + int(periods)
        return self._next(
            self._channel_of("sim_status", None), timeout,
            lambda s: s.mode == "paused" and s.state_seq >= want)

    def reset(self, **kw: Any) -> Optional[Message]:
        """Back to the scenario's initial state."""
        return self.sim_control(RESET, **kw)

    def save_checkpoint(self, path: str, **kw: Any) -> Optional[Message]:
        """Makes the simulator write a checkpoint (a path on its host)."""
        return self.sim_control(SAVE_CHECKPOINT, path=path, **kw)

    def load_checkpoint(self, path: str, **kw: Any) -> Optional[Message]:
        """Makes the simulator load a checkpoint (a path on its host)."""
        return self.sim_control(LOAD_CHECKPOINT, path=path, **kw)

    def set_speed(self, speed: float, **kw: Any) -> Optional[Message]:
        """Real-time factor of the realtime clock (> 0)."""
        return self.sim_control(SET_SPEED, speed=float(speed), **kw)

    def quit(self, **kw: Any) -> Optional[Message]:
        """Stops the simulator."""
        return self.sim_control(QUIT, **kw)

    def detach(self, robot: str, lock: str, **kw: Any) -> Optional[Message]:
        """Releases a lock of a robot."""
        return self.sim_control(DETACH, robot=robot, lock=lock, **kw)

    def attach(self, robot: str, lock: str, **kw: Any) -> Optional[Message]:
        """Re-makes a released lock of a robot."""
        return self.sim_control(ATTACH, robot=robot, lock=lock, **kw)

    def gait_command(self, robot: str, gait: Optional[str] = None,
                     parameters: Optional[Sequence[float]] = None,
                     motion: Optional[str] = None, strength: float = 1.0,
                     direction: Optional[Sequence[float]] = None,
                     wait: bool = True,
                     timeout: float = 5.0) -> Optional[Message]:
        """Sends a gait_command_t to the robot's mrsim-gait: a gait (preset,
        file or name), the seven parameters, a motion with strength, or
        direction (forward, turn). With wait, returns the gait status that
        acknowledges it; raises ControlError when it is rejected."""
        key = self._channel_of("gait_status", robot)
        if wait and not self._heard.get(key[0]):
            self._next(key, timeout)  # mrsim-gait is listening
        msg: Dict[str, Any] = {
            "utime": int(_time.time() * 1e6), "seq": self._gait_seq + 1,
            "sender": self.name, "robot": robot, "gait": gait or "",
            "motion": motion or "", "strength": float(strength)}
        if parameters is not None:
            msg["has_parameters"] = True
            msg["parameters"] = [float(v) for v in parameters]
        if direction is not None:
            forward_turn = [float(v) for v in direction]
            if len(forward_turn) != 2:
                raise ValueError("direction: expected (forward, turn)")
            msg["has_direction"] = True
            msg["forward"], msg["turn"] = forward_turn
        self.send("gait", msg, robot)
        self._gait_seq += 1
        seq = self._gait_seq
        if not wait:
            return None
        status = self._next(
            key, timeout,
            lambda s: s.command_seq == seq and s.command_sender == self.name)
        if status.command_result == "rejected":
            raise ControlError(status.command_error or "gait command rejected")
        return status

    def publish_state(self, state: Any) -> None:
        """Publishes a State as mrsim-sim would (tests, replays)."""
        self._lcm.publish_state(self.state_channel(state.robot), state)

    @property
    def repeated(self) -> int:
        """Re-sent states answered again with the same command."""
        return self._lcm.repeated

    @property
    def malformed(self) -> int:
        """Messages on our channels that did not decode (dropped)."""
        return self._lcm.malformed

    @property
    def signing(self) -> bool:
        """True when the node signs and checks messages (it has a key)."""
        return self._lcm.signing

    def auth_counts(self) -> Dict[str, int]:
        """Signed messages taken ('accepted') and messages dropped as
        'unsigned', 'forged' or 'replayed' (all 0 without a key)."""
        return dict(self._lcm.auth_counts())

    def fileno(self) -> int:
        """LCM's file descriptor (readable when messages wait)."""
        return self._lcm.fileno()

    def close(self) -> None:
        """Closes the LCM connection."""
        self._lcm = None  # type: ignore[assignment]

    def __enter__(self) -> "Node":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()
