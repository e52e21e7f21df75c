"""Validated reading of TOML input files (and the one TOML writer, :func:`toml_dumps`).

Every user-facing configuration (anvil, hammer, pile, system) is read through :class:`Table`,
so that a bad value always stops with one line naming the file, the key and the rule that was
broken, and an unknown key is rejected instead of silently ignored.
"""

from __future__ import annotations

import json
import math
import numbers
import re
import tomllib
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

_MISSING = object()


class InputError(Exception):
    """A user input broke a rule.

    ``str(error)`` is a single line ``<file>: <key>: <rule>`` meant to be shown to the user as it
    is, without a traceback.

    Parameters
    ----------
    source : str or Path
        The input file (stored as a string).
    key : str
        The dotted key that broke the rule ("" for the file as a whole).
    rule : str
        The rule that was broken, as a sentence fragment.
    """

    def __init__(self, source: str, key: str, rule: str):
        self.source = str(source)
        self.key = key
        self.rule = rule
        where = f"{self.source}: {key}" if key else self.source
        super().__init__(f"{where}: {rule}")

    def __reduce__(self):
        """Pickled with its three fields, so an error raised in a worker process reaches the
        parent as itself (process pools, dask).
        """
        return (InputError, (self.source, self.key, self.rule))


class InputRecord:
    """The input files read while it is active (:func:`record_inputs`), in the order read.

    Parameters
    ----------
    context : dict, optional
        What the files were read for (e.g. ``{"command": "drive", "arguments": {...}}``),
        recorded with them in a result folder's ``inputs.json``.

    Attributes
    ----------
    files : list of Path
        The files read (absolute, each once).
    context : dict
        As given.
    """

    def __init__(self, context: dict[str, Any] | None = None):
        self.files: list[Path] = []
        self.context = dict(context or {})

    def add(self, path: str | Path) -> None:
        """Record that ``path`` was read.

        A file not there, or one recorded already, is left out.

        Parameters
        ----------
        path : str or Path
            The file read.
        """
        path = Path(path).resolve()
        if path.is_file() and path not in self.files:
            self.files.append(path)


_RECORDS: list[InputRecord] = []
"""The active records, innermost last."""


@contextmanager
def record_inputs(**context: Any):
    """Record the input files read by anvilwave while the block runs.

    Every file read through :func:`read_text` (hence :func:`read_toml` and
    :meth:`Table.from_file`) or announced with :func:`note_input` is recorded; a result folder
    written inside the block saves a copy of each with its SHA-256
    (:mod:`anvilwave.output.writer`).

    Parameters
    ----------
    **context : dict, optional
        Stored as :attr:`InputRecord.context` (the command and its arguments).

    Yields
    ------
    InputRecord
        The record, filled as the files are read.

    Examples
    --------
    >>> with record_inputs(command="impact") as record:
    ...     pass
    >>> record.files
    []
    """
    record = InputRecord(context)
    _RECORDS.append(record)
    try:
        yield record
    finally:
        _RECORDS.remove(record)


def active_record() -> InputRecord | None:
    """The innermost active :class:`InputRecord`.

    Returns
    -------
    InputRecord or None
        None outside :func:`record_inputs`.
    """
    return _RECORDS[-1] if _RECORDS else None


def note_input(path: str | Path) -> None:
    """Record an input file read without :func:`read_text` (a mesh, a JSON table).

    Parameters
    ----------
    path : str or Path
        The file read.
    """
    for record in _RECORDS:
        record.add(path)


def read_text(path: str | Path, encoding: str = "utf-8") -> str:
    """The text of an input file; a missing or unreadable file is an :class:`InputError`.

    Parameters
    ----------
    path : str or Path
        The file.
    encoding : str, default "utf-8"
        Its text encoding.

    Returns
    -------
    str
        The file's text.

    Raises
    ------
    InputError
        If the file is missing or cannot be read.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding=encoding)
    except FileNotFoundError:
        raise InputError(path, "", "file not found") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(path, "", f"cannot be read ({exc})") from None
    note_input(path)
    return text


def read_toml(path: str | Path) -> dict[str, Any]:
    """Read a TOML file, turning I/O and syntax problems into :class:`InputError`.

    Parameters
    ----------
    path : str or Path
        The TOML file.

    Returns
    -------
    dict
        The parsed root table.

    Raises
    ------
    InputError
        If the file is missing, unreadable or not valid TOML.
    """
    path = Path(path)
    text = read_text(path)
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(path, "", f"is not valid TOML ({exc})") from None


class Table:
    """A TOML table whose keys are taken one by one with their rules.

    Parameters
    ----------
    data : dict
        The parsed table.
    source : str or Path
        The file it came from (used in error messages).
    prefix : str
        Dotted key of this table inside the file ("" for the root).
    """

    def __init__(self, data: dict[str, Any], source: str | Path, prefix: str = ""):
        if not isinstance(data, dict):
            raise InputError(source, prefix or "<root>", "must be a table")
        self.data = data
        self.source = str(source)
        self.prefix = prefix
        self._used: set[str] = set()

    @classmethod
    def from_file(cls, path: str | Path) -> Table:
        """The root table of a TOML file.

        Parameters
        ----------
        path : str or Path
            The TOML file.

        Returns
        -------
        Table
            Its root table.
        """
        return cls(read_toml(path), path)

    # ------------------------------------------------------------------ helpers
    def key(self, name: str) -> str:
        """The dotted key of ``name`` inside the file.

        Parameters
        ----------
        name : str
            Key in this table.

        Returns
        -------
        str
            ``prefix.name`` (or ``name`` in the root table).
        """
        return f"{self.prefix}.{name}" if self.prefix else name

    def error(self, name: str, rule: str) -> InputError:
        """An :class:`InputError` for key ``name`` of this table.

        Parameters
        ----------
        name : str
            Key in this table.
        rule : str
            The rule that was broken.

        Returns
        -------
        InputError
            The error (not raised).
        """
        return InputError(self.source, self.key(name), rule)

    def has(self, name: str) -> bool:
        """Whether the table has key ``name``.

        Parameters
        ----------
        name : str
            Key in this table.

        Returns
        -------
        bool
            True if present.
        """
        return name in self.data

    record: list[tuple[str, str]] | None = None
    """When a list, every key asked for is appended to it as (file, dotted key without array
    indices):
    the tests check that each accepted key is documented (``anvilwave.config.schema``)."""

    def _get(self, name: str, default: Any) -> Any:
        self._used.add(name)
        if Table.record is not None:
            Table.record.append((self.source, re.sub(r"\[\d+\]", "", self.key(name))))
        if name in self.data:
            return self.data[name]
        if default is _MISSING:
            raise self.error(name, "is required but missing")
        return default

    # ------------------------------------------------------------------ typed getters
    def number(
        self,
        name: str,
        default: Any = _MISSING,
        *,
        gt: float | None = None,
        ge: float | None = None,
        lt: float | None = None,
        le: float | None = None,
        unit: str = "",
    ) -> float:
        """A finite real number, with optional bounds.

        Parameters
        ----------
        name : str
            Key in this table.
        default : float, optional
            Value when the key is absent; the key is required when omitted.
        gt : float, optional
            Exclusive lower bound [unit].
        ge : float, optional
            Inclusive lower bound [unit].
        lt : float, optional
            Exclusive upper bound [unit].
        le : float, optional
            Inclusive upper bound [unit].
        unit : str, default ""
            Unit named in error messages.

        Returns
        -------
        float
            The value (None only through an explicit default of None).

        Raises
        ------
        InputError
            If the key is missing, not a finite number, or out of bounds.
        """
        value = self._get(name, default)
        if value is None:
            return None  # only reachable through an explicit default of None
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.error(name, f"must be a number{_unit(unit)}, got {value!r}")
        value = float(value)
        if not math.isfinite(value):
            raise self.error(name, f"must be finite, got {value!r}")
        for bound, ok, word in (
            (gt, lambda v, b: v > b, "greater than"),
            (ge, lambda v, b: v >= b, "at least"),
            (lt, lambda v, b: v < b, "less than"),
            (le, lambda v, b: v <= b, "at most"),
        ):
            if bound is not None and not ok(value, bound):
                raise self.error(name, f"must be {word} {bound:g}{_unit(unit)}, got {value:g}")
        return value

    def integer(self, name: str, default: Any = _MISSING, *, ge: int | None = None) -> int:
        """An integer, with an optional lower bound.

        Parameters
        ----------
        name : str
            Key in this table.
        default : int, optional
            Value when the key is absent; the key is required when omitted.
        ge : int, optional
            Inclusive lower bound.

        Returns
        -------
        int
            The value.

        Raises
        ------
        InputError
            If the key is missing, not an integer, or below ``ge``.
        """
        value = self._get(name, default)
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.error(name, f"must be an integer, got {value!r}")
        if ge is not None and value < ge:
            raise self.error(name, f"must be at least {ge}, got {value}")
        return int(value)

    def boolean(self, name: str, default: Any = _MISSING) -> bool:
        """A boolean.

        Parameters
        ----------
        name : str
            Key in this table.
        default : bool, optional
            Value when the key is absent; the key is required when omitted.

        Returns
        -------
        bool
            The value.

        Raises
        ------
        InputError
            If the key is missing or not true/false.
        """
        value = self._get(name, default)
        if not isinstance(value, bool):
            raise self.error(name, f"must be true or false, got {value!r}")
        return value

    def string(self, name: str, default: Any = _MISSING, *, choices=None) -> str:
        """A string, optionally one of ``choices``.

        Parameters
        ----------
        name : str
            Key in this table.
        default : str, optional
            Value when the key is absent; the key is required when omitted.
        choices : sequence of str, optional
            The allowed values.

        Returns
        -------
        str
            The value (None only through an explicit default of None).

        Raises
        ------
        InputError
            If the key is missing, not a string, or not one of ``choices``.
        """
        value = self._get(name, default)
        if value is None:
            return None
        if not isinstance(value, str):
            raise self.error(name, f"must be a string, got {value!r}")
        if choices is not None and value not in choices:
            raise self.error(name, f"must be one of {', '.join(map(repr, choices))}, got {value!r}")
        return value

    def path(self, name: str, default: Any = _MISSING) -> Path | None:
        """A file path, relative to the directory of the input file.

        Parameters
        ----------
        name : str
            Key in this table.
        default : str, optional
            Value when the key is absent; the key is required when omitted.

        Returns
        -------
        Path or None
            The path (None through a default of None).
        """
        value = self.string(name, default)
        if value is None:
            return None
        path = Path(value)
        if not path.is_absolute():
            path = Path(self.source).parent / path
        return path

    def array(
        self, name: str, default: Any = _MISSING, *, columns: int | None = None, min_rows: int = 1
    ) -> np.ndarray:
        """A list of numbers, or with ``columns`` a list of rows of that many numbers.

        Parameters
        ----------
        name : str
            Key in this table.
        default : array_like, optional
            Value when the key is absent; the key is required when omitted.
        columns : int, optional
            Number of numbers in each row; a flat list when None.
        min_rows : int, default 1
            Fewest entries (rows).

        Returns
        -------
        numpy.ndarray
            The values, 1D, or 2D with ``columns`` columns (None through a default of None).

        Raises
        ------
        InputError
            If the value is missing, of the wrong shape, or not finite numbers.
        """
        value = self._get(name, default)
        if value is None:
            return None
        shape_rule = f"a list of [{', '.join(['x'] * columns)}] rows" if columns else "a list"
        if not isinstance(value, list) or len(value) < min_rows:
            raise self.error(name, f"must be {shape_rule} of numbers with at least {min_rows} "
                                   "entries")
        for i, item in enumerate(value):
            for j, x in enumerate(item if isinstance(item, list) else [item]):
                if isinstance(x, bool) or not isinstance(x, numbers.Real):
                    where = f"row {i + 1}" + (f", column {j + 1}" if isinstance(item, list)
                                              else "")
                    raise self.error(name, f"{where}: {x!r} is not a number ({shape_rule} of "
                                           "numbers)")
        try:
            arr = np.array(value, dtype=float)
        except (TypeError, ValueError):
            raise self.error(name, f"must be {shape_rule} of numbers") from None
        expected_ndim = 2 if columns else 1
        if arr.ndim != expected_ndim or (columns and arr.shape[1] != columns):
            raise self.error(name, f"must be {shape_rule} of numbers")
        if not np.all(np.isfinite(arr)):
            bad = np.argwhere(~np.isfinite(arr))[0]
            raise self.error(name, f"row {int(bad[0]) + 1}: must contain finite numbers only")
        return arr

    def table(self, name: str, required: bool = True) -> Table | None:
        """A sub-table.

        Parameters
        ----------
        name : str
            Key in this table.
        required : bool, default True
            Whether the sub-table must be present.

        Returns
        -------
        Table or None
            The sub-table (None when absent and not required).

        Raises
        ------
        InputError
            If the key is missing (and required) or not a table.
        """
        value = self._get(name, _MISSING if required else None)
        if value is None:
            return None
        if not isinstance(value, dict):
            raise self.error(name, "must be a table")
        return Table(value, self.source, self.key(name))

    def tables(self, name: str, required: bool = True) -> list[Table]:
        """An array of tables (``[[name]]``).

        Parameters
        ----------
        name : str
            Key in this table.
        required : bool, default True
            Whether the array must be present (absent and not required: empty).

        Returns
        -------
        list of Table
            The tables.

        Raises
        ------
        InputError
            If the key is missing (and required) or not an array of tables.
        """
        value = self._get(name, _MISSING if required else [])
        if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
            raise self.error(name, "must be an array of tables ([[...]])")
        return [Table(v, self.source, f"{self.key(name)}[{i}]") for i, v in enumerate(value)]

    def finish(self) -> None:
        """Reject the keys nobody asked for (typos, unsupported options).

        Raises
        ------
        InputError
            Naming the first unknown key and the allowed ones.
        """
        unknown = sorted(set(self.data) - self._used)
        if unknown:
            allowed = ", ".join(sorted(self._used)) or "none"
            raise self.error(unknown[0], f"unknown key (allowed here: {allowed})")


def _unit(unit: str) -> str:
    return f" {unit}" if unit else ""


# ---------------------------------------------------------------------------- writing
def toml_dumps(root: dict[str, Any]) -> str:
    """TOML text of a nested dict of strings, booleans, numbers, lists and tables.

    Floats are written with ``repr`` so they read back bit for bit.

    Parameters
    ----------
    root : dict
        The root table.

    Returns
    -------
    str
        The TOML text.

    Raises
    ------
    TypeError
        If a value cannot be written to TOML.
    """
    lines: list[str] = []
    _toml_table(root, [], lines)
    return "\n".join(lines).lstrip("\n") + "\n"


def _toml_table(table: dict[str, Any], path: list[str], lines: list[str]) -> None:
    def is_table(v):
        return isinstance(v, dict)

    def is_table_array(v):
        return isinstance(v, list) and v and all(isinstance(x, dict) for x in v)

    for key, value in table.items():
        if not (is_table(value) or is_table_array(value)):
            lines.append(f"{_toml_key(key)} = {_toml_value(value)}")
    for key, value in table.items():
        if is_table(value):
            lines += ["", f"[{'.'.join(map(_toml_key, path + [key]))}]"]
            _toml_table(value, path + [key], lines)
        elif is_table_array(value):
            for item in value:
                lines += ["", f"[[{'.'.join(map(_toml_key, path + [key]))}]]"]
                _toml_table(item, path + [key], lines)


def _toml_key(key: str) -> str:
    return key if key.replace("_", "").replace("-", "").isalnum() else json.dumps(key)


def _toml_value(value: Any) -> str:
    if isinstance(value, bool | np.bool_):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        value = float(value)
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value)  # a JSON string is a valid TOML basic string
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, dict):  # an inline table (inside an array of mixed values)
        return "{" + ", ".join(f"{_toml_key(k)} = {_toml_value(v)}"
                               for k, v in value.items()) + "}"
    raise TypeError(f"cannot write {type(value).__name__} to TOML")
