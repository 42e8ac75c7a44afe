#!/usr/bin/env bash
# Side by side: tmm's path synthesis and pylinkage's particle swarm on the same target (24
# points of a crank-rocker's coupler curve). Creates its own virtual environment in a
# temporary directory (pip install pylinkage; needs PyPI), builds the Rust side in release,
# and prints the time and the error of each, with the machine's load. Usage:
#   benches/pylinkage/run.sh [PSO_ITERATIONS]   (default 200)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
cd "$here/../.."
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
python3 -m venv "$work/venv"
"$work/venv/bin/pip" install -q pylinkage
iterations="${1:-200}"
cargo build --release -q -p tmm-bench --example pylinkage_target
echo "load: $(uptime)"
# The target (and tmm's time to its own tolerance, 1e-9 of the path's size).
target/release/examples/pylinkage_target "$work/target.json"
pyl=$("$work/venv/bin/python" "$here/compare.py" "$work/target.json" "$iterations")
echo "$pyl"
# tmm again, stopping as soon as it is as good as pylinkage's best.
miss=$(echo "$pyl" | sed -n 's/.*mean miss \([0-9.e+-]*\) m.*/\1/p')
echo "tmm to pylinkage's error ($miss m):"
target/release/examples/pylinkage_target "$work/target2.json" "$miss" | tail -1
echo "load: $(uptime)"
