"""Datasets on more than one machine: the records of ``massprops batch``, computed on a Dask
``distributed`` cluster.

    >>> from dask.distributed import Client, LocalCluster
    >>> import massprops.dask
    >>> client = Client(LocalCluster(n_workers=4))           # or Client("scheduler:8786")
    >>> records = massprops.dask.map_files(paths, client=client, unit="mm", timeout=300)
    >>> df = massprops.dask.to_dataframe(records)

Each task's files are computed in a child process of its worker, and a file that crashes or hangs
it is computed again alone in a child of its own (as the command isolates files), so such a file
becomes a ``crashed`` or ``timeout`` record instead of killing the worker; a worker that dies anyway (killed, out of memory) has its tasks run again elsewhere by
Dask. Records come back in the order of the sorted paths, each exactly once, equal to the lines
``massprops batch`` writes for the same paths and options.
"""

import json

from . import _core


def _apply(fn, args):
    return fn(*args)


def map_tasks(fn, items, client=None, retries=3, **submit_options):
    """fn(*item) for every item, on the cluster; results in the order of `items`. Tasks are
    marked impure (each runs, none is taken from a cache) and retried on another worker when
    theirs dies. The generic runner under map_files, for other jobs (simulations, ...)."""
    from distributed import get_client

    client = client or get_client()
    futures = client.map(_apply, [fn] * len(items), list(items), pure=False, retries=retries, **submit_options)
    return client.gather(futures)


def _records(paths, indices, of, timeout, options):
    return [json.loads(line) for line in _core.batch_records(paths, indices, of, timeout, **options)]


def map_files(paths, client=None, timeout=600.0, files_per_task=16, **options):
    """The batch records of `paths` (sorted, duplicates dropped), computed on the cluster, in
    tasks of `files_per_task` files (Dask's overhead per task is milliseconds; a file of 10⁴
    triangles takes about one). `options` are the keywords of massprops.load (unit, density,
    repair, ...)."""
    files = sorted({str(p) for p in paths})
    step = max(1, int(files_per_task))
    items = [(files[i:i + step], list(range(i, min(i + step, len(files)))), len(files), float(timeout), options)
             for i in range(0, len(files), step)]
    return [record for chunk in map_tasks(_records, items, client=client) for record in chunk]


def to_dataframe(records):
    """A pandas DataFrame of records: file, status, message, and the main numbers of each result."""
    import pandas as pd

    rows = []
    for r in records:
        row = {"file": r["file"], "status": r["status"], "message": r.get("message")}
        res = r.get("result")
        if res is not None:
            row.update({k: res[k] for k in ("unit", "volume", "mass", "density", "surface_area")})
            row.update({f"com_{a}": c for a, c in zip("xyz", res["center_of_mass"])})
            row.update({f"i{k + 1}": m for k, m in enumerate(res["principal_moments"])})
            row["warnings"] = "; ".join(res["warnings"])
        rows.append(row)
    return pd.DataFrame(rows)
