#!/usr/bin/python3
"""Drop-weight impact: for each run, the impact force and the summed support reaction
against the time from the start of the impact force, with the peaks of the paper's
simulation (doc/reference_data.md section 5) marked at their times after its force
started, above the beam's final damage drawn on its reference configuration (the
crack pattern); below them, the heights above the notch tip of the fully softened
crack's tip (solid) and of the softening front (dashed) against time for all runs, in
one PNG.

    /usr/bin/python3 scripts/plot_drop_weight.py out/v264 out/v176 out/v088 \\
        --labels "2.64 m/s,1.76 m/s,0.881 m/s" --out drop_weight.png

Each argument is an output directory of prm/drop_weight.prm (history.csv,
summary.json, damage.csv). Forces are impact_force and reaction_force (kN, for the
beam's real thickness); damage is the particles' effective damage chi in [0, 1]
(damage.csv, body 0 = the beam).
"""
import json
import os

import matplotlib
from scene_plots import parse_runs, read_rows

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Molinos et al., simulated at 2.64 m/s: (time in ms after their impact force started,
# 0.039 ms after contact; force in kN).
PAPER_START = 0.039
PAPER_IMPACT = (0.139 - PAPER_START, 105.6)
PAPER_REACTION = (0.205 - PAPER_START, 59.5)


def main():
    args, labels = parse_runs(__doc__, "drop_weight.png")

    n = len(args.runs)
    fig = plt.figure(figsize=(5.0 * n, 9.0))
    grid = fig.add_gridspec(3, n)
    axes = [[fig.add_subplot(grid[row, i]) for i in range(n)] for row in range(2)]
    tips = fig.add_subplot(grid[2, :])
    for i, run in enumerate(args.runs):
        history = read_rows(os.path.join(run, "history.csv"), "drop-weight")
        with open(os.path.join(run, "summary.json")) as f:
            summary = json.load(f)
        t0 = summary.get("time_of_first_contact", 0.0)
        t = [1e3 * (float(r["time"]) - t0) for r in history]
        top = axes[0][i]
        top.plot(t, [1e-3 * float(r["impact_force"]) for r in history], label="impact")
        top.plot(t, [1e-3 * float(r["reaction_force"]) for r in history],
                 label="supports, summed")
        top.plot(*PAPER_IMPACT, "v", color="C0", label="paper: impact peak")
        top.plot(*PAPER_REACTION, "^", color="C1", label="paper: reaction peak")
        top.set_xlabel("time from the force's start (ms)")
        top.set_ylabel("force (kN)")
        top.set_title("%s: peaks %.0f / %.0f kN" % (
            labels[i], 1e-3 * summary.get("peak_impact_force", 0),
            1e-3 * summary.get("peak_reaction_force", 0)))
        top.grid(alpha=0.3)
        top.legend(fontsize=7)
        damage = [r for r in read_rows(os.path.join(run, "damage.csv"), "drop-weight")
                  if r.get("body", "0") == "0"]
        bottom = axes[1][i]
        sc = bottom.scatter([1e3 * float(r["x0_0"]) for r in damage],
                            [1e3 * float(r["x0_1"]) for r in damage],
                            c=[float(r["damage"]) for r in damage], s=0.6,
                            cmap="inferno_r", vmin=0, vmax=1)
        bottom.set_aspect("equal")
        bottom.set_xlabel("x (mm)")
        bottom.set_ylabel("y (mm)")
        fig.colorbar(sc, ax=bottom, shrink=0.6, label="damage")
        if "crack_tip" in history[0]:
            line, = tips.plot(t, [1e3 * float(r["crack_tip"]) for r in history],
                              label="%s: fully softened" % labels[i])
        if "softening_front" in history[0]:
            tips.plot(t, [1e3 * float(r["softening_front"]) for r in history], "--",
                      color=line.get_color(),
                      label="%s: softening front, max %.0f m/s" % (
                          labels[i], summary.get("max_softening_front_speed", 0)))
    tips.set_xlabel("time from the force's start (ms)")
    tips.set_ylabel("crack tip above the notch tip (mm)")
    tips.grid(alpha=0.3)
    tips.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
