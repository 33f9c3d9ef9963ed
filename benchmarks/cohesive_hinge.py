#!/usr/bin/python3
"""Peak load of a notched beam in three-point bending from a cohesive hinge, as an
independent check of the material constants of prm/three_point_bending.prm.

The ligament above the notch is a hinge of width s = factor * (D - a0) (plane sections
turning about a neutral axis, the idea of Ulfkjaer, Krenk and Brincker 1995 and Olesen
2001), cut into layers; a layer whose strain exceeds f_t / E opens a cohesive crack of
width w with s * eps = s * sigma / E + w and sigma = sigma(w) (linear, bilinear with the
kink at f_t / 3, or exponential: the softening laws of lme-mpm). For each curvature the
neutral axis is found from the zero axial force; the moment gives P = 4 M / S. The
largest P over the curvatures is printed. It is a model of the beam, not an exact
solution: it brackets what a cohesive crack with these constants can carry.

    /usr/bin/python3 benchmarks/cohesive_hinge.py --law bilinear --hinge 0.5 1.0
"""
import argparse

import numpy as np


def softening(law, ft, gf):
    """sigma(w) of the named law (numpy arrays)."""
    if law == "linear":
        wc = 2 * gf / ft
        return lambda w: np.where(w < wc, ft * (1 - w / wc), 0.0)
    if law == "exponential":
        return lambda w: ft * np.exp(-ft * w / gf)
    w1, wc = 0.8 * gf / ft, 3.6 * gf / ft  # Petersson's kink at (w1, f_t / 3)
    return lambda w: np.where(w < w1, ft * (1 - 2.0 / 3.0 * w / w1),
                              np.where(w < wc, ft / 3 * (wc - w) / (wc - w1), 0.0))


def peak_load(a):
    sigma_w = softening(a.law, a.ft, a.gf)
    h = a.depth - a.notch
    s = a.hinge_factor * h
    n = 400
    y = (np.arange(n) + 0.5) / n * h  # from the notch tip up
    dy = h / n

    def stress(eps):
        sig = a.E * eps
        cracked = eps > a.ft / a.E
        if cracked.any():
            e = eps[cracked]
            lo, hi = np.zeros_like(e), s * e
            for _ in range(60):  # bisection on w: s e = s sigma(w) / E + w
                w = 0.5 * (lo + hi)
                r = s * e - (s * sigma_w(w) / a.E + w)
                lo, hi = np.where(r > 0, w, lo), np.where(r > 0, hi, w)
            sig[cracked] = sigma_w(0.5 * (lo + hi))
        return sig

    best = 0.0
    for kappa in np.linspace(1e-5, 0.1, 800) / h:
        lo, hi = -2 * kappa * h, 2 * kappa * h
        for _ in range(60):  # the axial strain at the tip that balances the force
            e0 = 0.5 * (lo + hi)
            if np.sum(stress(e0 - kappa * y)) * dy > 0:
                hi = e0
            else:
                lo = e0
        sig = stress(e0 - kappa * y)
        moment = -np.sum(sig * (y - h / 2)) * dy * a.width
        best = max(best, 4 * moment / a.span)
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--E", type=float, default=37e9)
    ap.add_argument("--ft", type=float, default=3.9e6)
    ap.add_argument("--gf", type=float, default=143.0)
    ap.add_argument("--depth", type=float, default=0.05)
    ap.add_argument("--notch", type=float, default=0.025)
    ap.add_argument("--width", type=float, default=0.05)
    ap.add_argument("--span", type=float, default=0.125)
    ap.add_argument("--law", nargs="+", default=["linear", "bilinear", "exponential"])
    ap.add_argument("--hinge", type=float, nargs="+", default=[0.5, 1.0],
                    help="hinge widths as multiples of the ligament D - a0")
    a = ap.parse_args()
    print("law          hinge s/(D-a0)   peak load (N)")
    for law in a.law:
        for factor in a.hinge:
            a.law_name, a.hinge_factor = law, factor
            a_law = argparse.Namespace(**vars(a))
            a_law.law = law
            print("%-12s %8.2f %17.0f" % (law, factor, peak_load(a_law)))


if __name__ == "__main__":
    main()
