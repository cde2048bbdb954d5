"""Atomic file output: every file is written to a temporary name beside it and renamed into place,
so an interrupted run never leaves a half-written CSV, JSON or PNG behind."""

from __future__ import annotations

import contextlib
import csv
import json
import os
import tempfile
from pathlib import Path

import numpy as np

_UMASK = os.umask(0)
os.umask(_UMASK)


@contextlib.contextmanager
def atomic_path(path):
    """Yields a temporary path in the same directory (same suffix, so matplotlib and pyarrow pick
    the format); renames it to `path` when the block ends without an exception."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix, dir=path.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o666 & ~_UMASK)  # mkstemp makes 0600; give the file the usual permissions
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def write_text(path, text: str):
    with atomic_path(path) as tmp:
        Path(tmp).write_text(text)
    return Path(path)


def write_json(path, obj):
    return write_text(path, json.dumps(obj, indent=2) + "\n")


def write_csv(path, cols: dict, every: int = 1):
    """Columns (name -> array, equal lengths) as CSV with a header, rows 0, every, 2*every, ...
    and always the last row; numbers with 9 significant digits."""
    names = list(cols)
    data = np.column_stack([np.asarray(cols[n], float) for n in names])
    if every > 1 and len(data):
        idx = np.arange(0, len(data), every)
        if idx[-1] != len(data) - 1:
            idx = np.append(idx, len(data) - 1)
        data = data[idx]
    with atomic_path(path) as tmp:
        with open(tmp, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(names)
            for r in data:
                w.writerow([f"{x:.9g}" for x in r])
    return Path(path)
