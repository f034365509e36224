"""The study's samples: one value per parameter and run, as a full-factorial grid, a
Latin hypercube, plain Monte Carlo, or a Saltelli design for Sobol' indices (:mod:`.sobol`). The same study (and seed) gives the same samples.

Monte Carlo and the Latin hypercube draw points u in the unit cube (numpy's PCG64
generator; scipy.stats.qmc.LatinHypercube) and map each coordinate through its
parameter's inverse CDF (a bounded normal is truncated by it, not clipped). The grid takes
each parameter's ``levels`` if given, else ``sampling.levels`` quantiles at (i + ½)/k
(a choice: every choice), and runs every combination.
"""

from __future__ import annotations

import itertools
from typing import Any, Dict, List

import numpy as np

from . import sobol
from .spec import Parameter, Study


def unit_samples(method: str, runs: int, dims: int, seed: int) -> np.ndarray:
    """Points in (0, 1)^dims: ``runs`` of them by Monte Carlo or a Latin hypercube, or
    for ``saltelli`` the runs·(dims + 2) rows of a Saltelli design over ``runs`` base
    points (:mod:`.sobol`)."""
    if method == "saltelli":
        return sobol.unit_design(runs, dims, seed)
    if method == "latin_hypercube":
        from scipy.stats import qmc

        return qmc.LatinHypercube(d=dims, rng=np.random.default_rng(seed)).random(runs)
    return np.random.default_rng(seed).random((runs, dims))


def _value(p: Parameter, v: Any) -> Any:
    """A sampled value as stored: a choice as its label, a number as float."""
    return p.distribution.choices[int(v)] if p.categorical else float(v)


def _grid_levels(p: Parameter, k: int) -> List[Any]:
    if p.levels is not None:
        return list(p.levels)
    if p.categorical:
        return list(p.distribution.choices)
    return [float(x) for x in p.distribution.ppf((np.arange(k) + 0.5) / k)]


def samples(study: Study) -> List[Dict[str, Any]]:
    """Every run's parameter values (SI), by parameter name, in run order."""
    params = study.parameters
    if study.method == "grid":
        grid = itertools.product(*[_grid_levels(p, study.grid_levels) for p in params])
        return [dict(zip([p.name for p in params], combo)) for combo in grid]
    u = unit_samples(study.method, study.runs, len(params), study.seed)
    columns = [p.distribution.ppf(u[:, j]) for j, p in enumerate(params)]
    return [
        {p.name: _value(p, columns[j][i]) for j, p in enumerate(params)}
        for i in range(len(u))
    ]
