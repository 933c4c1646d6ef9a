"""Reading mrsim's logs into dictionaries of numpy arrays.

``read_csv_folder(folder)`` reads every CSV mrsim-log wrote into
``{channel: {column: array}}``; ``read_lcm_log(path)`` does the same for an
lcm-logger log, decoding with the logger's own C++ flatteners, so both give
the same column names (``time``, ``module3.joint.angle``, ``com.x``, ...);
its camera pictures come as numpy arrays (column ``image``).
``read_mcap(path)`` reads an MCAP file of mrsim-log --mcap (protobuf or
JSON messages) into the same shape, columns named by the JSON paths of the message's
fields (``modules.3.position.0``, ``com.1``). ``pandas.DataFrame(logs[channel])``
takes a channel as it is.
"""

from __future__ import annotations

import json
import os
import re
import warnings
from typing import Dict, List, Optional

import numpy as np

from . import _core

_PART = re.compile(r"^(?P<channel>.*)\.part(?P<n>\d+)$")


def read_csv(path: str) -> Dict[str, object]:
    """One CSV file: {column: float array} (text columns as lists of str).
    Raises LogError naming the file and line of a malformed row."""
    return _core.read_csv(os.fspath(path))


def _concat(parts):
    """Rows of several parts of one channel (shape changes): the union of
    their columns, NaN (or '') where a part has no such column."""
    if len(parts) == 1:
        return parts[0]
    names = []
    for p in parts:
        names += [n for n in p if n not in names]
    out = {}
    for n in names:
        chunks = []
        text = any(isinstance(p.get(n), list) for p in parts)
        for p in parts:
            rows = len(next(iter(p.values()))) if p else 0
            v = p.get(n)
            if v is None:
                v = [""] * rows if text else np.full(rows, np.nan)
            chunks.append(list(v) if text else np.asarray(v, dtype=float))
        out[n] = sum(chunks, []) if text else np.concatenate(chunks)
    return out


def read_csv_folder(folder: str) -> Dict[str, Dict[str, object]]:
    """Every CSV of a mrsim-log folder: {channel: {column: array}}. A
    channel written in parts (CHANNEL.part2.csv, ... after its message
    shape changed) is read as one, columns missing in a part as NaN."""
    folder = os.fspath(folder)
    if not os.path.isdir(folder):
        raise _core.LogError("%s: no such folder" % folder)
    parts: Dict[str, list] = {}
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".csv"):
            continue
        stem = name[:-4]
        m = _PART.match(stem)
        channel, n = (m.group("channel"), int(m.group("n"))) if m else (stem, 1)
        parts.setdefault(channel, []).append((n, os.path.join(folder, name)))
    return {ch: _concat([read_csv(p) for _, p in sorted(files)])
            for ch, files in sorted(parts.items())}


def read_lcm_log(path: str,
                 channels: Optional[str] = None) -> Dict[str, Dict[str, object]]:
    """An lcm-logger log: {channel: {column: array}}, columns named as
    mrsim-log names them plus 'log_time' (s). A camera channel
    (<prefix>_CAMERA_<robot>) has the picture messages' fields (seq,
    sim_time, camera, name, width, height, encoding, ...) and 'image': a
    list of (H, W, 3) uint8 arrays (JPEGs decoded; malformed pictures are
    left out). channels: a regex of the channels to read (default: all)."""
    return _core.read_lcm_log(os.fspath(path), channels or "")


def _flatten(value, prefix: str, row: Dict[str, object]) -> None:
    """One JSON value into row, keys joined by '.' (list items by index)."""
    if isinstance(value, dict):
        for k, v in value.items():
            _flatten(v, prefix + "." + k if prefix else k, row)
    elif isinstance(value, list):
        for i, v in enumerate(value):
            _flatten(v, "%s.%d" % (prefix, i) if prefix else str(i), row)
    else:
        row[prefix] = value


def _columns(rows: List[Dict[str, object]]) -> Dict[str, object]:
    """Rows into columns: numbers (and null: NaN) as float arrays, text as
    lists of str; a column missing from a row is NaN (or '')."""
    names: Dict[str, None] = {}
    for r in rows:
        for n in r:
            names.setdefault(n, None)
    out: Dict[str, object] = {}
    for n in names:
        cells = [r.get(n) for r in rows]
        if any(isinstance(c, str) for c in cells):
            out[n] = ["" if c is None else str(c) for c in cells]
        else:
            out[n] = np.array([np.nan if c is None else float(c) for c in cells],
                              dtype=float)
    return out


def read_mcap(path: str,
              channels: Optional[str] = None) -> Dict[str, Dict[str, object]]:
    """An MCAP file of mrsim-log --mcap: {channel: {column: array}}, each
    message's fields (protobuf messages decoded by the C++ reader, with the
    schema in the file, into the JSON the json encoding writes) flattened into columns named by their path
    (``seq``, ``modules.0.position.2``; booleans as 0/1), plus 'log_time'
    (s). channels: a regex of the channels to read (default: all). A file
    whose logger was killed reads up to its last whole chunk, with a
    warning. Raises LogError naming the byte of a malformed file."""
    topics, complete = _core.read_mcap_messages(os.fspath(path), channels or "")
    if not complete:
        warnings.warn("%s: the file ends before its summary (its writer was "
                      "stopped); read up to its last whole chunk" % path)
    out = {}
    for topic, (_schema, times, data) in topics.items():
        rows = []
        for t, text in zip(times, data):
            row: Dict[str, object] = {}
            _flatten(json.loads(text), "", row)
            row["log_time"] = float(t)
            rows.append(row)
        out[topic] = _columns(rows)
    return out
