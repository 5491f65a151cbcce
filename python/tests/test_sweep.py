"""noslip.sweep: on a 2-worker LocalCluster, with a worker killed mid-sweep, the result is
complete and identical to the serial one; a re-run with the same store computes nothing."""

import os
import signal
import threading
import time

import pandas as pd
import pytest

import noslip
from noslip.sweep import grid_points
from noslip.tables import sinai_collision_rate

GRID = {"gamma2": [0.0, 0.25, 0.5, 0.75, 1.0, 2 / 3], "radius": [0.1, 0.2, 0.25, 0.3]}
EVENTS = 20_000



@pytest.fixture(scope="module")
def serial():
    return noslip.sweep(sinai_collision_rate_20k, GRID, client="serial")


def sinai_collision_rate_20k(gamma2, radius):
    return sinai_collision_rate(gamma2, radius, events=EVENTS)


def test_grid_points_are_the_product_in_order():
    points = grid_points(GRID)
    assert len(points) == 24
    assert points[0] == {"gamma2": 0.0, "radius": 0.1}
    assert points[1] == {"gamma2": 0.0, "radius": 0.2}


def test_a_killed_worker_loses_nothing(serial, tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    store = tmp_path / "store"
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        pids = list(client.run(os.getpid).values())
        assert len(pids) == 2
        killed = []

        def kill_after_first_part():
            deadline = time.time() + 120
            while time.time() < deadline and not list(store.glob("part-*.parquet")):
                time.sleep(0.01)
            os.kill(pids[0], signal.SIGKILL)
            killed.append(len(list(store.glob("part-*.parquet"))))

        killer = threading.Thread(target=kill_after_first_part)
        killer.start()
        # sinai_collision_rate is importable on the workers (cloudpickle ships the test's
        # wrapper by reference to this module, which workers cannot import): use a partial.
        from functools import partial

        result = noslip.sweep(
            partial(sinai_collision_rate, events=EVENTS), GRID, client, store,
            points_per_task=1,
        )
        killer.join()
        alive = list(client.run(os.getpid).values())
    assert killed and killed[0] < 24, killed  # the kill came mid-sweep
    assert pids[0] not in alive
    assert len(result) == 24
    pd.testing.assert_frame_equal(result, serial, check_exact=True)
    assert len(list(store.glob("part-*.parquet"))) == 24


def test_a_rerun_with_the_store_computes_only_missing_points(serial, tmp_path):
    store = tmp_path / "store"
    calls = []

    def counted(gamma2, radius):
        calls.append((gamma2, radius))
        return sinai_collision_rate_20k(gamma2, radius)

    first = noslip.sweep(counted, {"gamma2": GRID["gamma2"][:3], "radius": GRID["radius"]},
                         client="serial", store=store, points_per_task=4)
    assert len(calls) == 12 and len(first) == 12
    calls.clear()
    full = noslip.sweep(counted, GRID, client="serial", store=store, points_per_task=4)
    assert len(calls) == 12
    calls.clear()
    again = noslip.sweep(counted, GRID, client="serial", store=store)
    assert calls == []
    pd.testing.assert_frame_equal(full, serial, check_exact=True)
    pd.testing.assert_frame_equal(again, serial, check_exact=True)


def test_results_are_physical(serial):
    """The map conserves energy: every run's drift is at rounding level."""
    assert (serial["energy_drift"].abs() < 1e-11).all()
    assert list(serial.columns) == ["gamma2", "radius", "collision_rate", "energy_drift"]
