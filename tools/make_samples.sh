#!/usr/bin/env bash
# Regenerates the bundled sample campaign data-samples/ bit for bit with `rockfit synth`.
#
#   tools/make_samples.sh [ROCKFIT] [OUTDIR] [TRIAL_ID ...]
#
# ROCKFIT  the rockfit program (default: build/tools/rockfit beside this script's checkout)
# OUTDIR   where to write (default: data-samples/); recordings go to OUTDIR/recordings/, the manifest (always
#          of the whole campaign) to OUTDIR/manifest.toml
# TRIAL_ID make only these trials (used by the regeneration test)
# --print  as the first argument: print the synth commands instead of running them
#
# Every number of every trial is in the table below; nothing else influences the files. The commands run
# inside OUTDIR with relative paths, so the truth files do not depend on where the campaign is written.
# Check a regeneration with:  tools/make_samples.sh build/tools/rockfit /tmp/samples && diff -r /tmp/samples data-samples
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
print_only=0
if [ "${1:-}" = "--print" ]; then
  print_only=1
  shift
fi
rockfit="${1:-$here/build/tools/rockfit}"
out="${2:-$here/data-samples}"
shift $(( $# > 2 ? 2 : $# ))
selected=("$@")
if [ "$print_only" -eq 0 ]; then
  [ -x "$rockfit" ] || { echo "make_samples.sh: no rockfit program at $rockfit; build first (see README.md)" >&2; exit 1; }
  rockfit="$(cd "$(dirname "$rockfit")" && pwd)/$(basename "$rockfit")"
  mkdir -p "$out/recordings"
  out="$(cd "$out" && pwd)"
fi

# Granite blocks as in the paper's Sect. 3.1: density 2692 kg/m³, the same h and b1 (b1/h = tan 0.245), b2 varies.
H=0.2
B1=0.05000453   # 0.2·tan(0.245) to 7 significant digits
RHO=2692

# Parameters vary between trials as the paper's Fig. 15 shows: α in (0.17, 0.24) rad, λ 0.5–2.5,
# λ_lat in (−5, 5) (far beyond the bound (27)), λ_lon in (0, 1.5) (often above 1, beyond (25)); trials in one
# position are alike, positions A and B differ. Position B is the block turned over with the IMU remounted on
# the new top face, rotated by 180° about the vertical (mounting -x,-y,z).
# Measurement: gyro noise σ [deg/s], bias X,Y,Z [deg/s], ringing gain / frequency [Hz] / decay time [s],
# drift slope and random walk of roll,pitch,yaw [deg/s, deg/√s], device clock at start-up [s after 2000-01-01],
# quaternion (Euler) rate [Hz]. block3-B-1 has the large drift of the paper's Fig. 5e; block2-A-1 has the
# parameters the paper fitted in its Fig. 14 (t0 = 2.33 s, α = 0.197, λ = 2.185, λ_lat = −2.032, λ_lon = 0.197).
#
# id       block  b2    pos alpha lambda lat    lon   t0   dur  seed noise bias             gain f  T     slope           walk             rtc   qrate
table=$(cat <<'TABLE'
block1-A-1 block1 0.025 A   0.21  1.9    -4.2   1.25  1.5  5.25 1101 0.10  0.04,-0.06,0.01  0.25 38 0.030 0.02,-0.04,0.35 0.01,0.01,0.03   3611  256
block1-A-2 block1 0.025 A   0.21  1.9    -4.5   1.20  1.3  5.0  1102 0.11  0.05,-0.07,0.02  0.22 38 0.028 0.01,-0.06,0.30 0.01,0.01,0.03   3702  256
block1-B-1 block1 0.025 B   0.18  2.0    2.0    1.30  1.8  5.25 1103 0.10  -0.02,0.03,0.05  0.30 41 0.035 -0.03,0.05,0.50 0.012,0.012,0.04 4933  256
block1-B-2 block1 0.025 B   0.21  1.9    1.6    1.20  1.4  4.75 1104 0.09  -0.03,0.02,0.04  0.28 41 0.032 -0.02,0.03,0.45 0.012,0.012,0.04 5020  256
block2-A-1 block2 0.035 A   0.197 2.185  -2.032 0.197 2.33 6.0  1201 0.10  0.01,0.05,-0.03  0.20 36 0.025 0.03,-0.02,0.25 0.01,0.01,0.02   7260  256
block2-A-2 block2 0.035 A   0.21  2.3    -1.8   0.25  1.25 5.0  1202 0.12  0.02,0.04,-0.02  0.18 36 0.024 0.02,-0.03,0.28 0.01,0.01,0.02   7341  256
block2-B-1 block2 0.035 B   0.17  1.3    3.5    1.20  1.9  5.75 1203 0.10  -0.05,0.00,0.02  0.26 43 0.030 0.00,0.04,0.40  0.01,0.015,0.03  8405  256
block2-B-2 block2 0.035 B   0.20  1.5    2.8    1.35  1.35 5.0  1204 0.11  -0.04,0.01,0.03  0.24 43 0.033 -0.01,0.05,0.42 0.01,0.015,0.03  8488  256
block3-A-1 block3 0.045 A   0.22  1.2    4.2    1.00  1.45 6.0  1301 0.10  0.06,-0.01,0.00  0.32 34 0.040 0.02,0.03,0.30  0.01,0.01,0.03   10822 256
block3-A-2 block3 0.045 A   0.19  1.4    3.6    1.10  1.7  5.5  1302 0.09  0.05,-0.02,0.01  0.30 34 0.038 0.01,0.02,0.33  0.01,0.01,0.03   10915 256
block3-B-1 block3 0.045 B   0.21  2.4    -0.4   1.20  1.2  5.75 1303 0.10  0.00,0.06,-0.04  0.20 39 0.022 0.15,-0.40,1.60 0.03,0.04,0.08   12004 256
block3-B-2 block3 0.045 B   0.18  2.1    -0.2   1.30  1.55 5.5  1304 0.10  0.01,0.05,-0.05  0.21 39 0.024 0.04,-0.08,0.50 0.015,0.015,0.04 12110 256
block4-A-1 block4 0.06  A   0.24  1.0    0.3    1.30  1.75 6.25 1401 0.11  -0.06,-0.03,0.02 0.27 45 0.030 0.02,-0.03,0.38 0.01,0.01,0.03   14439 256
block4-A-2 block4 0.06  A   0.21  1.4    0.6    1.20  1.3  5.75 1402 0.10  -0.05,-0.04,0.02 0.25 45 0.031 0.03,-0.02,0.36 0.01,0.01,0.03   14528 256
block4-B-1 block4 0.06  B   0.19  1.9    -1.0   1.00  1.65 6.5  1403 0.10  0.03,0.02,-0.06  0.23 37 0.027 -0.02,0.02,0.44 0.01,0.01,0.03   15711 256
block4-B-2 block4 0.06  B   0.18  2.0    -1.2   1.20  1.4  5.5  1404 0.10  0.02,0.03,-0.05  0.22 37 0.026 -0.01,0.03,0.41 0.01,0.01,0.03   15790 128
TABLE
)

wanted() {
  [ ${#selected[@]} -eq 0 ] && return 0
  local s
  for s in "${selected[@]}"; do [ "$s" = "$1" ] && return 0; done
  return 1
}

mounting_of() { [ "$1" = B ] && echo "-x,-y,z" || echo "x,y,z"; }

made=0
while read -r id block b2 pos alpha lambda lat lon t0 dur seed noise bias gain freq decay slope walk rtc qrate; do
  wanted "$id" || continue
  args=(synth --b1 "$B1" --b2 "$b2" --h "$H" --density "$RHO"
        --alpha "$alpha" --lambda "$lambda" --lambda-lat "$lat" --lambda-lon "$lon"
        --t0 "$t0" --duration "$dur" --rate 256 --quaternion-rate "$qrate" --mounting="$(mounting_of "$pos")"
        --rtc-start-s "$rtc" --no-rotation-matrix --seed "$seed"
        --gyro-noise-dps "$noise" --gyro-bias-dps="$bias"
        --ringing-gain "$gain" --ringing-frequency-hz "$freq" --ringing-decay-time-s "$decay"
        --drift-slope-dps="$slope" --drift-walk-deg-per-rt-s="$walk"
        -o "recordings/$id")
  if [ "$print_only" -eq 1 ]; then
    echo "rockfit ${args[*]}"
  else
    (cd "$out" && "$rockfit" "${args[@]}" >/dev/null)
  fi
  made=$((made + 1))
done <<< "$table"

# Two generated ground motions for `rockfit respond` (Clough–Penzien filtered white noise with a Jennings
# envelope, io/README.md "Stochastic ground motion"): a moderate one that rocks the granite blocks and a
# stronger, longer one. PEER AT2 files, values in g.
if [ "$print_only" -eq 1 ]; then
  echo "rockfit ground-motion synth --seed 1 --pga 0.3 --duration 20 -o ground-motions/cp-seed1-0.30g.AT2"
  echo "rockfit ground-motion synth --seed 2 --pga 0.45 --duration 30 --t-strong 15 -o ground-motions/cp-seed2-0.45g.AT2"
else
  mkdir -p "$out/ground-motions"
  (cd "$out" && "$rockfit" ground-motion synth --seed 1 --pga 0.3 --duration 20 -o ground-motions/cp-seed1-0.30g.AT2 >/dev/null)
  (cd "$out" && "$rockfit" ground-motion synth --seed 2 --pga 0.45 --duration 30 --t-strong 15 \
      -o ground-motions/cp-seed2-0.45g.AT2 >/dev/null)
fi

if [ "$made" -eq 0 ]; then
  echo "make_samples.sh: no trial matches ${selected[*]}" >&2
  exit 1
fi
[ "$print_only" -eq 1 ] && exit 0

# The campaign manifest (docs/design.md §8), from the same table.
{
  echo "# Sample campaign: synthetic x-IMU recordings made by tools/make_samples.sh with \`rockfit synth\`."
  echo "# The data are synthetic (simulated motion + a measurement model); the truth of every trial is in"
  echo "# recordings/<id>_truth.json. See README.md in this directory."
  for block in block1 block2 block3 block4; do
    b2=$(awk -v b="$block" '$2 == b { print $3; exit }' <<< "$table")
    echo
    echo "[[blocks]]"
    echo "id = \"$block\""
    echo "b1 = $B1"
    echo "b2 = $b2"
    echo "h = $H"
    echo "density = $RHO"
  done
  while read -r id block b2 pos alpha lambda lat lon t0 dur seed noise bias gain freq decay slope walk rtc qrate; do
    echo
    echo "[[trials]]"
    echo "id = \"$id\""
    echo "block = \"$block\""
    echo "position = \"$pos\""
    echo "files = \"recordings/$id\""
    echo "format = \"ximu-gui\""
    echo "rate = 256"
    echo "mounting = \"$(mounting_of "$pos")\""
    note="synthetic; t0 = $t0 s, alpha = $alpha rad, lambda = $lambda, lambda_lat = $lat, lambda_lon = $lon, seed $seed"
    [ "$qrate" != 256 ] && note="$note; Euler angles at $qrate Hz"
    echo "notes = \"$note\""
  done <<< "$table"
} > "$out/manifest.toml"
echo "make_samples.sh: wrote $made trial(s) and manifest.toml to $out"
