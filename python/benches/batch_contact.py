"""collide_batch with a contact law against the no-slip batch (docs/python.md, "A contact
law"): 200 000 rows in 3D, C-contiguous float64, one thread (parallel=False), into reused
outputs; 7 alternated rounds of the five variants, ns per row of thread CPU time, median
(min-max). Run: target/python-venv/bin/python python/benches/batch_contact.py [--validate]
(--validate: 20 000 approaching rows, each through the checked path)."""
import sys
import time, statistics, numpy as np, noslip
from typing import Any
VALIDATE = "--validate" in sys.argv
N, n = (20_000 if VALIDATE else 200_000), 3
rng = np.random.default_rng(0)
nu = rng.normal(size=(N, n)); nu /= np.linalg.norm(nu, axis=1, keepdims=True)
def body() -> dict[str, Any]:
    a = rng.uniform(-1, 1, (N, n, n))
    return {"angular_velocity": a - a.transpose(0, 2, 1), "velocity": rng.uniform(-1, 1, (N, n)),
            "inv_mass": rng.uniform(0.5, 2, N), "radius": rng.uniform(0.5, 1, N), "gamma2": rng.uniform(0.1, 0.6, N)}
b = [body(), body()]
e = rng.uniform(0, 1, N); beta = rng.uniform(-1, 1, N); mu = rng.uniform(0, 2, N); beta0 = rng.uniform(-1, 1, N)
variants = {
    "no-slip": None,
    "rough shared": {"e": 0.9, "beta": 0.4},
    "rough per row": {"e": e, "beta": beta},
    "walton shared": {"e": 0.9, "mu": 0.2, "beta0": 0.4},
    "walton per row": {"e": e, "mu": mu, "beta0": beta0},
}
nu[np.einsum("ij,ij->i", b[1]["velocity"] - b[0]["velocity"], nu) > 0] *= -1  # approaching
out = noslip.collide_batch(nu, b, validate=False)
t: dict[str, list[float]] = {k: [] for k in variants}
for r in range(7):
    for k, c in variants.items():
        t0 = time.thread_time()
        noslip.collide_batch(nu, b, contact=c, validate=VALIDATE, parallel=False, out=out)
        t[k].append((time.thread_time() - t0) / N * 1e9)
for k, v in t.items():
    print(f"| {k} | {statistics.median(v):.1f} ({min(v):.1f}-{max(v):.1f}) |")
