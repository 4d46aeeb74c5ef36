#!/bin/sh
# Seed corpora for the fuzz targets, from the crate's fixtures, small
# hand-made inputs, and (when BRDF_DATA is set) the real measured files.
# Run from crates/brdf-io; writes fuzz/corpus/<target>/ (not committed).
set -eu
fx=tests/fixtures
c=fuzz/corpus
mkdir -p $c/cornell $c/csv_samples $c/nist $c/sopp_grid $c/merl $c/curet $c/tensor_file $c/rgl_tables
cp $fx/cornell/two.brdf $c/cornell/
cp $fx/nist/Line3.dat $c/nist/
printf 'theta_i,phi_i,theta_o,phi_o,r,g,weight\n0.1,0,0.2,3,0.5,0.25,1\n0.3,1,0.4,2,0.1,0.2,0.5\n' > $c/csv_samples/two.csv
printf 'light_theta_deg,camera_theta_deg,camera_phi_deg,r,g,b\n0,0,0,1,1,1\n5,2.5,5.142857142857143,1,2,3\n' > $c/sopp_grid/two.csv
{ cat $fx/curet/table.txt; printf '\000'; cat $fx/curet/rbrdf.dat; } > $c/curet/fixture
python3 - "$c" <<'PY'
import struct, sys
c = sys.argv[1]
# MERL: the 90 x 90 x 180 header and the first values.
open(f"{c}/merl/header", "wb").write(struct.pack("<3i", 90, 90, 180) + struct.pack("<4d", 1, 2, -1, 0.5))
# A tiny RGL material: 1 phi_i, 2 theta_i, 2 x 2 tables.
def tensor(fields):
    head = 18 + sum(2 + len(n) + 2 + 1 + 8 + 8 * len(s) for n, s, _ in fields)
    out = b"tensor_file\0" + bytes([1, 0]) + struct.pack("<I", len(fields))
    data, off = b"", head
    for n, s, v in fields:
        out += struct.pack("<H", len(n)) + n.encode() + struct.pack("<HBQ", len(s), 10, off)
        out += b"".join(struct.pack("<Q", d) for d in s)
        b = struct.pack(f"<{len(v)}f", *v); data += b; off += len(b)
    return out + data
ones = lambda n: [1.0] * n
f = [("phi_i", [1], [0.0]), ("theta_i", [2], [0.0, 1.5]), ("ndf", [2, 2], ones(4)),
     ("sigma", [2, 2], ones(4)), ("vndf", [1, 2, 2, 2], ones(8)), ("rgb", [1, 2, 3, 2, 2], ones(24))]
open(f"{c}/tensor_file/tiny.bsdf", "wb").write(tensor(f))
PY
if [ -n "${BRDF_DATA:-}" ]; then
    cp "$BRDF_DATA"/cornell/*.brdf $c/cornell/
    cp "$BRDF_DATA"/nist_strd/*.dat $c/nist/
    { cat "$BRDF_DATA"/curet/table.txt; printf '\000'; head -c 4000 "$BRDF_DATA"/curet/abrdf.dat; } > $c/curet/real
fi
