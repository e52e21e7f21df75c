"""What a long step is doing, one line on stderr, and progress bars whose estimate is true.

A step announces itself only when it runs longer than :data:`SLOW_STEP` (a timer prints its
line then), so a quick step stays silent and a slow one (a kernel compiling on a first run, the
reference FEA, a dask cluster starting) never looks hung. A tqdm bar opened by :func:`bar`
shows no remaining-time estimate until ``warm`` items are done: the first items carry the
compilation of the kernels and would make the estimate wrong.
"""

from __future__ import annotations

import sys
import threading

SLOW_STEP = 2.0
"""A step running longer than this prints what it does [s]."""

NO_ESTIMATE = "{desc}: {percentage:3.0f}%|{bar}| {n_fmt}/{total_fmt} [{elapsed}, estimating]"
"""tqdm bar format without the remaining time (while the first items warm up)."""


def say(message: str, enabled: bool = True, stream=None) -> None:
    """Print one progress line to stderr.

    Parameters
    ----------
    message : str
        The line, e.g. ``"running the reference FEA..."``.
    enabled : bool, default True
        Print it (False: nothing, the quiet case).
    stream : file-like, optional
        Where to print (default: ``sys.stderr``).
    """
    if enabled:
        print(message, file=stream or sys.stderr, flush=True)


class Step:
    """A context manager that says what its block does once it has run :data:`SLOW_STEP`.

    Parameters
    ----------
    message : str
        The line printed (to stderr) if the block is still running after ``after``.
    enabled : bool, default True
        False: never print.
    after : float, default SLOW_STEP
        Delay before the line is printed [s]; 0 prints it at once.
    stream : file-like, optional
        Where to print (default: ``sys.stderr``).
    """

    def __init__(self, message: str, enabled: bool = True, after: float = SLOW_STEP,
                 stream=None):
        self.message = message
        self.enabled = enabled
        self.after = after
        self.stream = stream
        self.printed = False
        self._timer = None
        self._lock = threading.Lock()

    def _print(self) -> None:
        with self._lock:
            if self._timer is not None:
                say(self.message, stream=self.stream)
                self.printed = True

    def __enter__(self):
        if self.enabled:
            if self.after <= 0:
                say(self.message, stream=self.stream)
                self.printed = True
            else:
                self._timer = threading.Timer(self.after, self._print)
                self._timer.daemon = True
                self._timer.start()
        return self

    def __exit__(self, *exc):
        with self._lock:
            timer, self._timer = self._timer, None
        if timer is not None:
            timer.cancel()
        return False


def bar(total, *, enabled: bool = True, warm: int = 1, **kwargs):
    """A tqdm bar (stderr) without a remaining-time estimate until ``warm`` items are done.

    Parameters
    ----------
    total : int or float
        The bar's total.
    enabled : bool, default True
        False: None (no bar).
    warm : int, default 1
        Items done (counted from the bar's ``initial``) before the estimate is shown.
    **kwargs
        Further tqdm arguments (``desc``, ``unit``, ``initial``, ``bar_format`` for the
        estimating phase and after ...).

    Returns
    -------
    tqdm.tqdm or None
        The bar; its ``update`` switches to the full format (with the estimate) once warm.
    """
    if not enabled:
        return None
    from tqdm import tqdm

    final = kwargs.pop("bar_format", None)
    initial = kwargs.get("initial", 0)

    class _Warm(tqdm):
        def update(self, n=1):
            result = super().update(n)
            if self.bar_format == NO_ESTIMATE and self.n - initial >= warm:
                self.bar_format = final
                self.refresh()
            return result

    return _Warm(total=total, bar_format=NO_ESTIMATE if warm > 0 else final, **kwargs)


class CtrlC:
    """Remember a Ctrl-C (SIGINT) that a library swallows, so that the run still stops.

    Inside the block SIGINT raises KeyboardInterrupt as by default and is also remembered;
    :meth:`check` raises KeyboardInterrupt if one came, wherever it went (a worker pool that
    reports its SIGINT-ended workers as a broken pool, an event loop that catches the
    interrupt). Outside the main thread it does nothing (signals are the main thread's).
    """

    def __init__(self):
        self.seen = False
        self._previous = None

    def __enter__(self) -> CtrlC:
        import signal

        if threading.current_thread() is threading.main_thread():
            def handler(signum, frame):
                self.seen = True
                raise KeyboardInterrupt

            self._previous = signal.signal(signal.SIGINT, handler)
        return self

    def __exit__(self, *exc) -> None:
        import signal

        if self._previous is not None:
            signal.signal(signal.SIGINT, self._previous)
            self._previous = None

    def check(self) -> None:
        """Raise KeyboardInterrupt if a Ctrl-C came inside the block.

        Raises
        ------
        KeyboardInterrupt
            After a Ctrl-C.
        """
        if self.seen:
            raise KeyboardInterrupt
