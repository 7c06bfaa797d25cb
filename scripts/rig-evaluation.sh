#!/usr/bin/env bash
# In-between error of the curve rig (`--rig curves`, bones from the first key's iso-curves) against
# the motion-based rig (`--rig auto`) with `odeskin evaluate` (docs/rigging.md): horse-gallop
# frames 1-9 with keys 0, 4, 8 and frames 1-25 with keys every 4, under both skeleton sources, and
# cat-poses leave-one-out (each pose predicted from its two neighbours, truth skeleton). Prints
# Markdown tables of the mean error (% of the longest box side) to stdout.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ODESKIN_BUILD_DIR:-$root/build}"
data="${ODESKIN_SHARED_DIR:-$root/../shared}/data"
odeskin="$build/samples/odeskin"
[[ -x "$odeskin" ]] || { echo "rig-evaluation: $odeskin not found; build it first" >&2; exit 1; }
out="${1:-$(mktemp -d)}"
mkdir -p "$out"
methods=lbs,dqs,psd_lbs,odeskin_static,odeskin_dynamic
H="$data/horse-gallop"

table() {  # table TITLE FILE...: one row per JSON (rig, protocol), one column per method
  python3 - "$@" <<'PY'
import json, sys
title, files = sys.argv[1], sys.argv[2:]
methods = ["lbs", "dqs", "psd_lbs", "odeskin_static", "odeskin_dynamic"]
print(f"\n**{title}**\n")
print("| run | bones | " + " | ".join(methods) + " |")
print("|---|---:|" + "---:|" * len(methods))
for f in files:
    d = json.load(open(f))
    name = f.rsplit("/", 1)[-1].removesuffix(".json")
    bones = d.get("bones", "")
    print(f"| {name} | {bones} | " + " | ".join(f"{100 * d['summary'][m]['mean_mean']:.3f}" for m in methods) + " |")
PY
}

files=()
for rig in auto curves; do
  for source in truth keys; do
    "$odeskin" evaluate "$H"/horse-0{1..9}.obj --keys 0,4,8 --pose-source "$source" --rig "$rig" --methods "$methods" \
      --json "$out/horse-1-9-$rig-$source.json" --quiet
    files+=("$out/horse-1-9-$rig-$source.json")
  done
done
table "horse-gallop frames 1-9, keys 0, 4, 8 (mean %)" "${files[@]}"
files=()
for rig in auto curves; do
  for source in truth keys; do
    "$odeskin" evaluate "$H"/horse-{01..25}.obj --keys 0,4,8,12,16,20,24 --pose-source "$source" --rig "$rig" \
      --methods "$methods" --json "$out/horse-1-25-$rig-$source.json" --quiet
    files+=("$out/horse-1-25-$rig-$source.json")
  done
done
table "horse-gallop frames 1-25, keys every 4 (mean %)" "${files[@]}"

cats=("$data"/cat-poses/cat-0{1..9}.obj)
for rig in auto curves; do
  for ((i = 1; i + 1 < ${#cats[@]}; ++i)); do
    "$odeskin" evaluate "${cats[i - 1]}" "${cats[i]}" "${cats[i + 1]}" --keys 0,2 --pose-source truth --rig "$rig" \
      --methods "$methods" --json "$out/cat-$rig-$i.json" --quiet
  done
done
python3 - "$out" $((${#cats[@]} - 2)) <<'PY'
import json, sys
out, n = sys.argv[1], int(sys.argv[2])
methods = ["lbs", "dqs", "psd_lbs", "odeskin_static", "odeskin_dynamic"]
print(f"\n**cat-poses leave-one-out over {n} poses, truth skeleton (mean of the per-pose mean %)**\n")
print("| rig | " + " | ".join(methods) + " |")
print("|---|" + "---:|" * len(methods))
for rig in ["auto", "curves"]:
    docs = [json.load(open(f"{out}/cat-{rig}-{i}.json")) for i in range(1, n + 1)]
    print(f"| {rig} | " + " | ".join(f"{100 * sum(d['summary'][m]['mean_mean'] for d in docs) / n:.3f}" for m in methods) + " |")
PY
