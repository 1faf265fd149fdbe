"""The study's ball_drop heights figure, from Python: height against time of the ball drop
(1 kg from 1 m, e = 0.8, Kelvin-Voigt k = 1e5 N/m) under every method that can run it.

    /usr/bin/python3 examples/ball_drop_heights.py [out.png]

Needs the module on PYTHONPATH (build/python) and matplotlib (Debian's python3-matplotlib).
"""
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt

import contact_ode as co


def main(out="heights.png"):
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for method in co.methods_for("ball-drop", law="kelvin-voigt"):
        r = co.solve("ball-drop", method, law="kelvin-voigt", k=1e5, t_end=3.0, sample_dt=0.01)
        ax.plot(r.t, r.y[:, 0], label=method, linewidth=1)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("height [m]")
    ax.grid(True)
    ax.legend(fontsize=7, ncol=3)
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    return out


if __name__ == "__main__":
    print(main(*sys.argv[1:]))
