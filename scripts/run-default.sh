#!/usr/bin/env bash
# README command 1: install what is missing, build, and run the default hybrid simulation:
# configs/three-story.yaml (3-story shear building, El Centro 1940, one virtual BRFD in its
# own brfd-substructure process over LCM, inside a private network namespace).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
./build/bin/hybridsim run --config configs/three-story.yaml "$@"
