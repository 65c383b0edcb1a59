"""The peers' harness (shared/peers/halfspace/run_peers.py) with each solve's CPU time beside
its wall time: on a machine shared with other jobs, the CPU time of a single-threaded solve is
the figure that other jobs disturb least.

    PEERS_DIR=shared/peers/halfspace python benches/peers_cpu.py [run_peers.py's arguments]

Every harness solve function reads time.perf_counter() four times (setup start and end, solve
start and end); a clock in its place reads the process's CPU time at each, so the solve's CPU
time is that between the third and fourth reads. Each row gains `cpu_seconds`: the CPU time
of the solve whose wall time the row reports (the fastest of its repeats). The workers the
harness spawns run this file, not the harness (PEERS_DIR is in their environment), so that
they are measured the same way.
"""

import os
import sys
import time

sys.path.insert(0, os.path.abspath(os.environ["PEERS_DIR"]))
import run_peers  # noqa: E402


class _Clock:
    """time's functions, with perf_counter also noting the process's CPU time at each read."""

    def __init__(self):
        self.cpu = []

    def __getattr__(self, name):
        return getattr(time, name)

    def perf_counter(self):
        self.cpu.append(time.process_time())
        return time.perf_counter()


clock = _Clock()
run_peers.time = clock
solves = []


def _measured(solve):
    def wrapped(*args, **kwargs):
        clock.cpu.clear()
        out = solve(*args, **kwargs)
        solves.append((out["solve_s"], clock.cpu[3] - clock.cpu[2]))
        return out

    return wrapped


for name in ("solve_tamaas", "solve_contactmechanics", "solve_aspher"):
    setattr(run_peers, name, _measured(getattr(run_peers, name)))
_worker = run_peers.worker


def worker(*args, **kwargs):
    solves.clear()
    row = _worker(*args, **kwargs)
    row["cpu_seconds"] = round(min(solves)[1], 6)
    return row


run_peers.worker = worker
run_peers.__file__ = os.path.abspath(__file__)
run_peers.main()
