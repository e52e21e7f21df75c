"""Arrays for the time-stepping kernels: 64-byte aligned, so that every vector load of a sweep
falls in one cache line whatever address the allocator returns (a sweep over an unaligned
array runs up to 20 % slower, and by how much depends on where it happened to land)."""

from __future__ import annotations

import numpy as np

ALIGNMENT = 64
"""[bytes]: a cache line, and the width of an AVX-512 register."""


def aligned_zeros(shape, dtype=np.float64) -> np.ndarray:
    """A zero-filled C-contiguous array of ``shape`` whose first element is ALIGNMENT-aligned.

    Parameters
    ----------
    shape : int or tuple of int
        Shape of the array.
    dtype : data-type, default numpy.float64
        Element type.

    Returns
    -------
    numpy.ndarray
        The aligned zero array (a view into a slightly larger buffer).
    """
    dtype = np.dtype(dtype)
    count = int(np.prod(shape, dtype=np.int64))
    buffer = np.zeros(count * dtype.itemsize + ALIGNMENT, dtype=np.uint8)
    offset = -buffer.ctypes.data % ALIGNMENT
    return buffer[offset:offset + count * dtype.itemsize].view(dtype).reshape(shape)


def aligned_copy(array) -> np.ndarray:
    """An ALIGNMENT-aligned C-contiguous copy of ``array``.

    Parameters
    ----------
    array : array_like
        The values to copy.

    Returns
    -------
    numpy.ndarray
        The aligned copy, same shape and dtype.
    """
    array = np.asarray(array)
    out = aligned_zeros(array.shape, array.dtype)
    out[...] = array
    return out
