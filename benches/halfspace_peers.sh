#!/usr/bin/env bash
# Our Polonsky–Keer solver beside the public half-space peers, in one run, on the same cases
# and grids: the peers' harness (shared/peers/halfspace/run_peers.py: tamaas,
# ContactMechanics, ASPHER) and our `halfspace_peers` example, one thread each, then one
# table joining both JSON documents.
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
OMP_WAIT_POLICY=passive "$python" "$peers/run_peers.py" --sizes "$sizes" --threads 1 \
    ${PEERS_TOOLS:+--tools "$PEERS_TOOLS"} --timeout "${PEERS_TIMEOUT:-240}" \
    --budget "${PEERS_BUDGET:-60}" --out "$out/peers.json" >/dev/null
./target/release/examples/halfspace_peers ${sizes//,/ } >"$out/contopt.json"
"$python" - "$out/peers.json" "$out/contopt.json" <<'PY' | tee "$out/table.md"
import json, sys
rows = json.load(open(sys.argv[1]))["rows"] + json.load(open(sys.argv[2]))["rows"]
rows = [r for r in rows if r.get("status") == "ok"]
rows.sort(key=lambda r: (r["case"], r["N"], r["seconds"]))
print("| case | N | tool | time (s) | iterations | p error | contact-radius error | peak memory (MiB) |")
print("| --- | --- | --- | --- | --- | --- | --- | --- |")
for r in rows:
    print(f"| {r['case']} | {r['N']} | {r['tool']} | {r['seconds']:.3f} | {r['iterations']} "
          f"| {r['rel_err_p0']:.2e} | {r['rel_err_contact_radius']:.2e} | {r.get('max_rss_MiB', float('nan')):.0f} |")
PY
