"""The sweep's index table (one row per run) and ``load``, which reads a sweep folder back.

``index.csv`` is always written; ``index.parquet`` too when pyarrow is installed (it keeps the
columns' types; the CSV is read back with numbers, booleans and empty cells recognised). Both
are rewritten whole, under a temporary name, at the end of every sweep, from the runs'
``meta.json`` files, which stay the source of truth.
"""

from __future__ import annotations

import csv
import json
import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np

from . import folder as layout
from .execute import CLIP, FINAL, PROBES
from .spec import RunSpec

CSV = "index.csv"
PARQUET = "index.parquet"
FIRST = ["run_id", "index", "seed"]
LAST = ["outcome", "error", "steps", "frames", "sim_seconds", "wall_seconds", "path"]


def has_pyarrow() -> bool:
    try:
        import pyarrow
        import pyarrow.parquet  # noqa: F401
    except ImportError:
        return False
    return True


def rows_for(root: Path, runs: list[RunSpec]) -> list[dict[str, Any]]:
    """One row per committed run of ``runs``, in sweep order."""
    rows = []
    for run in runs:
        meta = layout.read_meta(root, run.run_id)
        if meta is None:
            continue
        row = {"run_id": run.run_id, "index": run.index, "seed": run.seed, **run.params}
        row.update({k: meta.get(k) for k in LAST if k != "path"})
        row["path"] = f"{layout.RUNS}/{run.run_id}"
        rows.append(row)
    return rows


def _columns(rows: list[dict[str, Any]]) -> list[str]:
    params: list[str] = []
    for row in rows:
        params += [k for k in row if k not in FIRST and k not in LAST and k not in params]
    return FIRST + params + LAST


def write_index(root: Path, rows: list[dict[str, Any]]) -> list[Path]:
    """Write ``index.csv`` (and ``index.parquet`` with pyarrow); returns the paths written."""
    columns = _columns(rows)
    written = []
    tmp = root / f".{CSV}.tmp"
    with tmp.open("w", newline="") as f:
        writer = csv.DictWriter(f, columns)
        writer.writeheader()
        for row in rows:
            writer.writerow({k: "" if row.get(k) is None else _csv_cell(row.get(k))
                             for k in columns})
    os.replace(tmp, root / CSV)
    written.append(root / CSV)
    if has_pyarrow():
        import pyarrow as pa
        import pyarrow.parquet as pq

        table = pa.Table.from_pylist([{k: row.get(k) for k in columns} for row in rows],
                                     schema=None) if rows else pa.table({k: [] for k in columns})
        tmp = root / f".{PARQUET}.tmp"
        pq.write_table(table, tmp)
        os.replace(tmp, root / PARQUET)
        written.append(root / PARQUET)
    return written


def _csv_cell(value: Any) -> str:
    return repr(value) if isinstance(value, float) else str(value)  # repr: every digit kept


def _parse(text: str) -> Any:
    if text == "":
        return None
    if text in ("True", "False"):
        return text == "True"
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def read_rows(root: Path) -> list[dict[str, Any]]:
    """The index's rows: from Parquet when it and pyarrow are there, else from the CSV."""
    root = Path(root)
    if (root / PARQUET).exists() and has_pyarrow():
        import pyarrow.parquet as pq

        return pq.read_table(root / PARQUET).to_pylist()
    with (root / CSV).open(newline="") as f:
        return [{k: _parse(v) for k, v in row.items()} for row in csv.DictReader(f)]


class Run:
    """One run of a loaded sweep: its index row, its folder, and its outputs on demand."""

    def __init__(self, root: Path, row: dict[str, Any]) -> None:
        self.row = row
        self.path = root / row["path"]

    @property
    def run_id(self) -> str:
        return self.row["run_id"]

    @property
    def ok(self) -> bool:
        return self.row["outcome"] == "ok"

    @property
    def meta(self) -> dict[str, Any]:
        return json.loads((self.path / layout.META).read_text())

    @property
    def clip(self) -> Path | None:
        """The run's mp4, or None (no clip kept, or the run failed)."""
        path = self.path / CLIP
        return path if path.exists() else None

    def probes(self) -> dict[str, np.ndarray]:
        """``{"t": (T,), name: (T, ...)}``, sample k at the time of frame k."""
        return _npz(self.path / PROBES)

    def final(self) -> dict[str, np.ndarray]:
        """The final state: ``time``, ``particles.<array>`` and ``bodies.<array>``."""
        return _npz(self.path / FINAL)

    def __repr__(self) -> str:
        return f"Run({self.run_id}, {self.row['outcome']})"


def _npz(path: Path) -> dict[str, np.ndarray]:
    if not path.exists():
        raise FileNotFoundError(f"{path} does not exist (not kept by this sweep, or the run "
                                "failed)")
    with np.load(path) as data:
        return {name: data[name] for name in data.files}


class SweepData:
    """A sweep folder read back: ``rows`` (the index), iteration over ``Run``s, ``[run_id]``
    or ``[i]``, and ``to_pandas()``."""

    def __init__(self, root: str | Path) -> None:
        self.root = Path(root)
        if not (self.root / CSV).exists():
            raise FileNotFoundError(f"{self.root} has no {CSV}: not a sweep folder, or its "
                                    "sweep never finished a run")
        self.rows = read_rows(self.root)
        self.settings = json.loads((self.root / layout.SETTINGS).read_text())

    def __len__(self) -> int:
        return len(self.rows)

    def __iter__(self) -> Iterator[Run]:
        return (Run(self.root, row) for row in self.rows)

    def __getitem__(self, key: int | str) -> Run:
        if isinstance(key, str):
            for row in self.rows:
                if row["run_id"] == key:
                    return Run(self.root, row)
            raise KeyError(f"no run {key!r} in {self.root}")
        return Run(self.root, self.rows[key])

    @property
    def failed(self) -> list[Run]:
        return [run for run in self if not run.ok]

    def to_pandas(self):
        import pandas as pd

        return pd.DataFrame(self.rows)

    def __repr__(self) -> str:
        return f"SweepData({str(self.root)!r}, {len(self)} runs, {len(self.failed)} failed)"


def load(folder: str | Path) -> SweepData:
    """Read a sweep folder back: ``load("out").rows``, ``for run in load("out"): run.probes()``."""
    return SweepData(folder)
