"""Reading mrsim's logs into dictionaries of numpy arrays.

``read_csv_folder(folder)`` reads every CSV mrsim-log wrote into
``{channel: {column: array}}``; ``read_lcm_log(path)`` does the same for an
lcm-logger log, decoding with the logger's own C++ flatteners, so both give
the same column names (``time``, ``module3.joint.angle``, ``com.x``, ...).
``pandas.DataFrame(logs[channel])`` takes a channel as it is.
"""

from __future__ import annotations

import os
import re
from typing import Dict, Optional

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
    mrsim-log names them plus 'log_time' (s). channels: a regex of the
    channels to read (default: all)."""
    return _core.read_lcm_log(os.fspath(path), channels or "")
