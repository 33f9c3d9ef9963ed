#!/usr/bin/env python3
"""Ratio between the energy release rate G of a sharp mode-I crack and eigenerosion's
estimate eps * <W> (the mean strain-energy density over a disc of radius eps), for the
asymptotic crack-tip field, with the disc centred at distance d ahead of the tip.

In the singular field W ~ K^2 / r, so eps * <W> is independent of eps: the ratio is a
number that depends only on Poisson's ratio and the plane assumption. It is the value
of eigenerosion's 'Energy release factor' that makes a particle at a sharp tip fail
when G = G_c (doc/validation_mode_i.md).

    python3 scripts/crack_tip_release_factor.py --nu 0.333
"""
import argparse

import numpy as np


def energy_density(x, y, nu, plane_strain, K=1.0, E=1.0):
    r = np.hypot(x, y)
    t = np.arctan2(y, x)
    f = K / np.sqrt(2 * np.pi * r)
    c, s = np.cos(t / 2), np.sin(t / 2)
    s3, c3 = np.sin(1.5 * t), np.cos(1.5 * t)
    sxx = f * c * (1 - s * s3)
    syy = f * c * (1 + s * s3)
    sxy = f * c * s * c3
    szz = nu * (sxx + syy) if plane_strain else 0 * sxx
    return ((sxx**2 + syy**2 + szz**2) - 2 * nu * (sxx * syy + syy * szz + szz * sxx)
            + 2 * (1 + nu) * sxy**2) / (2 * E)


def ratio(nu, plane_strain, d, n=4000):
    # Midpoint rule in polar coordinates about the disc centre (d, 0); eps = 1.
    rr = (np.arange(n) + 0.5) / n
    tt = (np.arange(n) + 0.5) / n * 2 * np.pi - np.pi
    R, T = np.meshgrid(rr, tt)
    w = energy_density(d + R * np.cos(T), R * np.sin(T), nu, plane_strain)
    mean = (w * R).sum() * (1.0 / n) * (2 * np.pi / n) / np.pi
    G = (1 - nu**2) if plane_strain else 1.0  # K^2 / E' with K = E = 1
    return G / mean


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--nu", type=float, default=0.333)
    ap.add_argument("--plane-stress", action="store_true")
    args = ap.parse_args()
    for d in (0.0, 0.1, 0.25, 0.5):
        print(f"disc centre {d:4.2f} eps ahead of the tip: G / (eps <W>) = "
              f"{ratio(args.nu, not args.plane_stress, d):.3f}")


if __name__ == "__main__":
    main()
