"""The pile head's ring kernel (anvilwave/pile/head_kernel.py) against Newton's second law and
reciprocity. Its check against the reference FEA's own pile, driven by the contact forces the
FEA records, is tests/test_study_pile_port.py::test_ring_kernel_reproduces_the_fea_pile."""

import numpy as np
import pytest

from anvilwave.anvil_rom.fem.geometry import STEEL
from anvilwave.pile.head_kernel import ring_kernel

R_IN, R_OUT, LENGTH, STEP, RINGS = 0.95, 1.0, 2.0, 2e-5, 2


@pytest.fixture(scope="module")
def kernel():
    return ring_kernel(STEEL, R_IN, R_OUT, LENGTH, STEP, 2000, RINGS, 0.1)


def test_free_tube_moves_off_with_the_impulse_over_its_mass(kernel):
    """A unit hat force on every ring of a free 2 m tube (impulse h per ring): over 40 ms the
    rings' mean displacement is the rigid motion K h t / M (t from the hat's peak, M the tube's
    mass) plus vibrations about it, so its least-squares slope is K h / M within 0.5 %
    (measured 0.03 %; what is left is the vibrations' share of the fit)."""
    edges = np.linspace(R_IN, R_OUT, RINGS + 1)
    weights = np.diff(edges**2) / (R_OUT**2 - R_IN**2)
    mean = np.einsum("i,kij,j->k", weights, kernel, np.ones(RINGS))
    t = np.arange(mean.size) * STEP
    slope = np.polyfit(t, mean, 1)[0]
    mass = STEEL.density * np.pi * (R_OUT**2 - R_IN**2) * LENGTH
    assert slope == pytest.approx(RINGS * STEP / mass, rel=0.005)


def test_kernel_is_reciprocal(kernel):
    """Maxwell-Betti: ring i's displacement under a force on ring j is ring j's under the same
    force on ring i, at every lag: each column of the kernel is its own run, so the symmetry
    comes from K and M being symmetric and the loads and outputs the same vectors. To 1e-10 of
    the largest entry (measured 6e-13, round-off)."""
    scale = np.abs(kernel).max()
    assert np.abs(kernel - kernel.transpose(0, 2, 1)).max() <= 1e-10 * scale
