#!/usr/bin/env bash
# Install what is missing on a fresh Debian machine: OpenFOAM (the openfoam.com line, Debian package)
# and hydroderiv with its Python dependencies in a virtual environment at .venv/.
# Safe to run again: it only installs what is not there yet.
set -euo pipefail
cd "$(dirname "$0")/.."

as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

if ! command -v simpleFoam >/dev/null 2>&1; then
    echo "== installing OpenFOAM (apt package 'openfoam')"
    as_root apt-get update -q
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -q openfoam
fi

if [ ! -x .venv/bin/python ]; then
    echo "== creating the Python virtual environment .venv"
    python3 -m venv .venv
fi
echo "== installing hydroderiv and its dependencies into .venv"
.venv/bin/python -m pip install -q --upgrade pip
.venv/bin/python -m pip install -q -e '.[test]'
