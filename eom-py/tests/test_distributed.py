"""eom.distributed: the Dask sweep equals the local one bit for bit, whatever the chunking."""

import numpy as np
import pytest

import eom
import eom.distributed

distributed = pytest.importorskip("distributed")


def bicycle_points(n, seed=7):
    bike = eom.load("bicycle")
    rng = np.random.default_rng(seed)
    nominal = np.array(list(bike.parameters.values()))
    pts = nominal * (1.0 + 0.2 * (2.0 * rng.random((n, nominal.size)) - 1.0))
    return bike, pts


def assert_identical(a, b):
    # Bit for bit: the same bytes (NaN-free, so array_equal is bitwise).
    assert a.max_real.tobytes() == b.max_real.tobytes()
    assert np.array_equal(a.verdict, b.verdict)
    assert np.array_equal(a.fallback, b.fallback)


def test_without_a_client_it_is_local():
    bike, pts = bicycle_points(500)
    assert_identical(eom.distributed.stability(bike, pts), bike.stability(pts))


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as c:
        yield c


@pytest.mark.parametrize("chunk, direct", [(1_000, True), (2_345, False), (20_000, True)])
def test_dask_equals_local_bit_for_bit(client, chunk, direct):
    bike, pts = bicycle_points(6_000)
    local = bike.stability(pts)
    remote = eom.distributed.stability(bike, pts, client=client, chunk=chunk, direct=direct)
    assert_identical(remote, local)
    # Both verdicts occur: the points straddle the weave and capsize speeds.
    assert (local.verdict == 1).any() and (local.verdict == -1).any()


def test_dask_takes_a_dict_of_points(client):
    bike = eom.load("bicycle")
    v = np.linspace(0.5, 10.0, 3_001)
    assert_identical(
        eom.distributed.stability(bike, {"v": v}, client=client, chunk=500),
        bike.stability({"v": v}),
    )


def test_points_do_not_travel_in_the_task_graph(client):
    # Dask warns when a task graph is large ("Sending large graph"): the chunks are scattered
    # as data instead. With the threshold lowered to 200 kB, 6 000 points (1.2 MB) embedded
    # in the graph would warn; scattered, the graph holds keys only.
    import warnings

    import dask

    bike, pts = bicycle_points(6_000, seed=11)
    with dask.config.set({"distributed.admin.large-graph-warning-threshold": "200kB"}):
        with warnings.catch_warnings():
            warnings.filterwarnings("error", message=".*large graph.*")
            remote = eom.distributed.stability(bike, pts, client=client, chunk=1_500)
    assert_identical(remote, bike.stability(pts))


def test_workers_sharing_a_machine_share_its_cores(client):
    # Two one-thread workers on this machine: each sees 2 task slots on its host, so each
    # task evaluates on cores ÷ 2 threads (one on two cores), not on all of them.
    slots = eom.distributed._slots_per_host(client)
    assert len(slots) == 2 and set(slots.values()) == {2}
    threads = client.run(
        lambda dask_worker: eom.distributed._worker_threads(slots, dask_worker.address)
    )
    assert set(threads.values()) == {max(1, eom.distributed._cores() // 2)}
    # Any thread count gives the same result, bit for bit.
    bike, pts = bicycle_points(1_000, seed=5)
    local = bike.stability(pts)
    for threads in (1, 2):
        assert_identical(
            eom.distributed.stability(bike, pts, client=client, chunk=300, threads=threads),
            local,
        )
        assert_identical(bike.stability(pts, threads=threads), local)


def test_threads_must_be_positive():
    bike, pts = bicycle_points(10)
    for bad in (0, -1, 1.5, True):
        with pytest.raises(eom.EomError, match="threads"):
            bike.stability(pts, threads=bad)


def test_a_dask_array_is_evaluated_where_its_blocks_are(client):
    # Points that live on the cluster (a dask array, persisted there): each block of rows is
    # evaluated on the worker that holds it, equal to the local result bit for bit whatever
    # the blocks; several column blocks are joined into whole rows.
    da = pytest.importorskip("dask.array")
    bike, pts = bicycle_points(5_000, seed=13)
    local = bike.stability(pts)
    for rows, cols in ((1_000, -1), (1_234, 10), (5_000, -1)):
        arr = client.persist(da.from_array(pts, chunks=(rows, cols)))
        assert_identical(eom.distributed.stability(bike, arr, client=client), local)
    # Lazy (computed on the workers), with names for its columns; and without a client.
    lazy = da.linspace(0.5, 10.0, 2_001, chunks=700)[:, None]
    v = lazy.compute()[:, 0]
    assert_identical(
        eom.distributed.stability(bike, lazy, client=client, names=["v"]),
        bike.stability({"v": v}),
    )
    assert_identical(eom.distributed.stability(bike, lazy, names=["v"]), bike.stability({"v": v}))


def test_a_bad_dask_array_raises(client):
    da = pytest.importorskip("dask.array")
    bike = eom.load("bicycle")
    with pytest.raises(ValueError, match="points"):
        eom.distributed.stability(bike, da.zeros(10, chunks=5), client=client)
    with pytest.raises(eom.EomError, match="no parameter `nope`"):
        eom.distributed.stability(
            bike, da.zeros((10, 1), chunks=5), client=client, names=["nope"]
        )


def test_only_the_given_columns_travel_and_equal_local(client):
    # A dict or named columns: the workers fill in the defaults, as Model.points does locally.
    bike = eom.load("bicycle")
    rng = np.random.default_rng(3)
    cols = np.column_stack([np.linspace(0.5, 10.0, 2_500), 80.0 + 10.0 * rng.random(2_500)])
    names = ["v", "mB"]
    local = bike.stability(cols, names)
    assert_identical(
        eom.distributed.stability(bike, cols, client=client, chunk=700, names=names), local
    )
    assert_identical(
        eom.distributed.stability(bike, dict(zip(names, cols.T)), client=client, chunk=900),
        local,
    )
    with pytest.raises(eom.EomError, match="no parameter `nope`"):
        eom.distributed.stability(bike, {"nope": cols[:, 0]}, client=client)
    with pytest.raises(eom.EomError, match="points"):
        eom.distributed.stability(bike, {"v": cols[:, 0], "mB": cols[:10, 1]}, client=client)
