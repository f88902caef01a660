"""A sweep's folder: ``sweep.json``, ``runs/<run id>/`` and the index; atomic run commits.

A run is written into ``runs/.tmp-<run id>-<pid>-<random>/`` and renamed to ``runs/<run id>/``
when everything in it (``meta.json`` last) is on disk. A rename within one folder is atomic, so
a run folder either holds a whole run or does not exist: a crash, SIGKILL or a full disk leaves
only a ``.tmp-`` folder, which the next sweep on the folder removes.
"""

from __future__ import annotations

import fcntl
import json
import os
import secrets
import shutil
from pathlib import Path
from typing import Any

RUNS = "runs"
META = "meta.json"
SETTINGS = "sweep.json"
LOCK = ".sweep.lock"
TMP_PREFIX = ".tmp-"


def run_dir(root: Path, run_id: str) -> Path:
    return root / RUNS / run_id


def read_meta(root: Path, run_id: str) -> dict[str, Any] | None:
    """A committed run's meta.json, or None when the run has not been committed."""
    try:
        return json.loads((run_dir(root, run_id) / META).read_text())
    except FileNotFoundError:
        return None


def new_tmp_dir(root: Path, run_id: str) -> Path:
    """A fresh temporary folder beside the final one (same filesystem: rename is atomic)."""
    path = root / RUNS / f"{TMP_PREFIX}{run_id}-{os.getpid()}-{secrets.token_hex(3)}"
    path.mkdir(parents=True)
    return path


def write_json(path: Path, data: dict) -> None:
    path.write_text(json.dumps(data, indent=2, sort_keys=False) + "\n")


def commit(tmp: Path, root: Path, run_id: str) -> bool:
    """Rename ``tmp`` to the run's folder; False (and ``tmp`` removed) if a copy of the run got
    there first (a retried task whose first attempt finished after all)."""
    _fsync_tree(tmp)
    final = run_dir(root, run_id)
    try:
        os.rename(tmp, final)
    except OSError:
        if final.exists():
            shutil.rmtree(tmp, ignore_errors=True)
            return False
        raise
    return True


def _fsync_tree(folder: Path) -> None:
    # The files' data reaches the disk before the rename makes them look complete (a power cut
    # between the two would otherwise leave a committed run with empty files).
    for child in folder.iterdir():
        if child.is_file():
            with open(child, "rb") as f:
                os.fsync(f.fileno())


def remove_stale(root: Path) -> int:
    """Remove the temporary folders a killed sweep left; returns how many."""
    runs = root / RUNS
    if not runs.is_dir():
        return 0
    stale = [p for p in runs.iterdir() if p.name.startswith(TMP_PREFIX)]
    for path in stale:
        shutil.rmtree(path, ignore_errors=True)
    return len(stale)


def check_settings(root: Path, settings: dict[str, Any]) -> None:
    """Write ``sweep.json``, or check that the folder's sweep matches this one: a rerun may add
    runs (values, draws, seeds) but not change what every run is (its length, outputs)."""
    path = root / SETTINGS
    if path.exists():
        old = json.loads(path.read_text())
        differ = [k for k in settings if old.get(k) != settings[k]]
        if differ:
            k = differ[0]
            raise ValueError(f"{root} holds a sweep with {k} = {old.get(k)!r}, not {settings[k]!r}"
                             f"; use another output folder (or delete this one)")
        return
    write_json(path, settings)


class FolderLock:
    """One sweep at a time per folder (an exclusive flock, released when the process dies)."""

    def __init__(self, root: Path) -> None:
        self.path = root / LOCK
        self._file = None

    def __enter__(self) -> FolderLock:
        self._file = open(self.path, "w")
        try:
            fcntl.flock(self._file, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            self._file.close()
            raise RuntimeError(f"another sweep is writing to {self.path.parent}") from None
        return self

    def __exit__(self, *exc) -> None:
        fcntl.flock(self._file, fcntl.LOCK_UN)
        self._file.close()
