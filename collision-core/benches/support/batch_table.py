#!/usr/bin/env python3
"""Median ns per collision of `cargo bench -p collision-core --bench batch`, with ratios.

Reads criterion's target/criterion/batch_{in,out}_dN/<variant>/new/{estimates,benchmark}.json
(run from the workspace root) and prints the Markdown tables of docs/batch.md.
"""
import json
import os

ROOT = "target/criterion"


def ns(group, variant):
    d = os.path.join(ROOT, group, variant, "new")
    try:
        median = json.load(open(os.path.join(d, "estimates.json")))["median"]["point_estimate"]
        elements = json.load(open(os.path.join(d, "benchmark.json")))["throughput"]["Elements"]
    except (OSError, KeyError):
        return None
    return median / elements


def fmt(x, digits=2):
    return "-" if x is None else f"{x:.{digits}f}"


def table(where, variants):
    print(f"\n{where} (median ns per collision; ratios to the floor and to scalar)\n")
    head = ["n", "floor", "scalar"] + variants + [f"{v}/floor" for v in variants] + [
        f"{v}/scalar" for v in variants
    ]
    print("| " + " | ".join(head) + " |")
    print("|" + "---:|" * len(head))
    for n in range(2, 7):
        g = f"batch_{where}_d{n}"
        floor, scalar = ns(g, "floor"), ns(g, "scalar")
        times = [ns(g, v) for v in variants]
        row = [str(n), fmt(floor), fmt(scalar)] + [fmt(t) for t in times]
        row += [fmt(t / floor if t and floor else None) for t in times]
        row += [fmt(t / scalar if t and scalar else None) for t in times]
        print("| " + " | ".join(row) + " |")


def threads():
    print("\nl2 (median ns per collision, one thread and two)\n")
    print("| n | serial | rayon | rayon / serial |")
    print("|---:|---:|---:|---:|")
    for n in range(2, 7):
        g = f"batch_l2_d{n}"
        serial, rayon = ns(g, "batch_serial"), ns(g, "batch_rayon")
        ratio = rayon / serial if serial and rayon else None
        print(f"| {n} | {fmt(serial)} | {fmt(rayon)} | {fmt(ratio)} |")


table(
    "in",
    [
        "batch_baseline",
        "batch_baseline_w2",
        "batch_baseline_w8",
        "scalar_lanes",
        "batch_avx2",
        "batch_avx2_w8",
        "batch_avx512",
        "batch_rayon",
    ],
)
threads()
table("out", ["batch_baseline", "batch_avx2", "batch_avx512", "batch_rayon", "floor_rayon"])
