"""The thermal solve against the group-level answer a view factor matrix gives: the classical
net-radiation (network) method, which takes each group's radiosity as uniform, solved on the
matrix F of `panelrad viewfactors` for the same groups. Prints, per group, the net heat rate of the
element-level thermal solve and of the network, their difference, and the time of each. The
network's error is what the group approximation costs (the view factors themselves are computed
to the solver's accuracy).

For a group I with a given temperature T_I and emissivity eps_I:
    J_I - (1 - eps_I) (sum_J F_IJ J_J + F_I,sky sigma T_env^4) = eps_I sigma T_I^4,
and with a given net flux q_I:
    J_I - (sum_J F_IJ J_J + F_I,sky sigma T_env^4) = q_I;
then H_I = sum_J F_IJ J_J + F_I,sky sigma T_env^4, Q_I = A_I (J_I - H_I), and where q was given
T_I = ((J_I - (1 - eps_I) H_I) / (eps_I sigma))^(1/4).

usage (from the repository's root, Debian's python3 for numpy):
    PYTHONPATH=build/python /usr/bin/python3 bench/thermal_network.py SCENE BC.json \\
        [--groups object] [--levels L [L ...]] [--threads T]
"""
import argparse
import json
import time

import numpy as np

import panelrad

SIGMA = 5.670374419e-8


def network(vf, conditions, T_env):
    """Group rates Q and temperatures T by the net-radiation method on vf.F."""
    F, A = np.asarray(vf.F), np.asarray(vf.area)
    sky = np.zeros(len(A)) if vf.enclosed else np.asarray(vf.uncovered)
    eb_env = SIGMA * T_env**4 if T_env is not None else 0.0
    k = len(vf.names)
    M, b = np.eye(k), np.zeros(k)
    eps = np.zeros(k)
    for I, name in enumerate(vf.names):
        c = conditions[name]
        eps[I] = c["emissivity"]
        rho = 1 - eps[I] if "T" in c else 1.0
        M[I] -= rho * F[I]
        b[I] = (eps[I] * SIGMA * c["T"] ** 4 if "T" in c else c["q"]) + rho * sky[I] * eb_env
    J = np.linalg.solve(M, b)
    H = F @ J + sky * eb_env
    T = np.array([conditions[name]["T"] if "T" in conditions[name] else
                  ((J[I] - (1 - eps[I]) * H[I]) / (eps[I] * SIGMA)) ** 0.25 for I, name in enumerate(vf.names)])
    return A * (J - H), T


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("scene")
    parser.add_argument("bc")
    parser.add_argument("--groups", default="object")
    parser.add_argument("--levels", type=int, nargs="+", default=[3])
    parser.add_argument("--threads", type=int, default=1)
    args = parser.parse_args()
    with open(args.bc) as f:
        bc = json.load(f)
    conditions = bc["groups"]
    env = bc.get("environment", "none")
    T_env = None if env == "none" else env["T"]
    panelrad.set_threads(args.threads)
    scene = panelrad.load_scene(args.scene, geometry_only=True)
    for level in args.levels:
        t0 = time.perf_counter()
        s = panelrad.thermal_solve(scene, conditions, args.groups, environment=T_env, level=level)
        t1 = time.perf_counter()
        vf = panelrad.view_factors(scene, groups=args.groups, estimate_error=False, level=level)
        t2 = time.perf_counter()
        assert list(vf.names) == list(s.names)
        Q_net, T_net = network(vf, conditions, T_env)
        scale = np.abs(s.group_Q).max()
        print(f"level {level}, n = {s.n}: thermal solve {t1 - t0:.2f} s ({s.method}), view factors {t2 - t1:.2f} s; "
              f"largest |Q| {scale:.4g} W")
        print(f"  {'group':12s} {'Q solve W':>12s} {'Q network W':>12s} {'diff / max|Q|':>14s} {'T solve K':>10s} "
              f"{'T network K':>11s}")
        for I, name in enumerate(s.names):
            print(f"  {name:12s} {s.group_Q[I]:12.5g} {Q_net[I]:12.5g} {(Q_net[I] - s.group_Q[I]) / scale:14.3e} "
                  f"{s.group_T[I]:10.4f} {T_net[I]:11.4f}")


if __name__ == "__main__":
    main()
