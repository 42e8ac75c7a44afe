"""pylinkage's numba path on the four-bar of tmm's `batch` and `kinematics` benches.

The same four-bar: crank O = (0, 0), l_OA = 0.1 m; frame pivot C = (0.4, 0.05) m; coupler
l_AB = 0.35 m, rocker l_CB = 0.3 m; B on the same branch as tmm's `Branch::Plus` (checked
against the closed form below before timing). Timed per position:

- `step_fast` (positions of every joint over N crank steps, one numba call);
- `step_fast_with_kinematics` (positions, velocities and accelerations, ω = 10 rad/s,
  ε = 1 rad/s² as in the Rust benches).

Each is the fastest of several rounds after a warm-up call (the JIT compiles once). Run by
`run.sh`, which builds its own virtual environment; never part of `cargo test`.
"""

import math
import sys
import time

import numpy as np
import numba
import pylinkage
from pylinkage.actuators import Crank
from pylinkage.components import Ground
from pylinkage.dyads import RRRDyad
from pylinkage.simulation import Linkage

L1, L2, L3 = 0.1, 0.35, 0.3
C = (0.4, 0.05)


def by_hand(phi):
    """B by the closed form of the Rust hand kernel (the branch of tmm's `Branch::Plus`)."""
    ax, ay = L1 * math.cos(phi), L1 * math.sin(phi)
    dx, dy = C[0] - ax, C[1] - ay
    l_sq = dx * dx + dy * dy
    l = math.sqrt(l_sq)
    x = (l_sq + L2 * L2 - L3 * L3) / (2.0 * l)
    h = math.sqrt(L2 * L2 - x * x)
    return ax + (x * dx - h * dy) / l, ay + (x * dy + h * dx) / l


def four_bar(n):
    """The four-bar turning its crank once in `n` steps, B started on the hand kernel's branch."""
    o = Ground(0.0, 0.0, name="O")
    c = Ground(C[0], C[1], name="C")
    crank = Crank(anchor=o, radius=L1, angular_velocity=math.tau / n, initial_angle=0.0, name="A")
    bx, by = by_hand(0.0)
    b = RRRDyad(crank.output, c, distance1=L2, distance2=L3, x=bx, y=by, name="B")
    linkage = Linkage([o, c, crank, b], name="four-bar")
    return linkage, crank


def fastest(f, rounds):
    best = math.inf
    for _ in range(rounds):
        t = time.perf_counter()
        f()
        best = min(best, time.perf_counter() - t)
    return best


def main():
    sizes = [int(a) for a in sys.argv[1:]] or [360, 4096, 100_000]
    print(f"pylinkage {pylinkage.__version__ if hasattr(pylinkage, '__version__') else '?'}, "
          f"numba {numba.__version__}, numpy {np.__version__}, python {sys.version.split()[0]}")
    for n in sizes:
        linkage, crank = four_bar(n)
        linkage.set_input_velocity(crank, 10.0, 1.0)
        traj = linkage.step_fast(iterations=n)  # compiles (cached after the first run)
        # The positions agree with the closed form: B after step k is at φ = (k + 1)·2π/n.
        b = traj[:, 3, :]
        worst = max(
            math.hypot(b[k, 0] - by_hand((k + 1) * math.tau / n)[0],
                       b[k, 1] - by_hand((k + 1) * math.tau / n)[1])
            for k in range(n)
        )
        assert worst < 1e-9, f"pylinkage's B is {worst} m from the closed form"
        linkage.step_fast_with_kinematics(iterations=n)
        rounds = max(3, min(200, 2_000_000 // n))
        t_pos = fastest(lambda: linkage.step_fast(iterations=n), rounds)
        t_kin = fastest(lambda: linkage.step_fast_with_kinematics(iterations=n), rounds)
        print(f"pylinkage | N = {n}: step_fast {t_pos / n * 1e9:.1f} ns per position, "
              f"step_fast_with_kinematics {t_kin / n * 1e9:.1f} ns per position "
              f"(B within {worst:.1e} m of the closed form)")


if __name__ == "__main__":
    main()
