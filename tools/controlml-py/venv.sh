#!/usr/bin/env bash
# Prints the python of controlml.py's venv (tools/controlml-py/target/venv), creating it first when it is missing
# or was made from another requirements.txt. Output of pip goes to stderr; stdout is only the path.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
venv=$here/target/venv
if [ ! -x "$venv/bin/python" ] || ! cmp -s "$here/requirements.txt" "$venv/requirements.txt"; then
    echo "[sabot] installing controlml.py's Python packages (requirements.txt) into $venv" >&2
    rm -rf "$venv"
    python3 -m venv "$venv" >&2 || { echo "[sabot] error: python3 -m venv failed (apt-get install -y python3-venv)" >&2; exit 1; }
    "$venv/bin/pip" install --quiet --disable-pip-version-check -r "$here/requirements.txt" >&2 \
        || { rm -rf "$venv"; echo "[sabot] error: pip install -r $here/requirements.txt failed" >&2; exit 1; }
    cp "$here/requirements.txt" "$venv/requirements.txt"
fi
echo "$venv/bin/python"
