#!/usr/bin/env bash
# Sets up and builds snee, renders the default built-in scene and prints where the images are.
# Extra arguments go to `snee render` (e.g. --spp 16 --resolution 640x360).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh
log=$(mktemp)
trap 'rm -f "$log"' EXIT
build/apps/snee render builtin:default "$@" | tee "$log"
echo
sed -n 's/^wrote //p' "$log" | while read -r file; do
  echo "image: $(realpath -- "$file")"
done
