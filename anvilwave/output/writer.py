"""Writing result folders without leaving half-written results behind."""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path


class ResultWriter:
    """Collect output files in a temporary folder; move them into place only on success.

    Parameters
    ----------
    directory : str or Path
        The result folder filled on success.

    Attributes
    ----------
    staging : Path
        The folder being filled.

    Examples
    --------
    >>> with ResultWriter("results/run") as out:
    ...     out.part("summary.json").write_text("{}")
    """

    def __init__(self, directory: str | Path):
        self.directory = Path(directory)
        self._tmp: Path | None = None
        self._names: list[str] = []

    def __enter__(self) -> ResultWriter:
        self.directory.parent.mkdir(parents=True, exist_ok=True)
        self._tmp = Path(tempfile.mkdtemp(prefix=".partial-", dir=self.directory.parent))
        return self

    def part(self, name: str) -> Path:
        """Path of an output file being written (``name`` may name a sub-folder).

        Parameters
        ----------
        name : str
            File name relative to the result folder.

        Returns
        -------
        Path
            Where to write it in the staging folder.
        """
        self._names.append(name)
        path = self._tmp / name
        path.parent.mkdir(parents=True, exist_ok=True)
        return path

    @property
    def staging(self) -> Path:
        """The folder being filled (for tools that write several files of their own)."""
        return self._tmp

    def __exit__(self, exc_type, exc, tb) -> bool:
        try:
            if exc_type is None:
                self.directory.mkdir(parents=True, exist_ok=True)
                for item in self._tmp.iterdir():
                    target = self.directory / item.name
                    if target.is_dir() and item.is_dir():
                        shutil.rmtree(target)
                    item.replace(target)
        finally:
            shutil.rmtree(self._tmp, ignore_errors=True)
        return False
