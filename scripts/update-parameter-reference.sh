#!/usr/bin/env bash
# Regenerates doc/parameters.prm, the parameter reference, from the program
# itself (every entry with its default and documentation). The ctest
# cli.parameter_reference_is_current fails when this file is stale.
# Usage: scripts/update-parameter-reference.sh [path/to/pantocat-fem]
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-build/pantocat-fem}
"$exe" --print-parameters prm > doc/parameters.prm
echo "wrote doc/parameters.prm"
