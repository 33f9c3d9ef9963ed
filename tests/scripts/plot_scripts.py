#!/usr/bin/env python3
"""The plot scripts read a run's own geometry: a Brazilian test on a 100 mm disc (not
the shipped 150 mm one) is drawn with a nominal stress whose peak equals the run's
splitting_strength, and the generic load-opening script finds the run's opening gauge
and its loading strip's force.

    plot_scripts.py LME_MPM_BINARY SOURCE_DIR WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys

binary, source, work = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "scripts"))
import plot_brazilian  # noqa: E402
import plot_load_opening  # noqa: E402

failures = []


def check(ok, what):
    print(("ok:     " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


shutil.rmtree(work, ignore_errors=True)
run = os.path.join(work, "disc_100mm")
subprocess.run([binary, os.path.join(source, "prm", "brazilian.prm"),
                "--set", "Scene/brazilian/Diameter=0.1",
                "--set", "Grid/Cell size=0.005",
                "--set", "Output/Directory=" + run, "--threads", "2"],
               check=True, stdout=subprocess.DEVNULL)
with open(os.path.join(run, "summary.json")) as f:
    summary = json.load(f)

approach, stress, geometry = plot_brazilian.curve(run)
check(geometry["diameter"] == 0.1 and geometry["thickness"] == 1.0,
      "D and t from the run's parameters.prm: %s" % geometry)
peak = max(stress)
strength = 1e-6 * summary["splitting_strength"]
check(abs(peak / strength - 1) < 1e-3,
      "drawn peak %.6g MPa against splitting_strength %.6g MPa" % (peak, strength))
check(geometry["tensile_strength"] == 5.4e6,
      "f_t from the disc's material: %s" % geometry["tensile_strength"])

w, p, force, opening = plot_load_opening.curve(run)
# The scene's own gauge across the disc is the run's only one.
check(opening == "opening_diameter", "opening column %s" % opening)
check(force in ("force_top_mean_y", "force_bottom_mean_y"), "force column %s" % force)
check(abs(max(p) / summary["peak_force"] - 1) < 0.02,
      "load-opening peak %.6g N against peak_force %.6g N" % (max(p), summary["peak_force"]))
# The disc widens under load: the lateral opening at the peak is more than at half of it.
i = max(range(len(p)), key=lambda k: p[k])
half = next(k for k in range(len(p)) if p[k] >= 0.5 * p[i])
check(w[i] > w[half] > 0, "opening %.3g m at half the peak, %.3g m at the peak" % (w[half], w[i]))

# The figures themselves, where a Python with matplotlib is at hand.
drawer = next((py for py in (sys.executable, "/usr/bin/python3") if subprocess.run(
    [py, "-c", "import matplotlib"], stderr=subprocess.DEVNULL).returncode == 0), None)
if drawer is None:
    print("note: no Python with matplotlib here; the figures are not drawn")
else:
    for script, out in (("plot_brazilian.py", "brazilian.png"),
                        ("plot_load_opening.py", "load_opening.png")):
        png = os.path.join(work, out)
        subprocess.run([drawer, os.path.join(source, "scripts", script), run, "--out", png],
                       check=True, stdout=subprocess.DEVNULL)
        check(os.path.getsize(png) > 10000, "%s drew %s" % (script, png))

# The mode-I panel's Griffith line follows the run's own material and size: on the
# reference proportions the finite-element line scaled (E doubled, G_c four times:
# stiffness x 2, delta_c x sqrt(2)); on others the fixed-grip strip's.
if drawer is not None:
    def griffith_line(name, sets):
        panel = os.path.join(work, name)
        command = [binary, os.path.join(source, "prm", "mode_i_panel.prm"),
                   "--set", "Time/End time=1", "--set", "Output/Directory=" + panel]
        for s in sets:
            command += ["--set", s]
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
        out = subprocess.run([drawer, os.path.join(source, "scripts", "plot_mode_i.py"),
                              panel, "--out", panel + ".png"], check=True,
                             capture_output=True, text=True).stdout
        line = next(l for l in out.splitlines() if l.startswith("Griffith:"))
        words = line.replace(",", "").split()
        return float(words[2]), float(words[4]), line

    k, dc, _ = griffith_line("mode_i_reference", [])
    check(abs(k - 0.990) < 1e-9 and abs(dc - 0.00651) < 1e-9,
          "reference panel: stiffness %.6g, delta_c %.6g" % (k, dc))
    k, dc, _ = griffith_line("mode_i_scaled", [
        "Material 1/linear elastic/Young's modulus=2.12",
        "Material 1/Fracture/Fracture energy=4e-4"])
    check(abs(k / 1.98 - 1) < 1e-3 and abs(dc / (0.00651 * 2 ** 0.5) - 1) < 1e-3,
          "E x 2, G_c x 4: stiffness %.6g, delta_c %.6g" % (k, dc))
    k, dc, line = griffith_line("mode_i_wide", [
        "Body 1/Shape=rectangle(0, 0, 1.5, 1)", "Grid/Upper corner=2, 1.1"])
    E_prime = 1.06 / (1 - 0.333 ** 2)
    check("strip" in line and abs(dc / (1e-4 / (2 * E_prime)) ** 0.5 - 1) < 1e-3
          and abs(k / (E_prime * 1.5) - 1) < 1e-3, "other proportions: " + line)

# The notched beam's figure draws the run's own curves: its CSV holds every history row,
# the load at each is the loading roller's force, and the beam's damage is drawn from
# the run's own corner and length (a beam moved and shortened from the shipped one).
if drawer is not None:
    beam = os.path.join(work, "beam")
    subprocess.run([binary, os.path.join(source, "prm", "three_point_bending.prm"),
                    "--set", "Grid/Cell size=0.005", "--set", "Time/End time=0.002",
                    "--set", "Scene/three point bending/Notch width=0.005",
                    "--set", "Scene/three point bending/CMOD gauge length=0.015",
                    "--set", "Scene/three point bending/Beam corner=0.015, 0.015",
                    "--set", "Scene/three point bending/Length=0.165",
                    "--set", "Scene/three point bending/Span=0.12",
                    "--set", "Output/Directory=" + beam], check=True,
                   stdout=subprocess.DEVNULL)
    table = os.path.join(work, "beam.csv")
    subprocess.run([drawer, os.path.join(source, "scripts", "plot_three_point_bending.py"),
                    beam, "--reference", "--csv", table, "--out", beam + ".png"],
                   check=True, stdout=subprocess.DEVNULL)
    import csv
    with open(table) as f:
        drawn = list(csv.DictReader(f))
    with open(os.path.join(beam, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    check(len(drawn) == len(rows), "beam: %d rows drawn of %d" % (len(drawn), len(rows)))
    def same(a, b):
        return abs(float(a) - float(b)) <= 1e-9 * max(abs(float(b)), 1e-12)
    check(all(same(d["load"], r["force_load_mean_y"]) and same(d["cmod"], r["opening_cmod"])
              for d, r in zip(drawn, rows)),
        "beam: load and CMOD drawn are the run's force_load_mean_y and opening_cmod")
    check(max(float(d["load"]) for d in drawn) > 100, "beam: the beam is loaded")
    check(os.path.getsize(beam + ".png") > 10000, "plot_three_point_bending.py drew a figure")

if failures:
    sys.exit("%d check(s) failed" % len(failures))
