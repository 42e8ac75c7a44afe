"""The Python side of the side-by-side run (run.sh): pylinkage's particle swarm on the target
that `tmm`'s example `pylinkage_target` wrote (24 points of a crank-rocker's coupler curve).

pylinkage is given the frame pivots at their true places and optimises the five other
dimensions (crank; coupler and rocker; the coupler point's distance and angle from A), a
smaller problem than tmm's (which is told nothing of the original). Its score is the mean
distance from the targets to the nearest of the coupler point's positions over a turn; the
error printed is that distance over a turn of 3600 steps, for the best design of the swarm.
Prints one line per run: time and error.
"""

import json
import math
import sys
import time

import numpy as np
import pylinkage as pl
from pylinkage.optimization import particle_swarm_optimization

STEPS = 96  # crank positions per turn in the score


def build(t):
    o1 = pl.Ground(*t["o1"], name="O1")
    o3 = pl.Ground(*t["o3"], name="O3")
    crank = pl.Crank(o1, radius=0.1, angular_velocity=2 * math.pi / STEPS, name="A")
    b = pl.RRRDyad(crank.output, o3, distance1=0.4, distance2=0.4, name="B")
    p = pl.FixedDyad(crank.output, b, distance=0.25, angle=0.6, name="P")
    return pl.Linkage([o1, o3, crank, b, p], name="four-bar"), p


def error(linkage, targets, steps):
    """Mean distance from each target to the nearest coupler point over `steps` positions."""
    path = []
    try:
        for coords in linkage.step(iterations=steps):
            path.append(coords[-1])
    except Exception:
        return math.inf
    path = np.array(path, dtype=float)
    if path.ndim != 2 or not np.all(np.isfinite(path)):
        return math.inf
    d = np.sqrt(((targets[:, None, :] - path[None, :, :]) ** 2).sum(axis=2))
    return float(d.min(axis=1).mean())


def main():
    t = json.load(open(sys.argv[1]))
    iterations = int(sys.argv[2]) if len(sys.argv) > 2 else 200
    targets = np.array(t["points"], dtype=float)
    linkage, _ = build(t)
    start_coords = linkage.get_coords()

    def score(lk, dims, pos):
        lk.set_constraints(dims)
        lk.set_coords(pos)
        return error(lk, targets, STEPS)

    # crank, coupler AB, rocker O3B, |AP| (m), the angle of AP from AB (rad)
    bounds = ([0.02, 0.02, 0.02, 0.02, -math.pi], [1.0, 1.0, 1.0, 1.0, math.pi])
    began, cpu = time.perf_counter(), time.process_time()
    ens = particle_swarm_optimization(
        score,
        linkage,
        bounds=bounds,
        n_particles=100,
        iterations=iterations,
        order_relation=min,
        verbose=False,
    )
    elapsed, cpu = time.perf_counter() - began, time.process_time() - cpu
    dims = np.asarray(ens.dimensions).reshape(-1)
    linkage.set_constraints(list(dims))
    linkage.set_coords(start_coords)
    fine = error(linkage, targets, 3600)
    print(f"pylinkage PSO ({iterations} iterations, 100 particles): {elapsed:.3f} s ({cpu:.3f} s CPU), "
          f"mean miss {fine:.3e} m (dimensions {np.round(dims, 5).tolist()})")


if __name__ == "__main__":
    main()
