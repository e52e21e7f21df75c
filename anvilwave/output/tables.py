"""Tables of results: CSV time series with ``name [unit]`` headers, and the binning of blow rows
into blow counts (no physics here)."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np


def write_csv(columns: dict[str, np.ndarray], path: str | Path) -> Path:
    """Write time series with a ``name [unit]`` header (DESIGN.md).

    Parameters
    ----------
    columns : dict of str to numpy.ndarray
        Columns named ``name [unit]``, all of one length.
    path : str or Path
        The CSV file.

    Returns
    -------
    Path
        The written file.
    """
    names = list(columns)
    data = np.column_stack([columns[n] for n in names])
    with open(path, "w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(names)
        for row in data:
            writer.writerow([f"{x:.9g}" for x in row])
    return Path(path)


def write_dict_rows(rows: list[dict], names, path: str | Path) -> Path:
    """Write rows of mixed values (numbers and names) with the header ``names``.

    Parameters
    ----------
    rows : list of dict
        The rows, keyed by column name.
    names : sequence of str
        The column names, in order.
    path : str or Path
        The CSV file.

    Returns
    -------
    Path
        The written file.
    """
    with open(path, "w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(names))
        writer.writeheader()
        writer.writerows(rows)
    return Path(path)


def read_csv(path: str | Path) -> dict[str, np.ndarray]:
    """Read a CSV written by :func:`write_csv`.

    Parameters
    ----------
    path : str or Path
        The CSV file.

    Returns
    -------
    dict of str to numpy.ndarray
        The columns by header name.
    """
    with open(path, newline="") as fh:
        reader = csv.reader(fh)
        names = next(reader)
        rows = np.array([[float(x) for x in row] for row in reader])
    return {n: rows[:, i] for i, n in enumerate(names)}


def blow_count_profile(rows: list[dict], bin_size: float = 0.25) -> tuple[np.ndarray, ...]:
    """(depth at the bin's bottom [m], blows in the bin [-]) of the blows per ``bin_size``.

    Parameters
    ----------
    rows : list of dict
        Blow rows, each with a ``tip_depth [m]`` entry.
    bin_size : float, default 0.25
        Depth bin [m].

    Returns
    -------
    depth : numpy.ndarray
        Depth at the bottom of each bin [m].
    blows : numpy.ndarray
        Number of blows in each bin [-].
    """
    tip = np.array([r["tip_depth [m]"] for r in rows])
    if tip.size == 0:
        return np.zeros(0), np.zeros(0)
    edges = np.arange(math.floor(tip[0] / bin_size) * bin_size, tip[-1] + bin_size, bin_size)
    counts, _ = np.histogram(tip, bins=edges)
    return edges[1:], counts.astype(float)
