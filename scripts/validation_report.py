#!/usr/bin/env python3
"""Runs every scene of prm/ with its shipped settings (and the semicircular bending
test at its three notch angles) and writes the measured numbers beside their reference
values into doc/validation.md, between the markers

    <!-- validation_report.py: SCENE -->  ...  <!-- validation_report.py: end -->

so that the page's numbers are those of the last regeneration, not typed in. Each block
names the command that reproduces it, the wall time and the build's git revision.

    /usr/bin/python3 scripts/validation_report.py --build build [--out output/validation]
        [--only brazilian semicircular_bending ...] [--reuse] [--threads 2]

--reuse reads the runs already in --out instead of running them again (to redo the
page after editing this script; the blocks keep the revision of those runs). The whole set takes about 45 minutes on two cores
(the semicircular bending test at 2 mm/s is 10 minutes per angle).
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import time

# Reference values (doc/reference_data.md has their sources).
GRIFFITH_PEAK, GRIFFITH_OPENING = 0.0129, 0.00651
SCB_PAPER = {0: 176.0, 30: 220.0, 60: 300.0}
DROP_PAPER_IMPACT, DROP_PAPER_REACTION = 105.6e3, 59.5e3


def run_case(build, out, name, prm, sets, threads, reuse):
    directory = os.path.join(out, name)
    command = [os.path.abspath(os.path.join(build, "lme-mpm")), prm] + \
        sum([["--set", s] for s in sets], [])
    # As a user types it, from the repository's root with the build in build/.
    shown = " ".join(["./build/lme-mpm", prm] + ['--set "%s"' % s for s in sets])
    if not (reuse and os.path.exists(os.path.join(directory, "summary.json"))):
        start = time.time()
        subprocess.run(command + ["--threads", str(threads), "--set",
                                  "Output/Directory=" + directory, "--set",
                                  "Output/Verbosity=0", "--set",
                                  "Output/Write particle files=false"],
                       check=False, stdout=subprocess.DEVNULL)
        print(f"{name}: {time.time() - start:.0f} s", file=sys.stderr)
    with open(os.path.join(directory, "summary.json")) as f:
        summary = json.load(f)
    rows = []
    history = os.path.join(directory, "history.csv")
    if os.path.exists(history):
        with open(history) as f:
            rows = list(csv.DictReader(f))
    return summary, rows, shown


def entries(directory):
    """'Subsection/.../Entry' -> value of the run's parameters.prm (what it used)."""
    values, path = {}, []
    with open(os.path.join(directory, "parameters.prm")) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if line.startswith("subsection "):
                path.append(line[len("subsection "):].strip())
            elif line == "end" and path:
                path.pop()
            elif line.startswith("set ") and "=" in line:
                name, value = line[4:].split("=", 1)
                values["/".join(path + [name.strip()])] = value.strip()
    return values


def number(values, entry, index=0):
    return float(values[entry].split(",")[index])


def fmt(x, digits=4):
    if x is None:
        return "-"
    if isinstance(x, str):
        return x
    return f"{x:.{digits}g}"


def block(rows, summary, shown):
    """A Markdown table of (quantity, reference, measured) rows and the run's facts."""
    lines = ["| quantity | reference | this build |", "|---|---|---|"]
    for quantity, reference, measured in rows:
        lines.append(f"| {quantity} | {reference} | {measured} |")
    lines.append(
        f"| status, `max_energy_drift` | | {summary.get('status')}, "
        f"{fmt(summary.get('max_energy_drift'), 3)} |")
    lines.append("")
    lines.append(f"`{shown}` ({summary.get('steps')} steps, "
                 f"{summary.get('wall_seconds', 0):.0f} s wall on "
                 f"{summary.get('threads')} threads)")
    return "\n".join(lines)


def column_max(rows, column):
    values = [abs(float(r[column])) for r in rows if column in r and r[column] != ""]
    return max(values) if values else None


def scb_curve_checks(rows):
    """From an SCB history: the largest load once the load has fallen below 80 % of
    its peak (over the peak; a softening tail stays below 0.8), and the loading
    branch's slope over the last third of the travel from 0.01 mm to the first
    softening against the first third (1 for a straight branch)."""
    u = [-float(r["displacement_load_y"]) for r in rows]
    load = [float(r["force_load_y"]) for r in rows]
    damage = [float(r["damage_total"]) for r in rows]
    if not load:
        return None, None
    i_peak = max(range(len(load)), key=lambda i: load[i])
    peak = load[i_peak]
    below = next((i for i in range(i_peak, len(load)) if load[i] < 0.8 * peak), None)
    tail = max(load[below:]) / peak if below is not None else None
    soft = next((i for i in range(len(rows)) if damage[i] > 0), len(rows))
    span = [i for i in range(soft) if u[i] >= 1e-5]
    slope_ratio = None
    if len(span) >= 6:
        third = len(span) // 3

        def slope(ids):
            n = len(ids)
            mu = sum(u[i] for i in ids) / n
            mf = sum(load[i] for i in ids) / n
            return sum((u[i] - mu) * (load[i] - mf) for i in ids) / \
                sum((u[i] - mu) ** 2 for i in ids)
        slope_ratio = slope(span[-third:]) / slope(span[:third])
    return tail, slope_ratio


# The fracture scenes run with both damage forms: (run name, prm, --set values).
FRACTURE_SCENES = [
    ("tension_bar", "prm/tension_bar.prm", []),
    ("inclined_tension_bar_30", "prm/inclined_tension_bar.prm",
     ["Scene/inclined tension bar/Angle=30"]),
    ("brazilian", "prm/brazilian.prm", []),
    ("semicircular_bending_0", "prm/semicircular_bending.prm",
     ["Scene/semicircular bending/Notch angle=0"]),
    ("semicircular_bending_30", "prm/semicircular_bending.prm",
     ["Scene/semicircular bending/Notch angle=30"]),
    ("semicircular_bending_60", "prm/semicircular_bending.prm",
     ["Scene/semicircular bending/Notch angle=60"]),
    ("drop_weight", "prm/drop_weight.prm", ["Time/End time=1e-3"]),
]
FORMS = ("isotropic", "crack oriented")


def damage_forms_block(case, out):
    """Every eigensoftening scene with the isotropic and the crack-oriented damage form
    (the shipped file's form marked): peak, energy per unit crack area, the crack's
    band and the share of the energy dissipated off it."""
    lines = ["| scene | damage form | peak | reference | `fracture_energy_ratio` | "
             "`crack_band_width` (mm) | `dissipation_off_crack_share` | crack speed / "
             "c_R | status, drift |",
             "|---|---|---|---|---|---|---|---|---|"]
    commands = []
    for name, prm, sets in FRACTURE_SCENES:
        shipped, _, _ = case(name, prm, sets)
        e = entries(os.path.join(out, name))
        materials = [k.split("/")[0] for k, v in e.items()
                     if k.endswith("/Fracture/Model") and v == "eigensoftening"]
        form = e.get(materials[0] + "/Fracture/Damage form", "isotropic")
        for other in FORMS:
            if other == form:
                s, rows, cmd = case(name, prm, sets)
            else:
                extra = [m + "/Fracture/Damage form=" + other for m in materials]
                s, rows, cmd = case(name + "_" + other.replace(" ", "_"), prm,
                                    sets + extra)
                commands.append(cmd)
            peak, reference = "-", "-"
            if name == "tension_bar":
                area = number(e, "Problem/Thickness") * (
                    number(e, "Grid/Upper corner", 1) - number(e, "Grid/Lower corner", 1))
                force = column_max(rows, "force_right_x")
                peak = fmt(force / area / number(e, "Material 1/Fracture/Tensile "
                                                  "strength") if force else None, 3)
                reference = "1 (peak stress / f_t)"
                ratio = s.get("dissipated_energy", 0) / (
                    number(e, "Material 1/Fracture/Fracture energy") * area)
            elif name.startswith("inclined"):
                peak, reference = fmt(s.get("peak_stress", 0) / 2.7e6, 3), "1 (/ f_t)"
                ratio = s.get("fracture_energy_ratio")
            elif name == "brazilian":
                peak = fmt(s.get("splitting_strength", 0) /
                           number(e, "Material 1/Fracture/Tensile strength"), 3)
                reference = "1 (splitting strength / f_t)"
                ratio = s.get("fracture_energy_ratio")
            elif name.startswith("semicircular"):
                angle = int(name.rsplit("_", 1)[1])
                peak, reference = fmt(s.get("peak_force"), 4), f"{SCB_PAPER[angle]:g} N"
                ratio = s.get("fracture_energy_ratio")
            else:
                peak = fmt(s.get("peak_impact_force"), 4)
                reference = f"{DROP_PAPER_IMPACT:g} N"
                ratio = s.get("fracture_energy_ratio")
            width = s.get("crack_band_width")
            marked = f"**{other}** (shipped)" if other == form else other
            lines.append(
                f"| {name} | {marked} | {peak} | {reference} | {fmt(ratio, 3)} | "
                f"{fmt(width * 1e3 if width is not None else None, 3)} | "
                f"{fmt(s.get('dissipation_off_crack_share'), 3)} | "
                f"{fmt(s.get('max_crack_speed_over_rayleigh'), 3)} | "
                f"{s.get('status')}, {fmt(s.get('max_energy_drift'), 3)} |")
    lines.append("")
    lines.append("The shipped files' runs are the blocks' above; the others add "
                 "`--set \"Material N/Fracture/Damage form=...\"` for each material "
                 "with eigensoftening, for example")
    lines.append("")
    lines += [f"    {c}" for c in commands[:2]]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="output/validation")
    parser.add_argument("--only", nargs="*")
    parser.add_argument("--reuse", action="store_true")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--page", default="doc/validation.md")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)

    done = {}

    def case(name, prm, sets=()):
        # A run two blocks read (the damage forms' table reads the scenes' own) is
        # made once.
        if name not in done:
            done[name] = run_case(args.build, args.out, name, prm, list(sets),
                                  args.threads, args.reuse)
        return done[name]

    blocks = {}

    def wanted(scene):
        return not args.only or scene in args.only

    if wanted("vibrating_bar"):
        s, _, cmd = case("vibrating_bar", "prm/vibrating_bar.prm")
        blocks["vibrating_bar"] = block(
            [("largest displacement error (L2 over the bar, relative)", "0 (exact solution)",
              fmt(s.get("max_error_displacement_l2"), 3)),
             ("largest velocity error (L2, relative)", "0 (exact solution)",
              fmt(s.get("max_error_velocity_l2"), 3))], s, cmd)
    if wanted("vibrating_bar_3d"):
        s, _, cmd = case("vibrating_bar_3d", "prm/vibrating_bar_3d.prm")
        blocks["vibrating_bar_3d"] = block(
            [("largest displacement error (L2, relative)", "0 (exact solution)",
              fmt(s.get("max_error_displacement_l2"), 3))], s, cmd)
    if wanted("two_disk_collision"):
        s, _, cmd = case("two_disk_collision", "prm/two_disk_collision.prm")
        blocks["two_disk_collision"] = block(
            [("total energy drift", "0 (conserved)", fmt(s.get("max_energy_drift"), 3))],
            s, cmd)
    if wanted("tension_bar"):
        s, rows, cmd = case("tension_bar", "prm/tension_bar.prm")
        # The bar fills the grid's height; material 1 is its weak zone.
        e = entries(os.path.join(args.out, "tension_bar"))
        area = number(e, "Problem/Thickness") * (number(e, "Grid/Upper corner", 1) -
                                                  number(e, "Grid/Lower corner", 1))
        G_F = number(e, "Material 1/Fracture/Fracture energy")
        f_t = number(e, "Material 1/Fracture/Tensile strength")
        peak = column_max(rows, "force_right_x")
        blocks["tension_bar"] = block(
            [("dissipated energy / (G_F A)", "1", fmt(s.get("dissipated_energy", 0) /
                                                       (G_F * area))),
             ("peak stress / f_t of the weak zone", "1",
              fmt(peak / area / f_t if peak else None)),
             ("snapped-back particles", "0",
              fmt(s.get("eigensoftening_snap_back_particles")))], s, cmd)
    if wanted("inclined_tension_bar"):
        s, _, cmd = case("inclined_tension_bar_30", "prm/inclined_tension_bar.prm",
                         ["Scene/inclined tension bar/Angle=30"])
        blocks["inclined_tension_bar"] = block(
            [("`fracture_energy_ratio` at 30 degrees", "1",
              fmt(s.get("fracture_energy_ratio"))),
             ("`peak_stress` / f_t of the weak zone", "1",
              fmt(s.get("peak_stress", 0) / 2.7e6))], s, cmd)
    if wanted("inclined_tension_bar_3d"):
        s, _, cmd = case("inclined_tension_bar_3d_30_35", "prm/inclined_tension_bar_3d.prm",
                         ["Scene/inclined tension bar/Angle=30",
                          "Scene/inclined tension bar/Out-of-plane angle=35"])
        blocks["inclined_tension_bar_3d"] = block(
            [("`fracture_energy_ratio` at (30, 35) degrees", "1",
              fmt(s.get("fracture_energy_ratio"))),
             ("`peak_stress` / f_t of the weak zone", "1",
              fmt(s.get("peak_stress", 0) / 2.7e6)),
             ("`crack_area` (m^2)", "W^2 = 1e-4", fmt(s.get("crack_area")))], s, cmd)
    if wanted("mode_i_panel"):
        s, _, cmd = case("mode_i_panel", "prm/mode_i_panel.prm")
        blocks["mode_i_panel"] = block(
            [("peak reaction", f"{GRIFFITH_PEAK} (Griffith)", fmt(s.get("peak_force"))),
             ("opening at the peak", f"{GRIFFITH_OPENING} (Griffith)",
              fmt(s.get("displacement_at_peak")))], s, cmd)
    if wanted("brazilian"):
        s, _, cmd = case("brazilian", "prm/brazilian.prm")
        e = entries(os.path.join(args.out, "brazilian"))
        f_t = number(e, "Material 1/Fracture/Tensile strength")
        G_F_D_t = (number(e, "Material 1/Fracture/Fracture energy") *
                   number(e, "Scene/brazilian/Diameter") * number(e, "Problem/Thickness"))
        blocks["brazilian"] = block(
            [("splitting strength / f_t", "about 1 (Rocco et al. 1999: within 25 %)",
              fmt(s.get("splitting_strength", 0) / f_t)),
             ("peak load (N per m of thickness)", "-", fmt(s.get("peak_force"))),
             ("damage within D/10 of the loaded diameter", "most of it",
              fmt(s.get("damage_share_near_loaded_diameter"), 3)),
             ("damaged band's height / D", "-",
              fmt(s.get("softened_band_height_over_diameter"), 3)),
             ("dissipated energy / (G_F D t), one crack through the whole diameter",
              "at most the band height / D (one crack dissipating G_F)",
              fmt(s.get("dissipated_energy", 0) / G_F_D_t, 3)),
             ("snapped-back particles", "0",
              fmt(s.get("eigensoftening_snap_back_particles")))], s, cmd)
    if wanted("brazilian_3d"):
        s, _, cmd = case("brazilian_3d", "prm/brazilian_3d.prm")
        e = entries(os.path.join(args.out, "brazilian_3d"))
        f_t = number(e, "Material 1/Fracture/Tensile strength")
        # The plane-strain disc with the same entries at the same cell size.
        s2, _, _ = case("brazilian_3d_plane_strain", "prm/brazilian.prm",
                        ["Grid/Cell size=0.005", "Scene/brazilian/Strip width=0.025",
                         "Shape functions/Type=ugimp", "Scene/brazilian/Stop at load fraction=0.4",
                         "Time/End time=4e-3"])
        blocks["brazilian_3d"] = block(
            [("splitting strength / f_t", "about 1 (Rocco et al. 1999: within 25 %)",
              fmt(s.get("splitting_strength", 0) / f_t)),
             ("splitting strength / the 2D plane-strain disc's (same cell size)",
              "within 10 %", fmt(s.get("splitting_strength", 0) /
                                 s2.get("splitting_strength", float("nan")), 4)),
             ("`crack_plane_deviation` (cells)", "at most 1",
              fmt(s.get("crack_plane_deviation"), 3)),
             ("`fracture_energy_ratio`", "0.8-1.3", fmt(s.get("fracture_energy_ratio"), 3)),
             ("particles, steps", "-", f"{s.get('particles', 0):.0f}, {s.get('steps', 0):.0f}")],
            s, cmd)
    if wanted("semicircular_bending"):
        rows_all, shown, summaries = [], [], []
        for angle in (0, 30, 60):
            s, rows, cmd = case(f"semicircular_bending_{angle}",
                                "prm/semicircular_bending.prm",
                                [f"Scene/semicircular bending/Notch angle={angle}"])
            tail, slope_ratio = scb_curve_checks(rows)
            summaries.append(s)
            shown.append(cmd)
            rows_all += [
                (f"{angle} degrees: peak load (N)",
                 f"{SCB_PAPER[angle]:g} (Molinos et al. 2021)", fmt(s.get("peak_force"))),
                (f"{angle} degrees: `fracture_energy_ratio`, snapped back, drift", "1, 0, 0",
                 f"{fmt(s.get('fracture_energy_ratio'), 3)}, "
                 f"{fmt(s.get('eigensoftening_snap_back_particles'))}, "
                 f"{fmt(s.get('max_energy_drift'), 3)}"),
                (f"{angle} degrees: largest load after it fell below 0.8 of the peak, "
                 "over the peak", "below 0.8 (a softening tail)", fmt(tail, 3)),
                (f"{angle} degrees: softened share of the notch tip to the arc's top",
                 "1 (the crack reaches the loading roller)",
                 fmt(s.get("softened_ligament_share"), 3)),
                (f"{angle} degrees: loading slope, last third over first third of the "
                 "travel from 0.01 mm to the first softening", "1 within 0.05",
                 fmt(slope_ratio, 3))]
        lines = ["| quantity | reference | this build |", "|---|---|---|"]
        lines += [f"| {q} | {r} | {m} |" for q, r, m in rows_all]
        lines.append("")
        for cmd, s in zip(shown, summaries):
            lines.append(f"`{cmd}` ({s.get('status')}, {s.get('steps')} steps, "
                         f"{s.get('wall_seconds', 0):.0f} s wall on {s.get('threads')} "
                         "threads)  ")
        blocks["semicircular_bending"] = "\n".join(lines).rstrip()
    # The same hammer at the three speeds of the tests, and on one velocity field.
    for variant, prm, speed in (("drop_weight", "drop_weight", None),
                                ("drop_weight_v176", "drop_weight", 1.76),
                                ("drop_weight_v0881", "drop_weight", 0.881),
                                ("drop_weight_single_field", "drop_weight_single_field",
                                 None),
                                ("drop_weight_node_supports", "drop_weight_single_field",
                                 None)):
        if wanted(variant):
            sets = [f"Scene/drop weight/Impact velocity={speed}"] if speed else []
            if variant == "drop_weight_node_supports":
                # Contact with the hammer and the paper's bilateral supports: the
                # single-field file's node sets.
                sets = ["Contact/Type=multi-field",
                        "Scene/drop weight/Support kind=node sets"]
            # The files stop at 0.6 ms (the span of the paper's plots); these blocks
            # and doc/drop_weight.md's tables follow the beam to 1 ms.
            sets.append("Time/End time=1e-3")
            s, _, cmd = case(variant, f"prm/{prm}.prm", sets)
            paper = speed is None
            blocks[variant] = block(
                [("peak impact force (N)",
                  f"{DROP_PAPER_IMPACT:g} (Molinos et al. 2021; head calibrated to it)"
                  if paper else "-", fmt(s.get("peak_impact_force"))),
                 ("its time after the force starts (s)", "1e-4" if paper else "-",
                  fmt(s.get("time_of_peak_impact_force"))),
                 ("peak summed support reaction (N)",
                  f"{DROP_PAPER_REACTION:g}" if paper else "-",
                  fmt(s.get("peak_reaction_force"))),
                 ("its time after the force starts (s)", "1.66e-4" if paper else "-",
                  fmt(s.get("time_of_peak_reaction_force"))),
                 ("crack tip above the notch tip at the end (m)", "0.05 (the ligament)",
                  fmt(s.get("crack_tip"))),
                 ("largest crack speed (m/s)", "-", fmt(s.get("max_crack_speed"))),
                 ("over the Rayleigh speed", "-",
                  fmt(s.get("max_crack_speed_over_rayleigh"))),
                 ("largest speed of the softening front (m/s)", "-",
                  fmt(s.get("max_softening_front_speed"))),
                 ("over the Rayleigh speed", "up to 0.206 (Zhang et al. 2010, gauges)",
                  fmt(s.get("max_softening_front_speed_over_rayleigh"))),
                 ("dissipated energy (J)", "-", fmt(s.get("dissipated_energy")))], s, cmd)
    if wanted("damage_forms"):
        blocks["damage_forms"] = damage_forms_block(case, args.out)
    if wanted("sliding_block"):
        s, _, cmd = case("sliding_block", "prm/sliding_block.prm")
        blocks["sliding_block"] = block(
            [("sliding distance (m)", f"{fmt(s.get('sliding_distance_exact'))} (inclined "
              "plane, exact)", fmt(s.get("sliding_distance")))], s, cmd)
    if wanted("disc_drop"):
        s, _, cmd = case("disc_drop", "prm/disc_drop.prm")
        blocks["disc_drop"] = block(
            [("peak contact force on the slab (N)", "- (no Hertz estimate yet)",
              fmt(s.get("peak_contact_force_slab")))], s, cmd)

    revision = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True).stdout.strip()
    # Changes to the code not yet committed are named: the runs did not come from HEAD.
    if subprocess.run(["git", "status", "--porcelain", "source", "include"],
                      capture_output=True, text=True).stdout.strip():
        revision += " with local changes to the code"
    with open(args.page) as f:
        page = f.read()
    missing = []
    for scene, text in blocks.items():
        pattern = re.compile(r"(<!-- validation_report.py: %s -->\n).*?(<!-- "
                             r"validation_report.py: end -->)" % re.escape(scene), re.S)
        if not pattern.search(page):
            missing.append(scene)
            continue
        stamp = f"Generated by `scripts/validation_report.py` at revision {revision}:\n\n"
        if args.reuse:
            # The runs are the earlier ones: so is the revision they ran at.
            earlier = re.search(r"Generated by `scripts/validation_report.py` at revision "
                                r"[^\n]*\n\n", pattern.search(page).group(0))
            stamp = earlier.group(0) if earlier else stamp
        page = pattern.sub(lambda m: m.group(1) + stamp + text + "\n" + m.group(2), page)
    with open(args.page, "w") as f:
        f.write(page)
    if missing:
        print("no markers in the page for: " + ", ".join(missing), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
