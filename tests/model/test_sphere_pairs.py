"""Self-collision's candidate pairs (model/collisions._sphere_pairs, sweep and prune along x) are the
dense distance matrix's (_sphere_pairs_dense): the same pairs in the same order, the same refusal."""

from __future__ import annotations

import numpy as np

from myrabot_desc.model.collisions import TooManyPairs, _sphere_pairs
from myrabot_desc.safety import limit


def _sphere_pairs_dense(np, items, min_depth: float) -> list:
    """_sphere_pairs by the whole distance matrix, a block of rows at a time: the reference."""
    C = np.array([i.centre for i in items])
    R = np.array([i.radius for i in items])
    most = limit("max_collision_pairs")
    out: list = []
    block = 128
    for s in range(0, len(items), block):
        d = np.linalg.norm(C[s:s + block, None, :] - C[None, :, :], axis=2)
        ii, jj = np.nonzero(d < R[s:s + block, None] + R[None, :] - min_depth)
        ii = ii + s
        keep = jj > ii
        out.extend(zip(ii[keep].tolist(), jj[keep].tolist()))
        if len(out) > most:
            raise TooManyPairs(f"self-collision: over {most} pairs of collision shapes meet at this pose (the links "
                               "are probably all at one place); not tested pair by pair "
                               "(MYRABOT_DESC_MAX_COLLISION_PAIRS)")
    return out


class _Item:
    def __init__(self, centre, radius):
        self.centre, self.radius = centre, radius


def _pairs(fn, items, min_depth):
    try:
        return fn(np, items, min_depth)
    except TooManyPairs:
        return "refused"


def test_sweep_equals_dense_on_random_scenes():
    rng = np.random.default_rng(1)
    for trial in range(200):
        n = int(rng.integers(0, 250))
        C = rng.normal(size=(n, 3)) * float(rng.choice([0.01, 0.1, 1.0, 10.0]))
        if trial % 3 == 0:
            C[:, 0] = np.round(C[:, 0], 1)          # many shapes at one x: long sweeps
        R = rng.uniform(0, 0.3, size=n) * float(rng.choice([0.1, 1.0, 3.0]))
        items = [_Item(tuple(c), float(r)) for c, r in zip(C, R)]
        md = float(rng.choice([0.001, 0.0, -0.01]))
        assert _pairs(_sphere_pairs, items, md) == _pairs(_sphere_pairs_dense, items, md), trial


def test_refused_past_the_limit_like_the_dense_form(monkeypatch):
    monkeypatch.setenv("MYRABOT_DESC_MAX_COLLISION_PAIRS", "50")
    items = [_Item((0.0, 0.0, 0.001 * k), 0.1) for k in range(20)]      # 190 pairs, all at one place
    assert _pairs(_sphere_pairs, items, 0.001) == _pairs(_sphere_pairs_dense, items, 0.001) == "refused"


def test_candidates_over_several_chunks_like_the_dense_form(monkeypatch):
    """400 shapes at one x: 79,800 candidates, more than one chunk; their neighbours meet (399 pairs),
    taken whole under a limit of 1,000 and refused under 300, as the dense form does."""
    items = [_Item((0.0, 0.5 * k, 0.0), 0.3) for k in range(400)]
    monkeypatch.setenv("MYRABOT_DESC_MAX_COLLISION_PAIRS", "1000")
    pairs = _pairs(_sphere_pairs, items, 0.001)
    assert pairs == _pairs(_sphere_pairs_dense, items, 0.001) and len(pairs) == 399
    monkeypatch.setenv("MYRABOT_DESC_MAX_COLLISION_PAIRS", "300")
    assert _pairs(_sphere_pairs, items, 0.001) == _pairs(_sphere_pairs_dense, items, 0.001) == "refused"
