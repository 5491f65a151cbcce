"""noslip.simulate keeps only what is cheap by default and caps the records it keeps
(issue 26, item 9); its `time` is refused as `noslip simulate --time` refuses it (item 11)."""

import subprocess
import sys
import textwrap

import numpy as np
import pytest

import noslip

#: The address-space limit of the child processes: the black-box run's 2 GiB.
LIMIT = 2 << 30


def run_limited(code: str, timeout: float = 300) -> subprocess.CompletedProcess:
    """`code` in a fresh interpreter whose address space is capped at LIMIT bytes."""
    prelude = textwrap.dedent(f"""
        import resource
        resource.setrlimit(resource.RLIMIT_AS, ({LIMIT}, {LIMIT}))
        import noslip
    """)
    return subprocess.run(
        [sys.executable, "-c", prelude + textwrap.dedent(code)],
        capture_output=True, text=True, timeout=timeout, check=False,
    )


def test_a_huge_logged_run_is_refused_up_front_not_aborted():
    """`events=10**8` with the log kept once grew the log in memory (about 0.9 kB a
    contact) until the interpreter died (SIGABRT under 2 GiB); now it is an InputError
    naming `events`, the bytes it needs and the most contacts that fit, before the run."""
    out = run_limited("""
        try:
            noslip.simulate(noslip.tables.sinai(0.5, 0.3), events=10**8, log=True)
        except noslip.InputError as e:
            print("refused:", e)
    """)
    assert out.returncode == 0, (out.returncode, out.stderr[-2000:])
    assert out.stdout.startswith("refused: events: 100000000 contacts with log=True"), out.stdout
    assert "beyond max_memory = 1073741824 bytes" in out.stdout, out.stdout


def test_by_default_a_long_run_keeps_no_records_and_runs_in_bounded_memory():
    """3 million contacts kept nothing but the summary and 2000 energy samples: before,
    the log and the boundary map were kept by default (2.8 GB: killed under 2 GiB). The
    peak resident memory is VmHWM (ru_maxrss keeps the forking parent's peak across exec)."""
    out = run_limited("""
        import re
        run = noslip.simulate(noslip.tables.sinai(0.5, 0.3), events=3_000_000)
        with open("/proc/self/status") as f:
            rss = re.search(r"VmHWM:\\s+(\\d+) kB", f.read()).group(1)
        print(run.summary["events"], len(run.events["time"]), len(run.boundary_map["time"]),
              len(run.energy["drift"]) <= 2001, rss)
    """)
    assert out.returncode == 0, (out.returncode, out.stderr[-2000:])
    events, logged, mapped, sampled, rss_kb = out.stdout.split()
    assert (events, logged, mapped, sampled) == ("3000000", "0", "0", "True")
    assert int(rss_kb) < 200_000, rss_kb


def test_a_run_to_a_time_stops_at_the_memory_cap_naming_time():
    """The number of contacts of a run to a time is not known up front: the run stops with
    an InputError when its records reach `max_memory`."""
    with pytest.raises(noslip.InputError, match=r"^time: the run to t = 1e12 with log=True "
                       r"reached max_memory = 1000000 bytes after 1658 contacts"):
        noslip.simulate(noslip.tables.sinai(0.5, 0.3), time=1e12, log=True,
                        max_memory=1_000_000)
    # Within the cap: the records are kept whole.
    run = noslip.simulate(noslip.tables.sinai(0.5, 0.3), events=1658, log=True,
                          boundary_map=True, max_memory=4_000_000)
    assert len(run.events["time"]) == 1658 and len(run.boundary_map["time"]) > 0


def test_the_cap_counts_the_records_asked_for(root):
    """603 bytes a contact for the 2D log, its share of the boundary map added when both are
    kept; the scene's own simulation.events is named as such."""
    scene = noslip.tables.sinai(0.5, 0.3)
    with pytest.raises(noslip.InputError, match=r"^events: 1001 contacts with log=True would "
                       r"keep up to 603603 bytes \(603 a contact in 2D\)"):
        noslip.simulate(scene, events=1001, log=True, max_memory=603_000)
    noslip.simulate(scene, events=1000, log=True, max_memory=603_000)
    with pytest.raises(noslip.InputError, match=r"with log=True and boundary_map=True"):
        noslip.simulate(scene, events=1000, log=True, boundary_map=True, max_memory=603_000)
    with pytest.raises(noslip.InputError, match=r"^events \(the scene's simulation.events\): "
                       r"100000 contacts"):
        noslip.simulate(noslip.Scene.from_file(root / "scenes" / "sinai.toml"), log=True,
                        max_memory=603_000)
    with pytest.raises(noslip.InputError, match=r"^max_memory: must be an integer"):
        noslip.simulate(scene, events=10, max_memory=-1)


@pytest.mark.parametrize("time", [1e-320, 5e-324, 2.2250738585072e-308])
def test_a_subnormal_time_is_refused_as_the_cli_refuses_it(time):
    """`noslip simulate --time 1e-320` is refused (a subnormal time has lost its
    precision); `simulate(time=1e-320)` ran. The same message, naming `time`."""
    with pytest.raises(noslip.InputError, match=r"^time: .* is not a normal f64 \(the least "
                       r"is 2.2250738585072014e-308\)$"):
        noslip.simulate(noslip.tables.sinai(0.5, 0.3), time=time)
    noslip.simulate(noslip.tables.sinai(0.5, 0.3), time=2.2250738585072014e-308)


#: A small driven 3D gas: 40 balls, a white-noise kick every 0.05 (docs/granular.md).
DRIVEN = {
    "dim": 3,
    "box": {"size": [8, 8, 8], "boundary": ["periodic"] * 3},
    "species": [{"mass": 1, "radius": "1/2", "count": 40}],
    "contact": {"balls": {"e": "0.9", "beta": "0.5"}},
    "random": {"seed": 2, "velocities": "maxwellian"},
    "thermostat": {"kind": "white-noise", "strength": "0.5", "interval": "0.05", "seed": 2},
}


def test_the_kicks_count_against_max_memory():
    """With ``log=True`` a kick's records count ``3 (8 n N_b + 24)`` bytes against
    ``max_memory`` (simulate's docstring), beside ``3 (57 + 56 n + 32 s)`` = 963 bytes a
    contact in 3D: a run whose contacts and kicks need exactly that many bytes runs within a
    cap of that many, and one byte less raises ``InputError`` naming ``max_memory``, the
    kicks and the bytes a kick. The records only grow, so the largest total is the run's
    last, whether the cap is asked after a contact or after a kick."""
    n, balls = 3, 40
    per_contact, per_kick = 3 * (57 + 56 * n + 32 * 3), 3 * (8 * n * balls + 24)
    assert (per_contact, per_kick) == (963, 2952)
    run = noslip.simulate(DRIVEN, time=2.0, log=True)
    contacts, kicks = len(run.events["time"]), len(run.events["kick"])
    assert kicks == run.summary["kicks"] == 40 and contacts == run.summary["events"] > 0
    need = contacts * per_contact + kicks * per_kick
    exact = noslip.simulate(DRIVEN, time=2.0, log=True, max_memory=need)
    for name in ("time", "post_velocity", "kick_velocities"):
        assert np.array_equal(exact.events[name], run.events[name]), name
    with pytest.raises(noslip.InputError, match=rf"^time: the run to t = 2e0 with log=True "
                       rf"reached max_memory = {need - 1} bytes after \d+ contacts and \d+ "
                       rf"kicks, at t = .* \(963 bytes a contact, 2952 a kick in 3D\)"):
        noslip.simulate(DRIVEN, time=2.0, log=True, max_memory=need - 1)
    # The contacts alone would fit: the kicks' bytes are what the cap saw.
    assert contacts * per_contact <= need - 1
    # Without the log nothing is kept per kick (nor per contact): any cap will do.
    assert noslip.simulate(DRIVEN, time=2.0, max_memory=1).summary["kicks"] == 40


def test_kicks_without_contacts_are_capped_too():
    """A lone ball has no contacts, only kicks (to the time limit): the cap is asked after
    each kick too, so 2000 kicks of ``3 (8 * 3 + 24)`` = 144 bytes do not fit in 100 kB (the
    run stops after 694 of them, the 695th passing it) and fit in 288 000 bytes."""
    lone = {**DRIVEN, "species": [{"mass": 1, "radius": "1/2", "count": 1}]}
    with pytest.raises(noslip.InputError, match=r"reached max_memory = 100000 bytes after 0 "
                       r"contacts and 694 kicks"):
        noslip.simulate(lone, time=100.0, log=True, max_memory=100_000)
    run = noslip.simulate(lone, time=100.0, log=True, max_memory=2000 * 144)
    assert run.summary["kicks"] == len(run.events["kick"]) == 2000
