"""The pile-port study's ring contact (benchmarks/study_pile_port.py): its complementarity
solver against exhaustive enumeration of the active sets, and the uniform-gap limit."""

import importlib.util
import itertools
import sys
from pathlib import Path

import numpy as np
import pytest

PATH = Path(__file__).resolve().parents[1] / "benchmarks" / "study_pile_port.py"


@pytest.fixture(scope="module")
def study():
    spec = importlib.util.spec_from_file_location("study_pile_port", PATH)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclass looks its module up
    spec.loader.exec_module(module)
    yield module
    del sys.modules[spec.name]


def enumerate_lcp(M, g):
    """The one active set whose forces are >= 0 and whose open contacts stay open (M SPD: the
    LCP solution is unique), by trying all 2^K sets."""
    K = g.size
    for active in itertools.product((False, True), repeat=K):
        a = np.array(active)
        F = np.zeros(K)
        if a.any():
            F[a] = np.linalg.solve(M[np.ix_(a, a)], g[a])
        if np.all(F[a] >= 0.0) and np.all((g - M @ F)[~a] <= 1e-12 * np.abs(g).max()):
            return F
    raise AssertionError("no complementary active set")


def test_ring_contact_is_the_unique_complementary_solution(study):
    """Random SPD matrices (contact springs + a residual flexibility) and gaps of both signs:
    the active-set solver equals enumeration to round-off (1e-9 of the largest force: the
    solves are of 6x6 systems of condition ~1e3)."""
    rng = np.random.default_rng(7)
    for _ in range(200):
        K = int(rng.integers(1, 7))
        A = rng.normal(size=(K, K))
        M = np.diag(rng.uniform(0.5, 2.0, K)) + 0.3 * A @ A.T / K
        g = rng.normal(size=K)
        F = study.contact_lcp(M, g)
        expected = enumerate_lcp(M, g)
        assert np.all(F >= 0.0)
        np.testing.assert_allclose(F, expected, atol=1e-9 * max(np.abs(expected).max(), 1.0))


def test_uniform_gap_on_rings_is_the_single_port(study):
    """Rings of a flat face closing on a flat head by the same gap, with springs shared by
    area and no residual flexibility, carry k g in total, split by area: the one-port contact."""
    share = np.array([0.1, 0.2, 0.3, 0.4])
    k = 5e12
    F = study.contact_lcp(np.diag(1.0 / (k * share)), np.full(4, 1e-5))
    assert F.sum() == pytest.approx(k * 1e-5, rel=1e-12)
    np.testing.assert_allclose(F / F.sum(), share, rtol=1e-12)
