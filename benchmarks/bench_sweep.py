"""8 independent model I runs on a 2-worker dask LocalCluster against the same 8 run serially
(target: >= 1.7x speed-up). Cluster start-up is timed apart and reported both ways.

    python -m benchmarks.bench_sweep [--duration S] [--smoke]
"""
import argparse
import tempfile
import time
from pathlib import Path

from compare.sweep import load_results, load_sweep, run_sweep


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--duration", type=float, default=6000.0, help="simulated seconds per run")
    ap.add_argument("--smoke", action="store_true")
    a = ap.parse_args(argv)
    dur = 30.0 if a.smoke else a.duration
    with tempfile.TemporaryDirectory() as d:
        d = Path(d)
        f = d / "b.toml"
        f.write_text(f'name = "bench"\ntarget = "model_I"\n[fixed]\nduration = {dur}\ndt_out = 1e-3\n'
                     "[grid]\nalpha = [0.5, 1.0]\nseed = [0, 1, 2, 3]\n")
        spec = load_sweep(f)
        # warm the JIT in this process first, so the serial timing holds no compilation or cache loading
        from reduced_models.spring_block import SpringBlockParams, simulate
        simulate(SpringBlockParams.reference(), 1.0, 1e-3, seed=0)
        t0 = time.perf_counter()
        run_sweep(spec, d / "serial", serial=True)
        serial = time.perf_counter() - t0
        from distributed import Client, LocalCluster

        t0 = time.perf_counter()
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
        # warm each worker's JIT the same way as this process (loading numba's cached kernels, ~1 s each)
        client.run(lambda: simulate(SpringBlockParams.reference(), 1.0, 1e-3, seed=0) and None)
        startup = time.perf_counter() - t0
        t0 = time.perf_counter()
        run_sweep(spec, d / "dask", scheduler=cluster.scheduler_address)
        par = time.perf_counter() - t0
        client.close()
        cluster.close()
        same = [r["C"] for r in load_results(d / "serial")] == [r["C"] for r in load_results(d / "dask")]
    print(f"8 model I runs of {dur:g} s: serial {serial:.1f} s; 2 workers {par:.1f} s + {startup:.1f} s cluster "
          "start-up and JIT warm-up (both sides warmed before timing)")
    print(f"speed-up {serial / par:.2f}x ({serial / (par + startup):.2f}x with start-up); results identical: {same}")


if __name__ == "__main__":
    main()
