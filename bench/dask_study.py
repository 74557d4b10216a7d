"""Studies written into Zarr by Dask workers: machines per second and the cost of one chunk.

    PYTHONPATH=build/python /usr/bin/python3 bench/dask_study.py [--machines 200000] [--workers 2]

Runs example 2's grid over rope length and sandbag mass three ways on this computer: the local
sweep on all threads (``whatnext.sweep``), the study in a Zarr store with large chunks, and with
small chunks. The difference between the two stores' times per chunk is a chunk's own cost (the
task, the write of its Zarr chunks, its marker); docs/explore.md turns these into the arithmetic
for a study of 10^9 machines.
"""

import argparse
import logging
import math
import os
import shutil
import tempfile
import time

import whatnext


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--machines", type=int, default=200_000)
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args()
    from distributed import Client, LocalCluster

    side = int(math.sqrt(args.machines))
    values = {"geometry.rope_length": whatnext.grid(0.62, 1.0, side), "masses.sandbag": whatnext.grid(0.2, 2.0, side)}
    m = whatnext.example(2)
    n = side * side
    t = time.perf_counter()
    whatnext.sweep(m, values)
    local = time.perf_counter() - t
    print(f"{n} machines, {os.cpu_count()} cores, load {os.getloadavg()[0]:.2f}")
    print(f"local sweep, all threads:      {local:7.2f} s  {n / local:9.0f} machines/s")
    work = tempfile.mkdtemp()
    try:
        with LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None,
                          silence_logs=logging.CRITICAL) as cluster, Client(cluster) as client:
            times = {}
            for chunk in (max(1, n // 8), max(1, n // 200)):
                store = os.path.join(work, f"{chunk}.zarr")
                t = time.perf_counter()
                ds = whatnext.sweep(m, values, client=client, store=store, chunk=chunk)
                times[chunk] = (time.perf_counter() - t, len(os.listdir(os.path.join(store, ".whatnext-done"))))
                size = sum(os.path.getsize(os.path.join(d, f)) for d, _, fs in os.walk(store) for f in fs)
                elapsed, chunks = times[chunk]
                print(f"store, {chunks:4d} chunks of ~{chunk:6d}: {elapsed:7.2f} s  {n / elapsed:9.0f} machines/s  "
                      f"store {size / n:.1f} bytes/machine")
                del ds
            (t_big, c_big), (t_small, c_small) = times.values()
            print(f"one chunk's own cost: {(t_small - t_big) / (c_small - c_big) * 1e3:.1f} ms "
                  f"(spread over {args.workers} workers: per worker-chunk "
                  f"{(t_small - t_big) / (c_small - c_big) * args.workers * 1e3:.1f} ms)")
    finally:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
