#!/usr/bin/env bash
# A census of earthquake responses: how every run of many fragility studies ends. Every block and position of
# the sample campaign with its fitted spread (the pooled estimates of `rockfit batch`), both overturning rules,
# PGA levels from 0.05 to 1 g, random incidence angles, the generated records and, when given, a directory of
# real PEER records. A run must end as rest, t_max, overturned or lift_off; the census prints the count of each
# end status and the largest |ω| that a rest set to zero (core/README.md, "Rest, uplift and lift-off").
#
#   tools/response_census.sh ROCKFIT OUT_DIR [SAMPLES_PER_LEVEL] [RECORD_DIR]
#
# 540 samples per level give 8 groups × 2 rules × 12 levels × 540 = 103,680 runs (3.5 min on two cores here);
# CI runs none of it (the tests hold the cases it found).
set -euo pipefail
rockfit="${1:?usage: tools/response_census.sh ROCKFIT OUT_DIR [SAMPLES_PER_LEVEL] [RECORD_DIR]}"
out="${2:?usage: tools/response_census.sh ROCKFIT OUT_DIR [SAMPLES_PER_LEVEL] [RECORD_DIR]}"
samples="${3:-540}"
record_dir="${4:-}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
manifest="$here/data-samples/manifest.toml"
mkdir -p "$out"

[ -f "$out/fits.h5" ] || "$rockfit" batch "$manifest" -o "$out/fits.h5" >/dev/null

records=(--record "$here/data-samples/ground-motions/cp-seed1-0.30g.AT2"
         --record "$here/data-samples/ground-motions/cp-seed2-0.45g.AT2" --synthetic-records 3)
if [ -n "$record_dir" ]; then
  for f in "$record_dir"/*.AT2 "$record_dir"/*.at2; do [ -f "$f" ] && records+=(--record "$f"); done
fi

for block in block1 block2 block3 block4; do
  for position in A B; do
    for rule in support side; do
      study="$out/census-$block-$position-$rule.h5"
      [ -f "$study" ] && continue
      "$rockfit" fragility --manifest "$manifest" --block "$block" --fits "$out/fits.h5" --group "$block,$position" \
        "${records[@]}" --pga 0.05:1:12 --samples "$samples" --seed 12 --overturn "$rule" -o "$study" --json \
        >"$out/census-$block-$position-$rule.json"
    done
  done
done

# Debian's interpreter has python3-h5py; another python3 first on PATH may not.
py=/usr/bin/python3
[ -x "$py" ] || py=python3
"$py" - "$out" <<'EOF'
import collections, glob, sys
import h5py, numpy as np
counts = collections.Counter()
worst = 0.0
worst_at = ""
failed = []
for path in sorted(glob.glob(sys.argv[1] + "/census-*.h5")):
    with h5py.File(path, "r") as f:
        s = f["fragility/samples"]
        reasons = [r.decode() if isinstance(r, bytes) else r for r in s["end_reason"][()]]
        counts.update(reasons)
        dropped = s["max_discarded_rate_rad_s"][()]
        k = int(np.argmax(dropped))
        if dropped[k] > worst:
            worst, worst_at = float(dropped[k]), f"{path}, sample {int(s['index'][k])}"
        failed += [f"{path}, sample {int(i)}" for i, r in zip(s["index"][()], reasons) if r in ("failed", "invalid")]
total = sum(counts.values())
print(f"runs: {total}")
for reason, n in counts.most_common():
    print(f"  {reason:<12} {n}")
print(f"largest |ω| a rest set to zero: {worst:.3g} rad/s ({worst_at})")
for line in failed[:20]:
    print("not counted:", line)
EOF
