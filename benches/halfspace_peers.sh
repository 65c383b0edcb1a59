#!/usr/bin/env bash
# Our Polonsky–Keer solver beside the public half-space peers, in one run, on the same cases
# and grids: the peers' harness (shared/peers/halfspace/run_peers.py: tamaas,
# ContactMechanics, ASPHER; run through benches/peers_cpu.py, which adds each solve's CPU
# time) and our `halfspace_peers` example, one thread each, then one table joining both JSON
# documents: per case and grid, each tool's wall and CPU time, steps and peak memory, our steps
# per grid level and our CPU time in padded FFT pairs (one pair's CPU time, in the same
# process), and ASPHER's times over ours.
#
#   PEERS_PYTHON=/path/to/venv/bin/python bash benches/halfspace_peers.sh [SIZES] [OUT]
#
# SIZES defaults to 256,512,1024 and OUT to target/halfspace_peers. The peers' venv is set up
# as their README says (requirements.txt, and requirements-aspher.txt for ASPHER). PEERS_TOOLS
# (e.g. aspher) runs some of the peers only, PEERS_TIMEOUT and PEERS_BUDGET (s) pass the
# harness's --timeout (one run) and --budget (no larger grid after a slower run): 4096² takes
# ASPHER minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
sizes=${1:-256,512,1024}
out=${2:-target/halfspace_peers}
peers=${PEERS_DIR:-../shared/peers/halfspace}
python=${PEERS_PYTHON:-python3}
mkdir -p "$out"
cargo build --release --quiet --example halfspace_peers
# OMP_WAIT_POLICY=passive: ASPHER's OpenMP threads otherwise spin against other jobs.
OMP_WAIT_POLICY=passive PEERS_DIR="$peers" "$python" benches/peers_cpu.py --sizes "$sizes" --threads 1 \
    ${PEERS_TOOLS:+--tools "$PEERS_TOOLS"} --timeout "${PEERS_TIMEOUT:-240}" \
    --budget "${PEERS_BUDGET:-60}" --out "$out/peers.json" >/dev/null
"${CARGO_TARGET_DIR:-target}/release/examples/halfspace_peers" ${sizes//,/ } >"$out/contopt.json"
"$python" - "$out/peers.json" "$out/contopt.json" <<'PY' | tee "$out/table.md"
import json, sys
rows = json.load(open(sys.argv[1]))["rows"] + json.load(open(sys.argv[2]))["rows"]
rows = [r for r in rows if r.get("status") == "ok"]
tools = ["contopt"] + sorted({r["tool"] for r in rows} - {"contopt"})
by = {(r["tool"], r["case"], r["N"]): r for r in rows}
head = ["case", "N"]
for t in tools:
    head += [f"{t} time (CPU) s", f"{t} steps", f"{t} MiB"]
head += ["our steps per grid", "our FFT pairs", "p error", "contact-radius error"]
if "aspher" in tools:
    head += ["ASPHER / ours (CPU)", "memory ours / ASPHER"]
print("| " + " | ".join(head) + " |")
print("|" + " --- |" * len(head))
for case, n in sorted({(r["case"], r["N"]) for r in rows}):
    ours = by.get(("contopt", case, n))
    cells = [case, str(n)]
    for t in tools:
        r = by.get((t, case, n))
        cells += [f"{r['seconds']:.3f} ({r.get('cpu_seconds', float('nan')):.3f})", str(r["iterations"]),
                  f"{r.get('max_rss_MiB', float('nan')):.0f}"] if r else ["—"] * 3
    if ours:
        levels = " + ".join(str(k) for k in ours["steps_per_level"] if k) or "0"
        cells += [levels, f"{ours['cpu_seconds'] / ours['fft_pair_cpu_s']:.0f}",
                  f"{ours['rel_err_p0']:.3e}", f"{ours['rel_err_contact_radius']:.3e}"]
    else:
        cells += ["—"] * 4
    a = by.get(("aspher", case, n))
    if "aspher" in tools:
        cells += [f"{a['seconds'] / ours['seconds']:.1f} ({a['cpu_seconds'] / ours['cpu_seconds']:.1f})",
                  f"{ours['max_rss_MiB'] / a['max_rss_MiB']:.2f}"] if a and ours else ["—"] * 2
    print("| " + " | ".join(cells) + " |")
PY
