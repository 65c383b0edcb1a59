#!/usr/bin/env python3
"""Our Python package beside the half-space peers, in Python, in one run: the peers' Hertz and
flat-punch cases (shared/peers/halfspace: E = 210 GPa, ν = 0.3, a 4 mm square on N × N cells,
load control, one thread) through tamaas's and ContactMechanics's Python APIs, as the peers'
harness calls them (its adapters are imported, so the cases are the same), and through
contopt's; each (tool, case, N) in a fresh process. It prints time, peak memory and the
errors against the closed forms, then our Python call against the same solve from Rust (the
`halfspace_peers` example, release): the overhead of the binding.

    PEERS_DIR=../shared/peers/halfspace CONTOPT_EXAMPLE=target/release/examples/halfspace_peers \\
        python crates/python/peers.py [SIZES, default 256,512] [--repeats K]

The interpreter needs contopt (built optimised: `pip install ./crates/python`) and the peers'
requirements (their README); a tool that cannot be imported is reported as unavailable.

    python crates/python/peers.py --overhead [SIZES, default 256,512] [REPEATS, default 21]

measures what the binding adds to a solve in one process (`overhead`), contopt and numpy alone.
"""

import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve()
PEERS_DIR = Path(os.environ.get("PEERS_DIR", HERE.parents[3] / "shared" / "peers" / "halfspace"))
TOOLS = ("contopt", "tamaas", "contactmechanics")
CASES = ("hertz", "punch")
# The tolerances of the peers' harness defaults, and ours as the Rust example sets it.
TOLERANCE = 1e-10


def peers():
    """The peers' harness as a module (its cases and adapters)."""
    sys.path.insert(0, str(PEERS_DIR))
    import numpy
    import run_peers

    run_peers.np = numpy  # the harness imports numpy in its main, once the threads are set
    return run_peers


def solve_contopt(case, n):
    """Our solve of `case` on n × n cells, timed as the Rust example times it: the indenter,
    the contact problem and the solve (the grid's kernel is the setup)."""
    import contopt

    rp = peers()
    ref = rp.analytic(case)
    h, heights, _ = rp.geometry(case, n)
    t0 = time.perf_counter()
    origin = -(n // 2) * h
    body = contopt.HalfSpace(
        nx=n, ny=n, dx_mm=h, dy_mm=h, e_mpa=rp.E, nu=rp.NU, origin_mm=(origin, origin)
    )
    gap = -heights.T  # the peers' arrays are indexed [x, y], ours [y, x]
    solver = contopt.Solver("polonsky_keer", tolerance=TOLERANCE)
    setup_s = time.perf_counter() - t0
    t0 = time.perf_counter()
    solution = solver.solve(contopt.Contact(body, gap, force_n=ref["F"]))
    pressure = solution.pressure_mpa
    solve_s = time.perf_counter() - t0
    # The call against the solve's own time in Rust, in the same run (the same load).
    t0 = time.perf_counter()
    again = solver.solve(contopt.Contact(body, gap, force_n=ref["F"]))
    again.pressure_mpa
    call_s = time.perf_counter() - t0
    return dict(
        call_s=call_s,
        rust_s=again.seconds,
        p=pressure.T,
        delta=solution.approach_mm,
        iterations=solution.iterations,
        solve_s=solve_s,
        setup_s=setup_s,
        converged=solution.converged,
        residual=solution.residuals["equilibrium"],
        settings=dict(tolerance=TOLERANCE, solver="polonsky_keer"),
    )


def one(tool, case, n, repeats):
    """One row, as the peers' harness makes it (its worker, with our adapter for contopt)."""
    rp = peers()

    class Args:
        tamaas_tol = TOLERANCE
        cm_rtol = TOLERANCE
        aspher_tol = TOLERANCE
        max_iter = 10_000
        max_repeats = repeats
        repeat_budget = 30.0

    if tool == "contopt":
        calls = []
        solve = solve_contopt

        def timed(case, n, tol, max_iter):
            out = solve(case, n)
            calls.append((out["call_s"], out["rust_s"]))
            return out

        rp.solve_aspher = timed
        rp.tool_version = lambda tool: __import__("contopt").__version__
        row = rp.worker("aspher", case, n, Args)
        row["tool"] = "contopt (Python)"
        row["call_s"], row["rust_s"] = min(calls)
        return row
    return rp.worker(tool, case, n, Args)


def rust_seconds(case, n, repeats):
    """The same solve from Rust: the fastest of `repeats` runs of the example."""
    example = os.environ.get("CONTOPT_EXAMPLE")
    if not example:
        return None
    best = None
    for _ in range(repeats):
        out = subprocess.run(
            [example, "--one", case, str(n)], capture_output=True, text=True, check=True
        )
        seconds = json.loads(out.stdout)["seconds"]
        best = seconds if best is None else min(best, seconds)
    return best


def overhead(sizes, repeats):
    """What the binding adds to a solve, measured in one process so that the machine's load
    falls on both alike: the call a user makes (`Solver.solve`, then reading the pressure and
    the gap as numpy) against `solve_in_rust`, the same solve of the same contact on this
    thread with nothing converted, the two interleaved (their order alternating) `repeats`
    times after one of each to warm up. Medians of the ratios: wall time (perf_counter), CPU
    time (process_time, every thread of the process), and the call's wall over its own solve's
    time inside Rust (`Solution.seconds`)."""
    import statistics

    import contopt

    rp = peers()
    print(
        "| case | N | Python call (s) | solve_in_rust (s) | wall over | CPU over "
        "| call over its solve in Rust |"
    )
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for case in CASES:
        for n in sizes:
            ref = rp.analytic(case)
            h, heights, _ = rp.geometry(case, n)
            origin = -(n // 2) * h
            body = contopt.HalfSpace(
                nx=n, ny=n, dx_mm=h, dy_mm=h, e_mpa=rp.E, nu=rp.NU, origin_mm=(origin, origin)
            )
            contact = contopt.Contact(body, -heights.T, force_n=ref["F"])
            solver = contopt.Solver("polonsky_keer", tolerance=TOLERANCE)

            def call():
                solution = solver.solve(contact)
                solution.pressure_mpa, solution.gap_mm
                return solution.seconds

            def timed(f):
                w, c = time.perf_counter(), time.process_time()
                inside = f()
                return time.perf_counter() - w, time.process_time() - c, inside

            call(), contopt.solve_in_rust(solver, contact)
            calls, rusts = [], []
            for k in range(repeats):
                if k % 2 == 0:
                    calls.append(timed(call))
                    rusts.append(timed(lambda: contopt.solve_in_rust(solver, contact)))
                else:
                    rusts.append(timed(lambda: contopt.solve_in_rust(solver, contact)))
                    calls.append(timed(call))
            med = statistics.median
            wall = med(c[0] / r[0] for c, r in zip(calls, rusts))
            cpu = med(c[1] / r[1] for c, r in zip(calls, rusts))
            inside = med(c[0] / c[2] for c in calls)
            print(
                f"| {case} | {n} | {med(c[0] for c in calls):.4f} | {med(r[0] for r in rusts):.4f} "
                f"| {100 * (wall - 1):+.1f} % | {100 * (cpu - 1):+.1f} % | {100 * (inside - 1):+.1f} % |",
                flush=True,
            )


def main():
    args = sys.argv[1:]
    if args[:1] == ["--overhead"]:
        sizes = [int(s) for s in (args[1] if len(args) > 1 else "256,512").split(",")]
        overhead(sizes, int(args[2]) if len(args) > 2 else 21)
        return
    if args[:1] == ["--one"]:
        tool, case, n, repeats = args[1], args[2], int(args[3]), int(args[4])
        try:
            row = one(tool, case, n, repeats)
            row["status"] = "ok"
        except ImportError as e:
            row = dict(tool=tool, case=case, N=n, status=f"unavailable ({e})")
        print(json.dumps(row))
        return
    repeats = 5
    if "--repeats" in args:
        k = args.index("--repeats")
        repeats = int(args[k + 1])
        del args[k : k + 2]
    sizes = [int(s) for s in (args[0] if args else "256,512").split(",")]
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
    rows = []
    for case in CASES:
        for n in sizes:
            for tool in TOOLS:
                out = subprocess.run(
                    [sys.executable, str(HERE), "--one", tool, case, str(n), str(repeats)],
                    capture_output=True,
                    text=True,
                    env=env,
                )
                if out.returncode != 0:
                    rows.append(dict(tool=tool, case=case, N=n, status="error: " + out.stderr[-300:]))
                    continue
                rows.append(json.loads(out.stdout.strip().splitlines()[-1]))
                print(f"{tool} {case} {n}: done", file=sys.stderr)
    print("| case | N | tool | time (s) | iterations | peak memory (MiB) | p error | radius error | approach error |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in rows:
        if r.get("status") != "ok":
            print(f"| {r['case']} | {r['N']} | {r['tool']} | {r['status']} | | | | | |")
            continue
        print(
            f"| {r['case']} | {r['N']} | {r['tool']} | {r['seconds']:.4f} | {r['iterations']} "
            f"| {r['max_rss_MiB']:.0f} | {r['rel_err_p0']:+.2e} | {r['rel_err_contact_radius']:+.2e} "
            f"| {r['rel_err_approach']:+.2e} |"
        )
    print()
    # The call holds the indenter, the contact problem and the solve, as the example times
    # them; "its solve" is the solve alone, measured inside the call.
    print("| case | N | Python call (s) | its solve alone (s) | the example from Rust (s) | call over the example |")
    print("| --- | --- | --- | --- | --- | --- |")
    for r in rows:
        if r.get("tool") != "contopt (Python)" or r.get("status") != "ok":
            continue
        rust = rust_seconds(r["case"], r["N"], repeats)
        example, over = ("(set CONTOPT_EXAMPLE)", "") if rust is None else (
            f"{rust:.4f}", f"{100 * (r['call_s'] / rust - 1):+.1f} %")
        print(f"| {r['case']} | {r['N']} | {r['call_s']:.4f} | {r['rust_s']:.4f} | {example} | {over} |")

if __name__ == "__main__":
    main()
