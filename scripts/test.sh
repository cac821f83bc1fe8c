#!/usr/bin/env bash
# Sets up and builds snee, then runs the whole test suite; exits with ctest's status.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh
exec ctest --test-dir build --output-on-failure -j"$(nproc)"
