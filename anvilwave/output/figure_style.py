"""The footer every saved figure carries, and saving a figure with it.

The footer reads ``anvilwave X.Y.Z · YYYY-MM-DD``: the installed version and the date the
figure was made, small in the bottom right corner. The date is today's (UTC), or that of the
environment variable ``SOURCE_DATE_EPOCH`` (seconds since 1970-01-01 UTC) when it is set, so a
figure can be reproduced byte for byte (https://reproducible-builds.org/specs/source-date-epoch/).
"""

from __future__ import annotations

import datetime
import os
from pathlib import Path

FOOTER_GID = "anvilwave-footer"
"""The ``gid`` of the footer's text artist (how a figure's footer is found again)."""

FOOTER_FONTSIZE = 6.5
"""Font size of the footer [pt]."""


def version() -> str:
    """The installed anvilwave version.

    Returns
    -------
    str
        The version, e.g. ``"0.1.0"``; ``"unknown"`` when anvilwave runs from a checkout that
        is not installed.
    """
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as _version

    try:
        return _version("anvilwave")
    except PackageNotFoundError:
        return "unknown"


def figure_date() -> str:
    """The date a figure is stamped with, ``YYYY-MM-DD`` (UTC).

    Returns
    -------
    str
        The date of ``SOURCE_DATE_EPOCH`` [s since 1970-01-01 UTC] when set and valid, else
        today's.
    """
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    if epoch is not None:
        try:
            moment = datetime.datetime.fromtimestamp(int(epoch), tz=datetime.UTC)
        except (ValueError, OverflowError, OSError):
            moment = datetime.datetime.now(tz=datetime.UTC)
    else:
        moment = datetime.datetime.now(tz=datetime.UTC)
    return moment.strftime("%Y-%m-%d")


def footer_text() -> str:
    """The footer of a figure: ``anvilwave X.Y.Z · YYYY-MM-DD``.

    Returns
    -------
    str
        The footer text (:func:`version`, :func:`figure_date`).
    """
    return f"anvilwave {version()} \u00b7 {figure_date()}"


def footer(fig, below: bool = True):
    """Write the footer into a figure's bottom right corner (once; a second call keeps it).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    below : bool, default True
        Just below the figure's bottom edge, clear of its axis labels (for a figure saved
        cropped to its content, ``bbox_inches="tight"``, which takes the footer in); else
        inside the bottom edge.

    Returns
    -------
    matplotlib.text.Text
        The footer's text artist (``gid`` :data:`FOOTER_GID`).
    """
    for text in fig.texts:
        if text.get_gid() == FOOTER_GID:
            return text
    return fig.text(0.995, -0.004 if below else 0.004, footer_text(), ha="right",
                    va="top" if below else "bottom", fontsize=FOOTER_FONTSIZE, color="0.35",
                    gid=FOOTER_GID)


def save_figure(fig, path: str | Path, dpi: int = 110, tight: bool = True) -> Path:
    """Save a figure as PNG with its footer, then close it.

    The file is written under a temporary name and renamed, so a partial PNG never sits under
    the final name.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    path : str or Path
        The PNG file.
    dpi : int, default 110
        Resolution [dots per inch].
    tight : bool, default True
        Crop to the drawn content, titles, labels and colour bars included
        (``bbox_inches="tight"``), so nothing is clipped.

    Returns
    -------
    Path
        The written figure.
    """
    import matplotlib.pyplot as plt

    path = Path(path)
    footer(fig, below=tight)
    tmp = path.with_name(f".{path.name}.part")
    fig.savefig(tmp, dpi=dpi, format="png", bbox_inches="tight" if tight else None,
                pad_inches=0.08)
    os.replace(tmp, path)
    plt.close(fig)
    return path
