"""Variance-based sensitivity from a Saltelli design (``sampling.method = "saltelli"``).

Design (Saltelli 2002; Saltelli et al. 2010, "Variance based sensitivity analysis of model
output", Comput. Phys. Commun. 181, §3): two independent sample matrices A and B of N
points each in the unit cube of the d parameters (here the two halves of one scrambled
Sobol' sequence in 2d dimensions, scipy.stats.qmc.Sobol), and for every parameter i the
matrix AB⁽ⁱ⁾ = A with its column i taken from B. The study runs the N (d + 2) rows in the
order A, B, AB⁽¹⁾ … AB⁽ᵈ⁾; run k·N + j is base point j of block k.

Estimators, with f the outcome and V the variance of f over A and B together:

* first order (Saltelli et al. 2010, table 2 (b)):  S_i = mean_j f(B)_j (f(AB⁽ⁱ⁾)_j − f(A)_j) / V
* total effect (Jansen 1999; Saltelli et al. 2010, table 2 (f)):
  S_Ti = mean_j (f(A)_j − f(AB⁽ⁱ⁾)_j)² / (2 V)

S_i is the share of the variance parameter i explains alone, S_Ti the share it takes part
in, interactions included; S_Ti − S_i is the interaction share. Confidence intervals: the
2.5 % and 97.5 % quantiles over bootstrap resamples of the base points. A base point whose
A, B or AB⁽ⁱ⁾ run failed is left out of parameter i's estimates (and counted).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import List, Optional, Tuple

import numpy as np

#: Bootstrap resamples of the base points for the confidence intervals.
BOOTSTRAP = 300


def unit_design(n: int, d: int, seed: int) -> np.ndarray:
    """The N (d + 2) × d design in (0, 1)^d: blocks A, B, AB⁽¹⁾ … AB⁽ᵈ⁾ of N rows each."""
    from scipy.stats import qmc

    with warnings.catch_warnings():  # N not a power of 2 loses balance, not validity
        warnings.simplefilter("ignore", UserWarning)
        ab = qmc.Sobol(d=2 * d, scramble=True, rng=np.random.default_rng(seed)).random(n)
    ab = np.clip(ab, 2.0**-53, 1 - 2.0**-53)  # an unbounded inverse CDF needs u ∈ (0, 1)
    a, b = ab[:, :d], ab[:, d:]
    blocks = [a, b]
    for i in range(d):
        m = a.copy()
        m[:, i] = b[:, i]
        blocks.append(m)
    return np.vstack(blocks)


def runs_of(n: int, d: int) -> int:
    """How many runs a Saltelli design of N base points over d parameters takes."""
    return n * (d + 2)


@dataclass
class Index:
    """One parameter's indices for one outcome, each with its 95 % bootstrap interval."""

    first: float
    first_ci: Tuple[float, float]
    total: float
    total_ci: Tuple[float, float]
    #: base points used (those whose A, B and AB⁽ⁱ⁾ runs all gave the outcome)
    points: int


def _first(fa, fb, fab, var):
    return np.mean(fb * (fab - fa), axis=-1) / var


def _total(fa, fab, var):
    return np.mean((fa - fab) ** 2, axis=-1) / (2 * var)


def indices(y: np.ndarray, n: int, d: int, seed: int = 0) -> List[Optional[Index]]:
    """S_i and S_Ti of each of the d parameters from the outcomes ``y`` of the N (d + 2)
    runs in design order (NaN for a run without the outcome); ``None`` for a parameter
    with fewer than 4 complete base points or an outcome without variance."""
    y = np.asarray(y, float)
    if y.shape != (runs_of(n, d),):
        raise ValueError(f"expected {runs_of(n, d)} outcomes (N = {n}, d = {d}), got {y.shape}")
    fa, fb = y[:n], y[n:2 * n]
    rng = np.random.default_rng(seed)
    out: List[Optional[Index]] = []
    for i in range(d):
        fab = y[(2 + i) * n:(3 + i) * n]
        ok = np.isfinite(fa) & np.isfinite(fb) & np.isfinite(fab)
        k = int(ok.sum())
        a, b, ab = fa[ok], fb[ok], fab[ok]
        var = np.var(np.concatenate([a, b]))
        if k < 4 or var == 0:
            out.append(None)
            continue
        pick = rng.integers(0, k, size=(BOOTSTRAP, k))
        va = np.var(np.concatenate([a[pick], b[pick]], axis=1), axis=1)
        va = np.where(va > 0, va, np.nan)
        boot_first = _first(a[pick], b[pick], ab[pick], va)
        boot_total = _total(a[pick], ab[pick], va)
        out.append(Index(
            first=float(_first(a, b, ab, var)),
            first_ci=tuple(float(x) for x in np.nanquantile(boot_first, [0.025, 0.975])),
            total=float(_total(a, ab, var)),
            total_ci=tuple(float(x) for x in np.nanquantile(boot_total, [0.025, 0.975])),
            points=k,
        ))
    return out
