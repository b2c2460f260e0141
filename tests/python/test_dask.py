"""massprops.dask on a real distributed.LocalCluster of 2 worker processes: the records equal the
single-process `massprops batch` output exactly, also when a file crashes its reader, another
hangs, and a worker process is killed with SIGKILL in the middle of the run.
"""
import json
import os
import shutil
import signal
import subprocess
import threading
import time

import pytest

DATA = os.environ.get("MASSPROPS_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))
CLI = os.environ.get("MASSPROPS_CLI", "massprops")
FAULTS = "crash:crashme,hang:hangme"  # injected into the child computing a matching file
# The library that injects them (tests/fault/batch_fault.cpp), preloaded: ctest names it.
FAULT_LIBRARY = os.environ.get("MASSPROPS_BATCH_FAULT_LIBRARY", "")


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    root = tmp_path_factory.mktemp("dataset")
    meshes = os.path.join(DATA, "meshes")
    names = ["t_handle.obj", "Moon.stl", "spot.obj", "HalfDonut_binary.stl", "ellipe0.003.off",
             "cube_cup_quad.obj", "box_0.1x0.2x0.3.gltf"]
    for k in range(3):  # 21 good or refused files, in three folders
        (root / f"set{k}").mkdir()
        for n in names:
            shutil.copy(os.path.join(meshes, n), root / f"set{k}" / n)
    (root / "set0" / "malformed.obj").write_text("v 0 0 0\nf 1 2 3\n")
    shutil.copy(os.path.join(meshes, "t_handle.obj"), root / "set1" / "crashme.obj")
    shutil.copy(os.path.join(meshes, "t_handle.obj"), root / "set2" / "hangme.obj")
    return root


def batch_records(root, manifest):
    assert os.path.exists(FAULT_LIBRARY), "MASSPROPS_BATCH_FAULT_LIBRARY (set by ctest) names no library"
    out = root / "batch.jsonl"
    if out.exists():
        out.unlink()
    env = dict(os.environ, MASSPROPS_BATCH_FAULT=FAULTS, LD_PRELOAD=FAULT_LIBRARY)
    subprocess.run([CLI, "batch", str(manifest), "-o", str(out), "--timeout", "1", "-q"], check=True, env=env)
    return [json.loads(line) for line in out.read_text().splitlines()]


def test_a_local_cluster_gives_the_batch_records_even_when_a_worker_is_killed(dataset, monkeypatch):
    import distributed  # Debian's python3-distributed, installed by scripts/install_deps.sh

    import massprops.dask

    paths = sorted(str(p) for p in dataset.rglob("*") if p.is_file())
    manifest = dataset / "manifest.txt"
    manifest.write_text("\n".join(paths) + "\n")
    expected = batch_records(dataset, manifest)
    statuses = {r["file"].rsplit("/", 1)[1]: r["status"] for r in expected}
    assert statuses["crashme.obj"] == "crashed" and statuses["malformed.obj"] == "error"
    assert statuses["hangme.obj"] == "timeout"
    assert statuses["ellipe0.003.off"] == "refused"

    # Worker processes inherit the fault injection from this environment (the library preloaded into
    # each new worker process).
    monkeypatch.setenv("MASSPROPS_BATCH_FAULT", FAULTS)
    monkeypatch.setenv("LD_PRELOAD", FAULT_LIBRARY)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=50) as cluster, distributed.Client(cluster) as client:
        pids = list(client.run(os.getpid).values())
        assert len(pids) == 2

        def kill_one():
            time.sleep(0.5)
            os.kill(pids[0], signal.SIGKILL)

        killer = threading.Thread(target=kill_one)
        killer.start()
        t0 = time.perf_counter()
        records = massprops.dask.map_files(paths, client=client, timeout=1)
        assert time.perf_counter() - t0 > 0.6  # the kill came in the middle of the run
        killer.join()
        # The killed worker was replaced (the nanny restarts it), and nothing was lost or repeated.
        assert pids[0] not in client.run(os.getpid).values()

    assert [r["file"] for r in records] == [r["file"] for r in expected]
    assert records == expected
    df = massprops.dask.to_dataframe(records)
    assert (df["status"] == "ok").sum() == sum(r["status"] == "ok" for r in expected)
