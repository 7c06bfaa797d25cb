#!/usr/bin/env bash
# Regenerates the horse-gallop tables of docs/results.md with `odeskin evaluate`: frames 1-9 with
# keys 0, 4, 8, and frames 1-25 with keys every 2, 4 and 8 frames, under both skeleton sources
# (truth, keys) and both skeleton fits (rigid, the default; lbs). Needs a built odeskin in
# ${ODESKIN_BUILD_DIR:-build} and the meshes in ${ODESKIN_SHARED_DIR:-../shared}/data. The JSON
# files go to ${1:-a temporary folder}; the Markdown tables go to stdout.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ODESKIN_BUILD_DIR:-$root/build}"
data="${ODESKIN_SHARED_DIR:-$root/../shared}/data"
odeskin="$build/samples/odeskin"
[[ -x "$odeskin" ]] || { echo "evaluation-tables: $odeskin not found; build it first" >&2; exit 1; }
out="${1:-$(mktemp -d)}"
mkdir -p "$out"
horse="$data/horse-gallop"
frames() { for f in $(seq "$1" "$2"); do printf '%s/horse-%02d.obj ' "$horse" "$f"; done; }
keys() { seq -s, 0 "$2" "$1"; }  # keys 0, step, ... up to the last index $1

runs=()
for fit in rigid lbs; do
  for source in truth keys; do
    name="horse-1-9-k4-$source-$fit"
    # shellcheck disable=SC2046
    "$odeskin" evaluate $(frames 1 9) --keys 0,4,8 --pose-source "$source" --skeleton-fit "$fit" \
      --json "$out/$name.json" --quiet
    runs+=("$name")
    for step in 2 4 8; do
      name="horse-1-25-k$step-$source-$fit"
      # shellcheck disable=SC2046
      "$odeskin" evaluate $(frames 1 25) --keys "$(keys 24 "$step")" --pose-source "$source" \
        --skeleton-fit "$fit" --json "$out/$name.json" --quiet
      runs+=("$name")
    done
  done
done

python3 - "$out" "${runs[@]}" <<'PY'
import json, sys
out, runs = sys.argv[1], sys.argv[2:]
methods = ["linear", "lbs", "dqs", "psd_lbs", "psd_dqs", "fd_curve", "odeskin_static", "odeskin_dynamic"]
for run in runs:
    doc = json.load(open(f"{out}/{run}.json"))
    s, frames = doc["summary"], doc["frames"]
    ms = {m: sum(f["methods"][m]["ms_per_frame"] for f in frames) / len(frames) for m in methods}
    print(f"\n**{run}** (pose source {doc['pose_source']}, {len(frames)} in-between frames)\n")
    print("| method | mean % | MVE % | ms/frame | mean / LBS |")
    print("|---|---:|---:|---:|---:|")
    for m in methods:
        print(f"| {m} | {100 * s[m]['mean_mean']:.3f} | {100 * s[m]['mve_max']:.2f} | {ms[m]:.2f} | "
              f"{s[m]['mean_mean'] / s['lbs']['mean_mean']:.2f} |")
PY
