#!/usr/bin/python3
"""The SciPy peer: the penalty ball drop under scipy.integrate.solve_ivp, as a numerical analyst
would set it up -- one smooth piece at a time, restarted at every contact switch located by an
event, with the analytic Jacobian (--setups tuned, the default) -- and as a user gets it at its
defaults -- one solve over the whole span, stepping across the switches, the Jacobian (BDF,
Radau, LSODA) by differences (--setups defaults) -- for the project's work-precision study and
benchmarks.

Ball of mass m dropped from h0 onto the floor y = 0; while y < 0 the linear law
F = -k y - c v pushes (unclamped, as the project's "kelvin-voigt"; c = 0 is Hooke).
Prints one JSON object per (method, rtol): the final state at t_end, the apex heights, the
right-hand-side and Jacobian evaluations, and the CPU time per solve (median of --repeats, with
min and max; with --budget, at least three and at most --repeats solves, stopping once they have
taken --budget seconds, as the project's time_cpu_within). Needs NumPy and SciPy (Debian: python3-scipy; run with /usr/bin/python3).
"""
import argparse
import json
import statistics
import sys
import time

try:
    import numpy as np
    from scipy.integrate import solve_ivp
except ImportError as missing:  # the caller says what to install (exit 3: the peer is absent, not failed)
    print(f"scipy_peer: {missing}", file=sys.stderr)
    sys.exit(3)


def smooth_pieces(m, g, k, c):
    """The two smooth pieces, flight and contact: their right-hand sides and analytic Jacobians."""
    free = lambda t, y: np.array([y[1], -g])
    spring = lambda t, y: np.array([y[1], -g - (k * y[0] + c * y[1]) / m])
    jac_free = lambda t, y: np.array([[0.0, 1.0], [0.0, 0.0]])
    jac_spring = lambda t, y: np.array([[0.0, 1.0], [-k / m, -c / m]])
    return free, spring, jac_free, jac_spring


def drop(method, rtol, atol, m, g, k, c, h0, v0, t_end):
    """One solve: returns (final state, apex heights, nfev, njev)."""
    free, spring, jac_free, jac_spring = smooth_pieces(m, g, k, c)
    touch = lambda t, y: y[0]
    touch.terminal = True
    apex = lambda t, y: y[1]
    apex.direction = -1
    t, y, apexes, nfev, njev = 0.0, np.array([h0, v0]), [], 0, 0
    in_contact = h0 < 0
    pieces = 0
    while t < t_end:
        pieces += 1
        if pieces > 100000:
            raise RuntimeError(f"{method}: more than 100000 contact switches before t = {t}")
        touch.direction = 1 if in_contact else -1
        options = dict(method=method, rtol=rtol, atol=atol, events=[touch] if in_contact else [touch, apex])
        if method != "RK45":
            options["jac"] = jac_spring if in_contact else jac_free
        sol = solve_ivp(spring if in_contact else free, (t, t_end), y, **options)
        if sol.status < 0:
            raise RuntimeError(f"{method} failed at t = {sol.t[-1]}: {sol.message}")
        nfev += int(sol.nfev)
        njev += int(sol.njev)
        if not in_contact:  # apexes of this flight, not a rest at its start
            apexes += [float(e[0]) for te, e in zip(sol.t_events[1], sol.y_events[1]) if te > t]
        t, y = float(sol.t[-1]), sol.y[:, -1].copy()
        if sol.status == 1:  # a switch: restart on the other side
            y[0] = 0.0
            in_contact = not in_contact
    return y, apexes, nfev, njev


def drop_at_defaults(method, rtol, atol, m, g, k, c, h0, v0, t_end):
    """One solve over [0, t_end] with the force switched inside the right-hand side; the apexes by a
    non-terminal event, which SciPy locates in each step's dense output after taking it (the steps
    are those of the solve without it)."""
    def rhs(t, y):
        force = -(k * y[0] + c * y[1]) if y[0] < 0 else 0.0
        return np.array([y[1], -g + force / m])
    apex = lambda t, y: y[1]
    apex.direction = -1
    sol = solve_ivp(rhs, (0.0, t_end), np.array([h0, v0]), method=method, rtol=rtol, atol=atol, events=[apex])
    if sol.status < 0:
        raise RuntimeError(f"{method} failed at t = {sol.t[-1]}: {sol.message}")
    apexes = [float(e[0]) for te, e in zip(sol.t_events[0], sol.y_events[0]) if te > 0]
    return sol.y[:, -1], apexes, int(sol.nfev), int(sol.njev)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--methods", default="BDF,Radau,LSODA,RK45")
    p.add_argument("--setups", default="tuned", help="tuned, defaults or both, comma-separated")
    p.add_argument("--rtols", default="1e-6")
    p.add_argument("--atol-ratio", type=float, default=1e-2, help="atol = rtol times this")
    p.add_argument("--atol", type=float, default=None, help="a fixed atol instead")
    p.add_argument("--m", type=float, default=1.0)
    p.add_argument("--g", type=float, default=9.81)
    p.add_argument("--k", type=float, default=1e4)
    p.add_argument("--c", type=float, default=0.0)
    p.add_argument("--h0", type=float, default=1.0)
    p.add_argument("--v0", type=float, default=0.0)
    p.add_argument("--t-end", type=float, default=1.5)
    p.add_argument("--repeats", type=int, default=1)
    p.add_argument("--budget", type=float, default=0.0, help="CPU seconds after which repeats stop (0: none)")
    a = p.parse_args()
    for name, value, low in (("--k", a.k, 0.0), ("--m", a.m, 0.0), ("--t-end", a.t_end, 0.0)):
        if not value > low:
            sys.exit(f"scipy_peer: {name}: value '{value}' is out of range; accepted range (0, inf)")
    if a.repeats < 1:
        sys.exit(f"scipy_peer: --repeats: value '{a.repeats}' is out of range; accepted range [1, inf)")
    if not a.budget >= 0:
        sys.exit(f"scipy_peer: --budget: value '{a.budget}' is out of range; accepted range [0, inf)")
    setups = {"tuned": drop, "defaults": drop_at_defaults}
    for setup in a.setups.split(","):
        if setup not in setups:
            sys.exit(f"scipy_peer: --setups: value '{setup}' is out of range; accepted: tuned, defaults")
    for setup in a.setups.split(","):
        for method in a.methods.split(","):
            for rtol in (float(r) for r in a.rtols.split(",")):
                atol = a.atol if a.atol is not None else rtol * a.atol_ratio
                times = []
                while len(times) < a.repeats and (a.budget == 0 or len(times) < 3 or sum(times) < a.budget):
                    start = time.process_time()
                    y, apexes, nfev, njev = setups[setup](method, rtol, atol, a.m, a.g, a.k, a.c, a.h0, a.v0,
                                                          a.t_end)
                    times.append(time.process_time() - start)
                print(json.dumps({"method": method, "setup": setup, "rtol": rtol, "atol": atol, "y": float(y[0]),
                                  "v": float(y[1]), "apexes": apexes, "nfev": nfev, "njev": njev,
                                  "cpu_s": statistics.median(times), "cpu_min_s": min(times),
                                  "cpu_max_s": max(times), "repeats": len(times)}))


if __name__ == "__main__":
    main()
