"""Meshes for the browser: above a triangle budget, each big mesh is simplified by vertex clustering
(vertices snapped to a grid and merged; faces that collapse dropped), the grid chosen per mesh to
meet its share of the budget. Software WebGL (no GPU) draws the result at interactive rates; the
PNG (``render``) and the checks use the full meshes.
"""

from __future__ import annotations

BUDGET = 120_000          # triangles per layer (visual, collision) sent to the browser
SMALL = 400               # a mesh this small is left alone


def cluster(vertices, faces, target: int):
    """(vertices, faces) with at most about ``target`` faces (vertex clustering on a grid found by
    bisection); the input when it is already small enough or the grid cannot do better."""
    import numpy as np

    v = np.asarray(vertices, dtype=np.float64)
    f = np.asarray(faces, dtype=np.int64)
    if len(f) <= target or len(v) == 0:
        return vertices, faces
    lo = v.min(axis=0)
    ext = float((v.max(axis=0) - lo).max()) or 1.0

    def attempt(res: int):
        q = np.floor((v - lo) / ext * res).astype(np.int64)
        key = (q[:, 0] * (res + 1) + q[:, 1]) * (res + 1) + q[:, 2]
        uniq, inv = np.unique(key, return_inverse=True)
        inv = inv.ravel()
        counts = np.bincount(inv, minlength=len(uniq)).astype(np.float64)
        nv = np.column_stack([np.bincount(inv, weights=v[:, k], minlength=len(uniq)) for k in range(3)])
        nv /= counts[:, None]
        nf = inv[f]
        keep = (nf[:, 0] != nf[:, 1]) & (nf[:, 1] != nf[:, 2]) & (nf[:, 0] != nf[:, 2])
        nf = nf[keep]
        if len(nf):
            _, first = np.unique(np.sort(nf, axis=1), axis=0, return_index=True)
            nf = nf[np.sort(first)]
        return nv, nf

    best = None
    lo_res, hi_res = 2, 2048
    for _ in range(12):
        if hi_res - lo_res <= 1:
            break
        mid = int(round((lo_res * hi_res) ** 0.5))
        mid = min(max(mid, lo_res + 1), hi_res - 1)
        nv, nf = attempt(mid)
        if len(nf) <= target:
            best, lo_res = (nv, nf), mid
        else:
            hi_res = mid
    if best is None or len(best[1]) == 0:
        return vertices, faces
    nv, nf = best
    used = np.unique(nf)
    remap = np.full(len(nv), -1, dtype=np.int64)
    remap[used] = np.arange(len(used))
    return nv[used].astype(np.float32), remap[nf].astype(np.uint32)


def browser_parts(parts, budget: int = BUDGET) -> list:
    """The scene's parts with the big meshes of each layer simplified to fit ``budget`` triangles
    (shared meshes are simplified once)."""
    out = list(parts)
    for layer in ("visual", "collision"):
        idx = [i for i, p in enumerate(parts) if p.layer == layer]
        total = sum(len(parts[i].faces) for i in idx)
        if total <= budget:
            continue
        small = sum(len(parts[i].faces) for i in idx if parts[i].kind != "mesh" or len(parts[i].faces) <= SMALL)
        big = total - small
        ratio = max(budget - small, budget // 4) / max(big, 1)
        done: dict = {}
        for i in idx:
            p = parts[i]
            if p.kind != "mesh" or len(p.faces) <= SMALL:
                continue
            key = (id(p.faces), p.vertices.shape, float(p.vertices[0, 0]) if len(p.vertices) else 0.0)
            if key not in done:
                done[key] = cluster(p.vertices, p.faces, max(SMALL, int(len(p.faces) * ratio)))
            nv, nf = done[key]
            out[i] = p._replace(vertices=nv, faces=nf)
    return out
