#!/usr/bin/python3
"""A one-dimensional model of the multi-field contact exchange, for studying its energy
gain (doc/contact.md, "A one-dimensional model of the gain").

An elastic bar (E = rho = 1, length 1, so c = 1) falls at --speed (0.1) onto a rigid body that
fills x < 0, starting one cell above it, and rebounds. The grid, the explicit Newmark
update (gamma = 1/2, particles carrying velocity and acceleration), the field masses
and volumes, the detection (the two fields fill at least 0.9 of the node's length,
each at least 0.1) follow the solver; the prints give the total energy after the
rebound over the initial one, its largest and smallest values over the run, and the
bar's mean velocity at the end over the impact velocity.

Exchanges (--variant):
  lumped      Contact/Exchange = nodal: approaching rates stopped for the positions, the
              corrector's trial end-of-step velocity stopped through the accelerations
  jump        one exchange on the rates, carried by the particles, with the positions
              following the particles' projected rate after it; solved so that the
              projected rate (consistent mass) stops approaching: the solver's
              Contact/Exchange = projected
  next-rate   no exchange on the rates; the corrector stops the particles' projected
              rate of the next predictor (consistent mass)
  hold        the node's rate and acceleration held at zero while it is pressed
  chain       no grid: the same lumped exchange on a chain of masses and springs

    /usr/bin/python3 scripts/contact_bar_1d.py --variant lumped --cfl 0.1 0.3 0.6
"""
import argparse

import numpy as np

details = ""


def quadratic_bspline(r):
    a = np.abs(r)
    n = np.where(a < 0.5, 0.75 - a**2, np.where(a < 1.5, 0.5 * (1.5 - a)**2, 0.0))
    dn = np.where(a < 0.5, -2 * r, np.where(a < 1.5, -(1.5 - a) * np.sign(r), 0.0))
    return n, dn


def linear(r):
    a = np.abs(r)
    return np.where(a < 1, 1 - a, 0.0), np.where(a < 1, -np.sign(r), 0.0)


def chain(cfl, n=40, v0=0.1, end=4.0):
    h = 1.0 / n
    m, k, dt = h, 1.0 / h, cfl * h
    x = np.arange(n) * h + 1e-9
    v, a = np.full(n, -v0), np.zeros(n)
    e0, energies = 0.5 * np.sum(m * v**2), []
    for _ in range(int(end / dt)):
        w = v + 0.5 * dt * a
        if x[0] <= 0 and w[0] < 0:
            w[0] = 0.0
        x = x + dt * w
        s = np.diff(x) - h
        f = np.zeros(n)
        f[:-1] += k * s
        f[1:] -= k * s
        acc = f / m
        trial = v + 0.5 * dt * (a + acc)
        if x[0] <= 0 and trial[0] < 0:
            acc[0] -= trial[0] / (0.5 * dt)
        v, a = v + 0.5 * dt * (a + acc), acc
        energies.append((0.5 * np.sum(m * v**2) + 0.5 * k * np.sum(s**2)) / e0)
    return energies[-1], max(energies), min(energies), np.mean(v) / v0


def bar(variant, h, cfl, shape, ppc=2, v0=0.1, end=3.0, iterations=10):
    dxp = h / ppc
    xb = h + (np.arange(int(round(1 / h)) * ppc) + 0.5) * dxp
    xw = -0.5 + (np.arange(int(round(0.5 / h)) * ppc) + 0.5) * dxp
    x = np.concatenate([xb, xw])
    is_bar = np.arange(x.size) < xb.size
    mp = np.full(x.size, dxp)
    vol = np.full(x.size, dxp)
    v, a, eps = np.where(is_bar, -v0, 0.0), np.zeros(x.size), np.zeros(x.size)
    lo, nn = -1.0, int(round(3.0 / h)) + 1
    xn = lo + np.arange(nn) * h
    dt, tol = cfl * h, 1e-12
    e0, energies = 0.5 * np.sum(mp[is_bar] * v0**2), []
    # Where the energy changes: steps whose contact set changed, steps in contact
    # with the same set, steps without contact.
    split, last, most = [0.0, 0.0, 0.0], None, 0
    reach = np.arange(-3, 4)
    b = is_bar

    def scatter(idx, weights, values):
        out = np.zeros(nn)
        np.add.at(out, idx, weights * values[:, None])
        return out

    for _ in range(int(end / dt)):
        idx = np.floor((x - lo) / h).astype(int)[:, None] + reach[None, :]
        n, dn = shape((x[:, None] - xn[idx]) / h)
        dn = dn / h
        m = [scatter(idx[s], n[s], mp[s]) for s in (b, ~b)]
        fill = [scatter(idx[s], n[s], vol[s]) for s in (b, ~b)]
        safe = np.maximum(m[0], tol)
        has = m[0] > tol
        contact = has & (m[1] > tol) & (fill[0] + fill[1] >= 0.9 * h) & (
            np.minimum(fill[0], fill[1]) >= 0.1 * h)
        nodes = np.where(contact)[0]
        # Diagonal of the consistent over the lumped mass, for the Jacobi sweeps.
        diag = np.where(has, scatter(idx[b], n[b]**2, mp[b]) / safe, 1.0)

        def projected(values):  # the particles' mass-weighted projection on the grid
            return np.where(has, scatter(idx[b], n[b], mp[b] * values[b]) / safe, 0.0)

        def interpolate(nodal):
            return np.sum(n * nodal[idx], axis=1)

        w = projected(v + 0.5 * dt * a)
        if variant == "jump":
            jump = np.zeros(nn)
            for _ in range(iterations):
                rate = w + projected(interpolate(jump))
                jump[nodes] = np.maximum(jump[nodes] - rate[nodes] / diag[nodes], 0.0)
            v = v + np.where(b, interpolate(jump), 0.0)
            w = projected(v + 0.5 * dt * a)
        before = w
        held = contact & (before <= 0)
        if variant in ("lumped", "hold"):
            w = np.where(contact & (before < 0), 0.0, w)
        de = dt * np.sum(dn * w[idx], axis=1)
        eps = eps + np.where(b, de, 0.0)
        x = x + dt * np.where(b, interpolate(w), 0.0)
        force = scatter(idx[b], -dn[b], vol[b] * eps[b])
        acc = np.where(has, force / safe, 0.0)
        if variant == "lumped":
            trial = before + 0.5 * dt * acc
            stop = contact & (trial < 0)
            acc[stop] -= trial[stop] / (0.5 * dt)
        elif variant == "hold":
            acc[held & (acc < 0)] = 0.0
        elif variant == "next-rate":
            base = projected(v + 0.5 * dt * a)
            extra = np.zeros(nn)
            for _ in range(iterations):
                rate = base + dt * projected(interpolate(acc + extra))
                extra[nodes] = np.maximum(
                    extra[nodes] - rate[nodes] / (dt * diag[nodes]), 0.0)
            acc = acc + extra
        a_new = np.where(b, interpolate(acc), 0.0)
        v, a = v + 0.5 * dt * (a + a_new), a_new
        energies.append((0.5 * np.sum(mp[b] * v[b]**2) + 0.5 * np.sum(vol[b] * eps[b]**2)) /
                        e0)
        key = tuple(nodes.tolist())
        if len(energies) > 1:
            change = energies[-1] - energies[-2]
            split[0 if key != last else 1 if key else 2] += change
        last, most = key, max(most, len(key))
    global details
    details = "  energy change: %.4f as the contact set changed, %.4f in contact, " \
              "%.4f out of contact; at most %d nodes in contact" % (*split, most)
    return energies[-1], max(energies), min(energies), np.mean(v[b]) / v0


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--variant", default="lumped",
                   choices=["lumped", "jump", "next-rate", "hold", "chain"])
    p.add_argument("--cfl", type=float, nargs="+", default=[0.3])
    p.add_argument("--cells", type=int, nargs="+", default=[80],
                   help="cells over the bar's length")
    p.add_argument("--shape", default="bspline", choices=["bspline", "linear"])
    p.add_argument("--speed", type=float, default=0.1,
                   help="impact velocity over the bar's wave speed")
    args = p.parse_args()
    shape = quadratic_bspline if args.shape == "bspline" else linear
    for cells in args.cells:
        for cfl in args.cfl:
            r = chain(cfl, cells, v0=args.speed) if args.variant == "chain" else bar(
                args.variant, 1.0 / cells, cfl, shape, v0=args.speed)
            print("%s %s h=1/%d cfl=%.2f: end %.4f max %.4f min %.4f rebound %.3f" %
                  (args.variant, args.shape, cells, cfl, *r))
            if args.variant != "chain":
                print(details)


if __name__ == "__main__":
    main()
