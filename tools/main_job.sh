#!/usr/bin/env bash
# The main job: what rockfit does for a user, on the bundled data. Called by `tools/bootstrap.sh run`.
set -euo pipefail
rockfit="${1:?usage: tools/main_job.sh PATH_TO_ROCKFIT}"
echo "== the block of the paper's Fig. 11 (m = 1 kg, b1 = 5 cm, b2 = 3 cm, h = 20 cm)"
"$rockfit" block --b1 0.05 --b2 0.03 --h 0.20 --mass 1
