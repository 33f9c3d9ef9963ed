#!/usr/bin/env python3
"""How well a servo-controlled run held its opening rate after the peak.

Usage: servo_windows.py RATE GAUGE DEVICE OUTDIR [OUTDIR ...]

RATE is Loading control/Opening rate (m/s), GAUGE the opening gauge's name and
DEVICE the loading body's name. For each output directory: the opening rate over
windows of eight history rows from the first row after device_peak_time, as a share
of RATE, while the device's load (force_<DEVICE>_y) stays above a quarter of
device_peak_load, and after; the largest kinetic over strain energy in each part.
Plain Python (no numpy).
"""
import csv
import json
import sys


def windows(directory, rate, gauge, device):
    rows = list(csv.DictReader(open(directory + "/history.csv")))
    summary = json.load(open(directory + "/summary.json"))
    results = summary.get("results", summary)
    t_peak, peak = results["device_peak_time"], results["device_peak_load"]
    data = [(float(r["time"]), float(r["opening_" + gauge]),
             abs(float(r["force_" + device + "_y"])),
             float(r["kinetic_energy"]) / max(float(r["strain_energy"]), 1e-30))
            for r in rows]
    first = next(i for i, d in enumerate(data) if d[0] > t_peak)
    parts = {"above": ([], []), "below": ([], [])}
    below = False
    for i in range(first, len(data) - 8, 8):
        span = data[i:i + 9]
        below = below or min(d[2] for d in span) / peak < 0.25
        share = (span[-1][1] - span[0][1]) / (span[-1][0] - span[0][0]) / rate
        part = parts["below" if below else "above"]
        part[0].append(share)
        part[1].append(max(d[3] for d in span))
    return t_peak, peak, parts, results["max_kinetic_share_after_peak"]


def main():
    rate, gauge, device = float(sys.argv[1]), sys.argv[2], sys.argv[3]
    for directory in sys.argv[4:]:
        t_peak, peak, parts, share = windows(directory, rate, gauge, device)
        line = f"{directory}: peak {peak / 1e3:.2f} kN at {t_peak * 1e3:.2f} ms"
        for name, (rates, kinetic) in parts.items():
            if rates:
                line += (f"; {name} a quarter: {len(rates)} windows, rate "
                         f"{min(rates):.3f}-{max(rates):.3f} of target, kinetic/strain "
                         f"up to {max(kinetic):.4f}")
        print(line + f"; max_kinetic_share_after_peak {share:.3f}")


if __name__ == "__main__":
    main()
