#!/usr/bin/env python3
"""Every particle field that doc/outputs.md documents is in a written particle file,
with one value per particle (dim values for a vector), and nothing undocumented is:
a 2D tension bar that cracks and a 3D bar, read back from their VTU files.

    vtu_fields.py LME_MPM_BINARY SOURCE_DIR WORK_DIR
"""
import base64
import os
import re
import shutil
import struct
import subprocess
import sys
import zlib

binary, source, work = sys.argv[1:4]
failures = []


def check(ok, what):
    print(("ok:     " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


def documented_fields(dim):
    """{name: number of components} of the particle-file table of doc/outputs.md."""
    with open(os.path.join(source, "doc", "outputs.md")) as f:
        text = f.read()
    start = text.index("## particles.pvd")
    table = text[start:text.index("\n## ", start + 1)]
    fields = {}
    for row in re.findall(r"^\| `([a-z_]+)` \|(.*)$", table, re.M):
        name, rest = row
        if "3D runs" in rest.split("|")[-2] and dim == 2:
            continue
        fields[name] = dim if "Vector:" in rest else 1
    return fields


def decode(element, text):
    """The values of one binary (zlib, base64) or ascii DataArray."""
    kind = re.search(r'type="(\w+)"', element).group(1)
    size = {"Float32": 4, "Float64": 8, "Int32": 4, "UInt8": 1, "Int64": 8}[kind]
    code = {"Float32": "f", "Float64": "d", "Int32": "i", "UInt8": "B", "Int64": "q"}[kind]
    if 'format="ascii"' in element:
        return [float(x) for x in text.split()]
    text = text.strip()
    # A header of UInt32 block counts and sizes, base64 on its own, then the blocks.
    head = base64.b64decode(text[:8])
    n_blocks = struct.unpack("<I", head[:4])[0]
    header_len = 4 * (3 + n_blocks)
    header_chars = 4 * ((header_len + 2) // 3)
    header = struct.unpack("<%dI" % (3 + n_blocks), base64.b64decode(text[:header_chars]))
    data = base64.b64decode(text[header_chars:])
    raw, offset = b"", 0
    for c in header[3:]:
        raw += zlib.decompress(data[offset:offset + c])
        offset += c
    return list(struct.unpack("<%d%s" % (len(raw) // size, code), raw))


def read_point_data(path):
    with open(path) as f:
        text = f.read()
    n = int(re.search(r'NumberOfPoints="(\d+)"', text).group(1))
    point_data = text[text.index("<PointData"):text.index("</PointData>")]
    arrays = {}
    for element, body in re.findall(r"(<DataArray[^>]*>)(.*?)</DataArray>", point_data, re.S):
        name = re.search(r'Name="([^"]+)"', element).group(1)
        comps = re.search(r'NumberOfComponents="(\d+)"', element)
        arrays[name] = (int(comps.group(1)) if comps else 1, decode(element, body))
    return n, arrays


def run(name, prm, dim, extra):
    out = os.path.join(work, name)
    subprocess.run([binary, os.path.join(source, "prm", prm), "--set",
                    "Output/Write particle files=true", "--set", "Output/Directory=" + out]
                   + sum((["--set", e] for e in extra), []),
                   check=True, stdout=subprocess.DEVNULL)
    files = sorted(f for f in os.listdir(out) if re.match(r"particles_\d+\.vtu$", f))
    n, arrays = read_point_data(os.path.join(out, files[-1]))
    fields = documented_fields(dim)
    check(n > 100, "%s: %d particles in %s" % (name, n, files[-1]))
    for field, comps in fields.items():
        if field not in arrays:
            check(False, "%s: documented field '%s' is missing" % (name, field))
            continue
        # deal.II writes a vector with 3 components in 2D (the z one zero).
        written, values = arrays[field]
        want = comps if comps == 1 else (3 if dim == 2 else dim)
        check(written == want and len(values) == n * want,
              "%s: %s has %d components and %d values for %d particles"
              % (name, field, written, len(values), n))
    extra_fields = sorted(set(arrays) - set(fields))
    check(not extra_fields, "%s: undocumented fields %s" % (name, extra_fields))
    return arrays


shutil.rmtree(work, ignore_errors=True)
# The bar is pulled until its weak band has softened: crack fields are not all zero.
bar = run("tension_bar", "tension_bar.prm", 2, [])
check(max(bar["dissipated_energy_density"][1]) > 0, "tension bar: some energy dissipated")
check(max(bar["crack_opening"][1]) > 0, "tension bar: some crack opening")
check(min(bar["size"][1]) > 0, "tension bar: every size positive")
run("bar_3d", "vibrating_bar_3d.prm", 3, ["Time/End time=2e-4"])

if failures:
    sys.exit("%d check(s) failed" % len(failures))
