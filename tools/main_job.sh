#!/usr/bin/env bash
# The main job: analyse the bundled sample campaign as an experimenter would. Called by
# `tools/bootstrap.sh run`; writes its outputs (HDF5, PNG, HTML) to OUT_DIR (default build/results).
set -euo pipefail
rockfit="${1:?usage: tools/main_job.sh PATH_TO_ROCKFIT [OUT_DIR]}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${2:-$here/build/results}"
manifest="$here/data-samples/manifest.toml"
mkdir -p "$out"

echo "== 1. one trial of the bundled campaign, read as the x-IMU GUI wrote it (rate from its _Registers.csv)"
"$rockfit" inspect "$here/data-samples/recordings/block2-A-1"

echo
echo "== 2. drift correction, OPMF and AVRF of every trial, per block and position (paper Sect. 3, Fig. 6)"
"$rockfit" summary "$manifest" -o "$out/campaign.h5"

echo
echo "== 3. figures: Euler angles raw vs corrected (Fig. 5) and the campaign summary (Fig. 6)"
"$rockfit" plot euler "$out/campaign.h5" --trial block2-A-1 -o "$out/euler_block2-A-1.png"
"$rockfit" plot summary "$out/campaign.h5" -o "$out/summary.png"

echo
echo "== 4. fit t0, α, λ, λ_lat, λ_lon of one trial with no starting point (error (28)); truth: recordings/block2-A-1_truth.json"
"$rockfit" fit "$manifest" --trial block2-A-1 -o "$out/fits.h5" --plot "$out/fit_block2-A-1.png"

echo
echo "== 5. the whole campaign in parallel (resumable), then its fitted parameters per block and position (Fig. 15)"
"$rockfit" batch "$manifest" -o "$out/fits.h5" --resume
"$rockfit" plot parameters "$out/fits.h5" -o "$out/parameters.png"

echo
echo "== 6. earthquake response of block2 in position A with its fitted λ, λ_lat, λ_lon (mean of its fits),"
echo "      under a generated Clough–Penzien record at 30° to the block's x axis"
"$rockfit" respond --manifest "$manifest" --block block2 --fits "$out/fits.h5" --group block2,A \
  --record "$here/data-samples/ground-motions/cp-seed2-0.45g.AT2" --angle 30 --format hdf5 -o "$out/response_block2-A.h5"
"$rockfit" plot response "$out/response_block2-A.h5" -o "$out/response_block2-A.png"

echo
echo "== 7. one HTML page of the campaign to share (opens offline; figures need gnuplot): overview, every trial, provenance"
"$rockfit" report "$out/campaign.h5" --fits "$out/fits.h5" --response "$out/response_block2-A.h5" \
  --title "Sample campaign" -o "$out/report.html"

echo
echo "outputs in $out:"
ls -1 "$out"
