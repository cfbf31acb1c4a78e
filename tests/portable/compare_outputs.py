#!/usr/bin/env python3
"""Compares two `pss project` CSV outputs of the same cloud computed by the core's two copies (the
x86-64 baseline and x86-64-v3, whose fused multiply-adds round differently): the same rows and
columns, the same integer columns (Iterations, Converged, ExtremumType, StopReason), every other
value within a tolerance. Prints the largest differences; exit 0 when they agree.

    compare_outputs.py --h H [--tolerance T] [--energy-in-h2] BASELINE.csv V3.csv

Coordinates and displacements must agree within T * h, normals, stabilities and the other
unitless columns within T, energies within T relative to the largest energy of the file, or with
--energy-in-h2 within T * h^2: for definitions whose energy is a squared length that vanishes on
the surface (APSS and RIMLS: f^2), so that every energy of a converged projection is rounding
noise and the largest one is no scale.
"""
import argparse
import csv
import sys

EXACT = {"Iterations", "Converged", "ExtremumType", "StopReason"}
LENGTHS = ("x", "y", "z", "Displacement", "distancetoshape")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--h", type=float, required=True)
    parser.add_argument("--tolerance", type=float, default=1e-10)
    parser.add_argument("--energy-in-h2", action="store_true")
    parser.add_argument("baseline")
    parser.add_argument("v3")
    args = parser.parse_args()
    with open(args.baseline) as f:
        a = list(csv.DictReader(f))
    with open(args.v3) as f:
        b = list(csv.DictReader(f))
    if len(a) != len(b) or not a or list(a[0]) != list(b[0]):
        print("FAIL: the files differ in rows or columns (%d and %d rows)" % (len(a), len(b)))
        return 1
    energy_scale = max(abs(float(r["Energy"])) for r in a) if "Energy" in a[0] else 1.0
    if args.energy_in_h2:
        energy_scale = args.h * args.h
    worst = {}
    failed = False
    for row, (r, s) in enumerate(zip(a, b)):
        for column in r:
            if column in EXACT:
                if r[column] != s[column]:
                    print("FAIL: row %d, %s: %s against %s" % (row, column, r[column], s[column]))
                    failed = True
                continue
            difference = abs(float(r[column]) - float(s[column]))
            if column.startswith(LENGTHS):
                scale = args.h
            elif column == "Energy":
                scale = energy_scale
            else:
                scale = 1.0
            worst[column] = max(worst.get(column, 0.0), difference / scale)
    for column, difference in sorted(worst.items()):
        verdict = "ok  " if difference <= args.tolerance else "FAIL"
        failed = failed or difference > args.tolerance
        print("%s %s: largest difference %.3g (tolerance %.3g)" % (verdict, column, difference, args.tolerance))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
