"""Sweeps on a Dask cluster: the same sweep as :func:`whatnext.sweep`, run in chunks on the workers.

Use it through ``whatnext.sweep(machine, values, client=client)``, with a
``dask.distributed.Client`` (Debian's ``python3-distributed``)::

    from dask.distributed import Client, LocalCluster
    import whatnext

    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        s = whatnext.sweep(whatnext.example(2), {"geometry.rope_length": whatnext.grid(0.62, 1.0, 400),
                                                 "masses.sandbag": whatnext.grid(0.2, 2.0, 300)},
                           client=client, progress=True)
    s.to_csv("sweep.csv")        # the same bytes as the same sweep run locally, or by `whatnext sweep`

The sweep is cut into chunks of consecutive machines. Each chunk is one Dask task: it carries the
machine (its input values, a few kB), the values per key (a grid) or its own rows of a Latin
hypercube, runs its machines in C++ on the worker with the GIL released, and sends back their
columns (about 200 bytes per machine). Each machine's row depends only on the machine, never on
where or with what it ran, so the result equals the local sweep's to the last bit. A chunk lost
with its worker is run again by Dask on another worker; one that raises is retried twice. The
workers must be able to ``import whatnext``: the same build of the module on every machine of the
cluster (PYTHONPATH), as docs/explore.md says.
"""

import math
import sys
from typing import Any, Callable, Dict, List, Optional, Tuple, Union

import numpy as np

from . import Sweep, _Plan, _whole

__all__ = ["run", "chunk_size", "run_chunks", "settings"]


def _run_chunk(plan: _Plan, start: int, stop: int, threads: int) -> Dict[str, np.ndarray]:
    """One task: machines start..stop-1, on the worker; their columns go back to the client."""
    return plan.run(start, stop, threads)


def chunk_size(machines: int, worker_threads: int) -> int:
    """The default chunk: about eight chunks per worker thread (so that a slow chunk or a lost
    worker delays the end by little), at least 2,000 machines (a task's own cost, a few milliseconds,
    stays below a tenth of its run) and at most 50,000 (about 10 MB of results per task)."""
    return int(min(50_000, max(2_000, math.ceil(machines / (8 * max(1, worker_threads))))))


def settings(client: Any, machines: int, chunk: Optional[int], threads: Optional[int]) -> Tuple[int, int]:
    """The machines per chunk (``chunk=``, else :func:`chunk_size` for the client's cluster) and the
    threads per chunk (``threads=``, else one: every worker thread runs a chunk of its own)."""
    worker_threads = sum(client.nthreads().values())
    size = chunk_size(machines, worker_threads) if chunk is None else _whole("sweep: chunk", chunk, 1, machines)
    per_chunk = 1 if threads is None else _whole("sweep: threads", threads, 1, 4096)
    return size, per_chunk


def run_chunks(client: Any, task: Callable[..., Any], chunks: List[Tuple[int, int]],
               arguments: Callable[[int, int], Tuple[Any, ...]], total: int,
               progress: Union[bool, Callable[[int, int], None]] = False, done: int = 0) -> List[Any]:
    """Runs ``task(*arguments(a, b))`` on the cluster for each chunk of machines [a, b), a chunk that
    raises retried twice; reports ``done`` machines of ``total`` as chunks finish, releases each
    result as it comes, and returns the results in the chunks' order. Any exception (Ctrl-C, a
    chunk that failed for good) cancels the chunks still to run before it is raised."""
    from distributed import as_completed  # only here: Dask is needed only for sweeps on a cluster

    futures = [client.submit(task, *arguments(a, b), pure=False, retries=2) for a, b in chunks]
    where = {f.key: i for i, f in enumerate(futures)}
    results: List[Any] = [None] * len(chunks)
    report = _reporter(progress)
    try:
        for future, result in as_completed(futures, with_results=True):
            i = where[future.key]
            results[i] = result
            done += chunks[i][1] - chunks[i][0]
            report(done, total)
            future.release()
    except BaseException:
        client.cancel(futures)
        raise
    return results


def run(plan: _Plan, client: Any, *, chunk: Optional[int] = None, threads: Optional[int] = None,
        progress: Union[bool, Callable[[int, int], None]] = False) -> Sweep:
    """Runs a checked sweep (whatnext.sweep's plan) on the client's cluster; see the module's help."""
    n = plan.size
    size, per_chunk = settings(client, n, chunk, threads)
    bounds = [(a, min(n, a + size)) for a in range(0, n, size)]
    parts: List[Dict[str, np.ndarray]] = run_chunks(
        client, _run_chunk, bounds, lambda a, b: (plan.part(a, b), a, b, per_chunk), n, progress)
    names = list(parts[0]) if parts else []
    columns = {name: np.concatenate([p[name] for p in parts]) for name in names}
    return Sweep(plan.keys, columns, plan.axes, plan.info())


def _reporter(progress: Union[bool, Callable[[int, int], None]]) -> Callable[[int, int], None]:
    if callable(progress):
        return progress
    if not progress:
        return lambda done, total: None

    def show(done: int, total: int) -> None:
        end = "\n" if done == total else ""
        print(f"\rsweep: {done} of {total} machines ({100 * done / total:.0f} %)", end=end, file=sys.stderr,
              flush=True)
    return show
