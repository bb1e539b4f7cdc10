#!/usr/bin/env bash
# The main job: what rockfit does for a user, on the bundled data. Called by `tools/bootstrap.sh run`.
set -euo pipefail
rockfit="${1:?usage: tools/main_job.sh PATH_TO_ROCKFIT}"
echo "== the block of the paper's Fig. 11 (m = 1 kg, b1 = 5 cm, b2 = 3 cm, h = 20 cm)"
"$rockfit" block --b1 0.05 --b2 0.03 --h 0.20 --mass 1
echo "== a facet impact of that block (unified map, no-spin rule (24)) falling about V1V2"
"$rockfit" impact facet --b1 0.05 --b2 0.03 --h 0.20 --mass 1 --pivot-edge 1,2 --omega-minus 0,1,0 --lambda-lat 0.3 --lambda-lon 0.8
echo "== then an edge impact: rocking about V4 until the edge V4V3 lands, base tilted 0.03 rad"
"$rockfit" impact edge --b1 0.05 --b2 0.03 --h 0.20 --mass 1 --pivot 4 --landing 3 --tilt 0.03 --omega-minus -0.4,0.6,0 --lambda 0.6
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
echo "== the bundled sample campaign: 16 synthetic x-IMU recordings of 4 granite blocks (data-samples/README.md)"
echo "== one trial, read as the x-IMU GUI wrote it (rate from its _Registers.csv)"
"$rockfit" inspect "$here/data-samples/recordings/block2-A-1"
