#!/bin/sh
# Times pylinkage's numba path on tmm's bench four-bar (four_bar.py), in a virtual
# environment of its own made in a temporary directory and removed afterwards.
# Usage: benches/pylinkage_numba/run.sh [N ...]   (needs python3 and access to PyPI)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
venv=$(mktemp -d "${TMPDIR:-/tmp}/tmm-pylinkage.XXXXXX")
trap 'rm -rf "$venv"' EXIT
python3 -m venv "$venv"
"$venv/bin/pip" install --quiet pylinkage numba
uptime
"$venv/bin/python" "$here/four_bar.py" "$@"
