#!/usr/bin/env python3
"""noslip's event loop beside F. Smallenburg's EDMD, side by side in alternated rounds.

The peer (Eur. Phys. J. E 45, 22 (2022); github.com/FSmallenburg/EDMD) is never vendored:
give the path of a checkout. Its ``Cell`` and ``Single`` variants are compiled here, in a
temporary directory, with the flags of their own Makefiles (``-Ofast -funroll-loops
-march=native``), each source included unchanged by a small harness that sets ``N``,
``packfrac`` and the FCC start (``initialconfig = 1``), runs ``warm`` collisions, then times
one stretch of ``contacts`` collisions with ``clock()`` (the process's CPU time). The stretch
is ``max(N, 10^6)`` collisions unless ``--contacts`` says otherwise: one to four seconds a
program at these ``N`` (a stretch of 2 10^5, a fifth of a second at ``N`` = 4000, moved by up
to 40 % between rounds on a shared host).

noslip's side is ``sim/examples/event_rate`` (built here in release) on the 3D gas of the
same ``N`` and ``phi``, smooth contacts (as the peer's), one stretch per round.

Each round runs noslip, Cell and Single once per ``(N, phi)``, and the rounds alternate
(noslip, peer, noslip, peer, ...); the table gives the median and the min-max of microseconds
per collision over the rounds, and noslip's speed over the best variant's as the median
(min-max) of the ratios within each round (the faster of Cell and Single in that round over
noslip in that round): programs run back to back in a round share the machine's load of the
moment, so these paired ratios move less than a ratio of two medians would.

Usage::

    scripts/peer_edmd.py PATH/TO/EDMD [--balls 4000,32000,108000]
        [--phi 0.1,0.2,0.3,0.4] [--rounds 3] [--contacts C] [--no-slip] [--noslip BINARY]
        [--before BINARY] [--lists SKIN]

``--before`` adds an earlier build of ``event_rate`` to every round (before, noslip, Cell,
Single), and the table its times and noslip's time over them (paired within each round too).
``--lists SKIN`` adds noslip's list engine (``event_rate --lists SKIN``, the same binary) to
every round, and the table its times and its speed over the best variant's (paired).

A second table gives each program's peak resident memory (the before build's and the list
engine's too, when they run) and, between successive ``N``, the bytes each added ball costs.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent

HARNESS = r"""
#define main peer_original_main
#include "{source}"
#undef main
#include <time.h>

int main(int argc, char **argv)
{{
    N = atoi(argv[1]);
    packfrac = atof(argv[2]);
    long warm = atol(argv[3]), contacts = atol(argv[4]);
    initialconfig = 1;
    makesnapshots = 0;
    init();
    unsigned int start = colcounter;
    while ((long)(colcounter - start) < warm) step();
    start = colcounter;
    clock_t t0 = clock();
    while ((long)(colcounter - start) < contacts) step();
    double seconds = (double)(clock() - t0) / CLOCKS_PER_SEC;
    fprintf(stderr, "PEER %.6f\n", 1e6 * seconds / (double)(colcounter - start));
    return 0;
}}
"""


def build_peer(checkout: Path, variant: str, work: Path) -> Path:
    """Compile one variant of the peer with its Makefile's flags; the binary's path."""
    source = checkout / variant / f"md{variant}.c"
    if not source.exists():
        sys.exit(f"{source}: not found (give the path of an EDMD checkout)")
    harness = work / f"harness_{variant}.c"
    harness.write_text(HARNESS.format(source=source))
    binary = work / f"peer_{variant}"
    flags = ["-Ofast", "-funroll-loops", "-march=native", "-w"]
    command = ["gcc", *flags, f"-I{source.parent}", str(harness), "-o", str(binary), "-lm"]
    subprocess.run(command, check=True)
    return binary


def run_measured(args: list[str], cwd: str | None = None) -> tuple[str, str, int]:
    """Run ``args``; its standard output and error, and its peak resident memory in bytes
    (``ru_maxrss`` of this child alone, from ``wait4``; the output goes through files so that
    nothing but ``wait4`` reaps the child)."""
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        child = subprocess.Popen(args, cwd=cwd, stdout=out, stderr=err, text=True)
        _, status, usage = os.wait4(child.pid, 0)
        child.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        stdout, stderr = out.read(), err.read()
    if child.returncode != 0:
        sys.exit(f"{args[0]} failed ({child.returncode}): {stderr}")
    return stdout, stderr, usage.ru_maxrss * 1024


def run_peer(binary: Path, n: int, phi: float, warm: int, contacts: int) -> tuple[float, int]:
    """Microseconds per collision of one timed stretch, and the peak memory in bytes."""
    with tempfile.TemporaryDirectory() as cwd:
        _, err, peak = run_measured([str(binary), str(n), str(phi), str(warm), str(contacts)], cwd)
    line = [x for x in err.splitlines() if x.startswith("PEER ")][-1]
    return float(line.split()[1]), peak


def run_noslip(
    binary: Path,
    n: int,
    phi: float,
    warm: int,
    contacts: int,
    smooth: bool,
    extra: list[str] | None = None,
) -> tuple[float, int]:
    """Microseconds per contact of one timed stretch of ``event_rate`` (with the arguments
    ``extra`` added), and the peak memory in bytes."""
    args = [str(binary), "--dims", "3", "--balls", str(n), "--phi", str(phi), "--runs", "1"]
    args += ["--warm", str(warm), "--contacts", str(contacts), *(extra or [])]
    if smooth:
        args.append("--smooth")
    out, _, peak = run_measured(args)
    row = out.splitlines()[-1].split()
    if "skipped:" in row:
        sys.exit(f"event_rate: {out}")
    return float(row[4]), peak


def spread(xs: list[float]) -> str:
    """``median (min-max)``."""
    return f"{statistics.median(xs):.2f} ({min(xs):.2f}-{max(xs):.2f})"


def paired(ours: list[float], cell: list[float], single: list[float]) -> str:
    """The speed of ``ours`` over the faster peer variant, round by round: ``median
    (min-max)`` of ``min(cell_r, single_r) / ours_r`` (times per collision)."""
    return spread([min(c, s) / o for o, c, s in zip(ours, cell, single)])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("checkout", type=Path)
    parser.add_argument("--balls", default="4000,32000,108000")
    parser.add_argument("--phi", default="0.1,0.2,0.3,0.4")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--contacts", type=int, default=None)
    parser.add_argument("--no-slip", action="store_true", help="noslip's contacts no-slip")
    parser.add_argument(
        "--noslip",
        type=Path,
        default=None,
        help="an event_rate binary to time (default: the repository's, built in release here)",
    )
    parser.add_argument(
        "--before",
        type=Path,
        default=None,
        help="an earlier event_rate binary, timed in the same rounds",
    )
    parser.add_argument(
        "--lists",
        type=float,
        default=None,
        help="also time noslip's list engine with this skin (event_rate --lists SKIN)",
    )
    a = parser.parse_args()
    balls = [int(x) for x in a.balls.split(",")]
    phis = [float(x) for x in a.phi.split(",")]
    ours = a.noslip or REPO / "target" / "release" / "examples" / "event_rate"
    if a.noslip is None:
        subprocess.run(
            ["cargo", "build", "--release", "-q", "-p", "noslip-sim", "--example", "event_rate"],
            cwd=REPO,
            check=True,
        )
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        peers = {v: build_peer(a.checkout.resolve(), v, work) for v in ("Cell", "Single")}
        times: dict[tuple[int, float, str], list[float]] = {}
        peaks: dict[tuple[int, float, str], int] = {}
        for r in range(a.rounds):
            for n in balls:
                warm = max(2 * n, 100_000)
                contacts = a.contacts or max(n, 1_000_000)
                for phi in phis:
                    order = ["noslip", "Cell", "Single"]
                    if a.before is not None:
                        order.insert(0, "before")
                    if a.lists is not None:
                        order.insert(1, "lists")
                    if r % 2:
                        order.reverse()
                    for who in order:
                        if who in ("noslip", "before", "lists"):
                            binary = a.before if who == "before" else ours
                            extra = ["--lists", str(a.lists)] if who == "lists" else []
                            smooth = not a.no_slip
                            t, peak = run_noslip(binary, n, phi, warm, contacts, smooth, extra)
                        else:
                            t, peak = run_peer(peers[who], n, phi, warm, contacts)
                        times.setdefault((n, phi, who), []).append(t)
                        peaks[(n, phi, who)] = max(peaks.get((n, phi, who), 0), peak)
                        print(f"round {r + 1}: N {n} phi {phi} {who}: {t:.3f} us", file=sys.stderr)
    kind = "no-slip" if a.no_slip else "smooth"
    load = os.getloadavg()
    print(f"# us per collision, medians (min-max) of {a.rounds} alternated rounds; noslip {kind};")
    print("# speed over the best peer: median (min-max) of the ratios within each round")
    print(f"# load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f} at the end")
    before = a.before is not None
    head = "| N | phi | " + ("before | " if before else "") + "noslip | "
    head += "noslip / before (time) | " if before else ""
    lists = a.lists is not None
    tail = " lists | lists / best peer (speed) |" if lists else ""
    print(head + "peer Cell | peer Single | noslip / best peer (speed) |" + tail)
    rule = "|---:|---:|" + ("---:|---:|" if before else "") + "---:|---:|---:|---:|"
    print(rule + ("---:|---:|" if lists else ""))
    for n in balls:
        for phi in phis:
            ours, cell, single = (times[(n, phi, w)] for w in ("noslip", "Cell", "Single"))
            row = f"| {n} | {phi} | "
            if before:
                old = times[(n, phi, "before")]
                gain = spread([o / b for o, b in zip(ours, old)])
                row += f"{spread(old)} | {spread(ours)} | {gain} | "
            else:
                row += f"{spread(ours)} | "
            row += f"{spread(cell)} | {spread(single)} | {paired(ours, cell, single)} |"
            if lists:
                by_lists = times[(n, phi, "lists")]
                row += f" {spread(by_lists)} | {paired(by_lists, cell, single)} |"
            print(row)
    print()
    print("# peak resident memory (ru_maxrss, MiB; it counts the forking Python too, about")
    print("# 15 MiB), and bytes per ball added from the previous N (the memory a ball costs)")
    programs = (["before"] if before else []) + ["noslip"] + (["lists"] if lists else [])
    programs += ["Cell", "Single"]
    names = {"Cell": "peer Cell", "Single": "peer Single"}
    print("| N | phi | " + " | ".join(names.get(w, w) for w in programs) + " |")
    print("|---:|---:|" + "---:|" * len(programs))
    for phi in phis:
        for k, n in enumerate(balls):
            entries = []
            for w in programs:
                entry = f"{peaks[(n, phi, w)] / 2**20:.0f} MiB"
                if k > 0:
                    m = balls[k - 1]
                    per = (peaks[(n, phi, w)] - peaks[(m, phi, w)]) / (n - m)
                    entry += f", {per:.0f} B/ball"
                entries.append(entry)
            print(f"| {n} | {phi} | " + " | ".join(entries) + " |")

if __name__ == "__main__":
    main()
