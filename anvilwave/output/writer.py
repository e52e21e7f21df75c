"""Writing result folders without leaving half-written results behind.

A result is staged in a hidden ``.partial-<pid>-*`` folder beside its output folder and moved
into place only when the command succeeded. The output folder gets a small marker,
:data:`MARKER`, naming the command that wrote it, so that another command's result is never
mixed into it. Every problem with the output location (a file in the way, a location that
cannot be written, a disk that fills up) is one :class:`~anvilwave.inputs.InputError` naming
``--out``; the staging folder is removed, and the staging folders of killed runs (their
process gone) are removed by the next run.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from pathlib import Path

from anvilwave.inputs import InputError

MARKER = ".anvilwave-result"
"""File in an output folder naming the command that wrote it (JSON: ``{"command": ...}``)."""

STAGING_PREFIX = ".partial-"
"""Prefix of the staging folders (``.partial-<pid>-<random>``)."""


def _out_error(directory: Path, rule: str) -> InputError:
    return InputError("--out", "", f"{directory}: {rule}")


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def remove_stale_staging(parent: Path) -> list[Path]:
    """Remove the staging folders in ``parent`` whose process is gone (a killed run's).

    Parameters
    ----------
    parent : Path
        The folder the staging folders lie in (the result folder's parent).

    Returns
    -------
    list of Path
        The staging folders removed.
    """
    removed = []
    if not parent.is_dir():
        return removed
    for item in parent.glob(f"{STAGING_PREFIX}*"):
        pid = item.name[len(STAGING_PREFIX):].split("-", 1)[0]
        if item.is_dir() and (not pid.isdigit() or not _pid_alive(int(pid))):
            shutil.rmtree(item, ignore_errors=True)
            removed.append(item)
    return removed


def result_command(directory: str | Path) -> str | None:
    """The command whose result a folder holds.

    Parameters
    ----------
    directory : str or Path
        A result folder.

    Returns
    -------
    str or None
        The command named by its :data:`MARKER`; None without a readable marker.
    """
    try:
        return str(json.loads((Path(directory) / MARKER).read_text())["command"])
    except (OSError, ValueError, KeyError, TypeError):
        return None


def check_output(directory: str | Path, command: str | None = None) -> Path:
    """Refuse an output folder before any work.

    Refused: a file in the way (the folder itself or a folder above it), a location that
    cannot be written, or a folder holding the result of another command.

    Parameters
    ----------
    directory : str or Path
        The output folder (``--out``).
    command : str, optional
        The command that will write it; a folder holding another command's result is refused.

    Returns
    -------
    Path
        The folder.

    Raises
    ------
    anvilwave.inputs.InputError
        Naming ``--out`` and the rule.
    """
    directory = Path(directory)
    if directory.exists() and not directory.is_dir():
        raise _out_error(directory, "is a file, not a folder (choose a folder to write into)")
    existing = directory
    while not existing.exists():
        if existing.parent == existing:
            break
        existing = existing.parent
    if existing != directory and not existing.is_dir():
        raise _out_error(directory, f"cannot be made: {existing} is a file, not a folder")
    if command is not None and directory.is_dir():
        held = result_command(directory)
        if held is not None and held != command:
            raise _out_error(directory, f"holds the result of 'anvilwave {held}', not of "
                                        f"'{command}' (choose another folder or remove it)")
    try:  # a probe: permissions, read-only file systems, ACLs
        fd, probe = tempfile.mkstemp(prefix=STAGING_PREFIX + "probe-", dir=existing)
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        raise _out_error(directory, f"cannot be written ({exc.strerror or exc})") from None
    return directory


class ResultWriter:
    """Collect output files in a temporary folder; move them into place only on success.

    Parameters
    ----------
    directory : str or Path
        The result folder filled on success.
    command : str, optional
        The command writing it: recorded in the folder's :data:`MARKER`; a folder holding
        another command's result is refused.

    Attributes
    ----------
    staging : Path
        The folder being filled.

    Examples
    --------
    >>> with ResultWriter("results/run", command="impact") as out:
    ...     out.part("summary.json").write_text("{}")
    """

    def __init__(self, directory: str | Path, command: str | None = None):
        self.directory = Path(directory)
        self.command = command
        self._tmp: Path | None = None
        self._names: list[str] = []

    def __enter__(self) -> ResultWriter:
        check_output(self.directory, self.command)
        try:
            self.directory.parent.mkdir(parents=True, exist_ok=True)
            remove_stale_staging(self.directory.parent)
            self._tmp = Path(tempfile.mkdtemp(prefix=f"{STAGING_PREFIX}{os.getpid()}-",
                                              dir=self.directory.parent))
        except OSError as exc:
            raise _out_error(self.directory, f"cannot be written ({exc.strerror or exc})") \
                from None
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
                try:
                    if self.command is not None:
                        (self._tmp / MARKER).write_text(
                            json.dumps({"command": self.command}) + "\n")
                    self.directory.mkdir(parents=True, exist_ok=True)
                    for item in self._tmp.iterdir():
                        target = self.directory / item.name
                        if target.is_dir() and item.is_dir():
                            shutil.rmtree(target)
                        item.replace(target)
                except OSError as err:
                    raise _out_error(self.directory, f"cannot be written ({err.strerror or err})"
                                                     "; the result was not written") from None
            elif issubclass(exc_type, OSError) and not isinstance(exc, InputError):
                raise _out_error(self.directory, f"cannot be written ({exc.strerror or exc}); "
                                                 "the result was not written") from None
        finally:
            if self._tmp is not None:
                shutil.rmtree(self._tmp, ignore_errors=True)
        return False
