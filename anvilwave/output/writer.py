"""Writing result folders without leaving half-written results behind.

A result is staged in a hidden ``.partial-<pid>-*`` folder beside its output folder and moved
into place only when the command succeeded. The output folder gets a small marker,
:data:`MARKER`, naming the command that wrote it, so that another command's result is never
mixed into it. Every problem with the output location (a file in the way, a location that
cannot be written, a disk that fills up) is one :class:`~anvilwave.inputs.InputError` naming
``--out``; the staging folder is removed, and the staging folders of killed runs (their
process gone) are removed by the next run.

A result written inside :func:`anvilwave.inputs.record_inputs` (every command of the command
line runs inside one) records its inputs: a copy of every input file read, under
:data:`INPUTS_DIR`, and the manifest :data:`INPUTS_MANIFEST` with their names relative to the
first one's folder, SHA-256 hashes and sizes, the command and its settings, the version of
anvilwave and the time. Nothing in it is an absolute path.
"""

from __future__ import annotations

import datetime
import hashlib
import json
import os
import shutil
import tempfile
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

from anvilwave.inputs import InputError, InputRecord, active_record

MARKER = ".anvilwave-result"
"""File in an output folder naming the command that wrote it (JSON: ``{"command": ...}``)."""

STAGING_PREFIX = ".partial-"
"""Prefix of the staging folders (``.partial-<pid>-<random>``)."""

INPUTS_DIR = "inputs"
"""Folder of a result holding the copies of its input files."""

INPUTS_MANIFEST = "inputs.json"
"""The manifest of a result's inputs (JSON: ``files``, ``command``, ``arguments`` ...)."""

MAX_COPY_BYTES = 50 * 2**20
"""Input files larger than this [B] are hashed but not copied into :data:`INPUTS_DIR`."""


def software_version() -> str:
    """The version of the installed anvilwave.

    Returns
    -------
    str
        E.g. ``"0.1.0"``; ``"unknown"`` when run from a checkout that is not installed.
    """
    try:
        return version("anvilwave")
    except PackageNotFoundError:
        return "unknown"


def file_sha256(path: str | Path) -> str:
    """The SHA-256 hash of a file's bytes.

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    str
        The hash, 64 hexadecimal digits.
    """
    digest = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(2**20), b""):
            digest.update(block)
    return digest.hexdigest()


def portable(value):
    """A JSON-able value with every absolute path replaced by its file name.

    Parameters
    ----------
    value : object
        A value of a summary (str, Path, number, list, tuple, dict, None).

    Returns
    -------
    object
        The same structure; a string or Path that is an absolute path becomes its last part.
    """
    if isinstance(value, Path) or (isinstance(value, str) and os.path.isabs(value)):
        return Path(value).name
    if isinstance(value, dict):
        return {k: portable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [portable(v) for v in value]
    return value


def _input_names(files: list[Path]) -> list[str]:
    """Names of the input copies: relative to the first file's folder where they lie below
    it, else the file name (made unique with a number)."""
    base = files[0].parent if files else Path()
    names: list[str] = []
    for path in files:
        try:
            name = path.relative_to(base).as_posix()
        except ValueError:
            name = path.name
        stem, suffix, k = Path(name).with_suffix("").as_posix(), Path(name).suffix, 2
        while name in names:
            name, k = f"{stem}-{k}{suffix}", k + 1
        names.append(name)
    return names


def write_inputs(directory: str | Path, record: InputRecord,
                 exclude: str | Path | None = None) -> dict:
    """Save the inputs of ``record`` into a result folder.

    A copy of each file under :data:`INPUTS_DIR` (files above :data:`MAX_COPY_BYTES` are
    hashed only) and the manifest :data:`INPUTS_MANIFEST`.

    Parameters
    ----------
    directory : str or Path
        The result folder (or its staging folder).
    record : InputRecord
        The files read (:func:`anvilwave.inputs.record_inputs`); its ``context`` goes into
        the manifest.
    exclude : str or Path, optional
        Files below this folder are not inputs (a result read back by the command that
        writes it).

    Returns
    -------
    dict
        The manifest written.
    """
    directory = Path(directory)
    skip = [directory.resolve()] + ([Path(exclude).resolve()] if exclude is not None else [])
    files = [p for p in record.files
             if p.is_file() and not any(p.is_relative_to(s) for s in skip)]
    entries = []
    for path, name in zip(files, _input_names(files), strict=True):
        size = path.stat().st_size
        entry = {"name": name, "sha256": file_sha256(path), "bytes": size, "copy": None}
        if size <= MAX_COPY_BYTES:
            target = directory / INPUTS_DIR / name
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(path, target)
            entry["copy"] = f"{INPUTS_DIR}/{name}"
        entries.append(entry)
    manifest = {
        "anvilwave_version": software_version(),
        "written": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        **portable(record.context),
        "files": entries,
    }
    (directory / INPUTS_MANIFEST).write_text(json.dumps(manifest, indent=2) + "\n")
    return manifest


def write_marker(directory: str | Path, command: str) -> None:
    """Mark a folder as the result of ``command`` (its :data:`MARKER`).

    For the commands that fill their folder themselves (``batch``); :class:`ResultWriter`
    writes it for the others.

    Parameters
    ----------
    directory : str or Path
        The result folder.
    command : str
        The command that wrote it.
    """
    (Path(directory) / MARKER).write_text(json.dumps({"command": command}) + "\n")


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


def check_output(directory: str | Path, command: str | None = None, force: bool = False
                 ) -> Path:
    """Refuse an output folder before any work.

    Refused: a file in the way (the folder itself or a folder above it), a location that
    cannot be written, or a folder holding the result of another command (unless ``force``:
    that result is then replaced whole when the new one is written).

    Parameters
    ----------
    directory : str or Path
        The output folder (``--out``).
    command : str, optional
        The command that will write it; a folder holding another command's result is refused.
    force : bool, default False
        Accept a folder holding another command's result (``--force``).

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
    try:
        _check_location(directory, command, force)
    except OSError as exc:  # a folder on the way that may not be looked into, say
        raise _out_error(directory, f"cannot be written ({exc.strerror or exc})") from None
    return directory


def _check_location(directory: Path, command: str | None, force: bool) -> None:
    """The checks of :func:`check_output` (OSErrors left to it)."""
    if directory.exists() and not directory.is_dir():
        raise _out_error(directory, "is a file, not a folder (choose a folder to write into)")
    existing = directory
    while not existing.exists():
        if existing.parent == existing:
            break
        existing = existing.parent
    if existing != directory and not existing.is_dir():
        raise _out_error(directory, f"cannot be made: {existing} is a file, not a folder")
    if command is not None and directory.is_dir() and not force:
        held = result_command(directory)
        if held is not None and held != command:
            raise _out_error(directory, f"holds the result of 'anvilwave {held}', not of "
                                        f"'{command}' (choose another folder, remove it or "
                                        "give --force to replace it)")
    # a probe: permissions, read-only file systems, ACLs
    fd, probe = tempfile.mkstemp(prefix=STAGING_PREFIX + "probe-", dir=existing)
    os.close(fd)
    os.unlink(probe)


class ResultWriter:
    """Collect output files in a temporary folder; move them into place only on success.

    Parameters
    ----------
    directory : str or Path
        The result folder filled on success.
    command : str, optional
        The command writing it: recorded in the folder's :data:`MARKER`; a folder holding
        another command's result is refused.
    force : bool, default False
        Replace a folder holding another command's result (``--force``).

    Attributes
    ----------
    staging : Path
        The folder being filled.

    Notes
    -----
    A folder that holds a result (it has a :data:`MARKER`) is replaced whole by the new one, so
    no file of an earlier result stays beside it; a folder without a marker keeps its other
    files.

    Examples
    --------
    >>> with ResultWriter("results/run", command="impact") as out:
    ...     out.part("summary.json").write_text("{}")
    """

    def __init__(self, directory: str | Path, command: str | None = None, force: bool = False):
        self.directory = Path(directory)
        self.command = command
        self.force = force
        self._tmp: Path | None = None
        self._names: list[str] = []

    def __enter__(self) -> ResultWriter:
        check_output(self.directory, self.command, self.force)
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
                        write_marker(self._tmp, self.command)
                    record = active_record()
                    if record is not None:
                        write_inputs(self._tmp, record, exclude=self.directory)
                    self._move_into_place()
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

    def _move_into_place(self) -> None:
        """Move the staged files into the result folder; an earlier result there is replaced
        whole (renamed aside, the staging folder renamed into place, the old one removed)."""
        if (self.directory / MARKER).is_file():
            mode = self.directory.stat().st_mode & 0o7777
            aside = Path(tempfile.mkdtemp(prefix=f"{STAGING_PREFIX}{os.getpid()}-old-",
                                          dir=self.directory.parent))
            try:
                self.directory.replace(aside / "result")
            except OSError:  # the folder cannot be renamed (the working directory, a mount)
                shutil.rmtree(aside, ignore_errors=True)
                for item in self.directory.iterdir():
                    if item.is_dir() and not item.is_symlink():
                        shutil.rmtree(item)
                    else:
                        item.unlink()
            else:
                self._tmp.chmod(mode)  # the old folder's permissions, not the staging's 0700
                self._tmp.replace(self.directory)
                shutil.rmtree(aside, ignore_errors=True)
                return
        self.directory.mkdir(parents=True, exist_ok=True)
        for item in self._tmp.iterdir():
            target = self.directory / item.name
            if target.is_dir() and item.is_dir():
                shutil.rmtree(target)
            item.replace(target)
