#!/usr/bin/env bash
# The checks a real GPU settles (docs/performance.md, "On a GPU"), in one run of a few minutes:
#  1. every Vulkan test binary, with the texel and then the storage builds of the deformation
#     shaders (ODESKIN_SHADER_INPUTS), under the validation layer when it is installed;
#  2. `odeskin bench`, Vulkan only (CPU cases in between left the GPU cases up to 4x slower in the
#     one mixed run on an H200), texel against storage, twice in alternation;
#  3. the runtime sample, 1,000 cats, texel against storage, and the boxes read from their
#     mapping against staged through cached memory (`read bounds` in its totals);
#  4. the full harness (CPU fast path and Vulkan), for the issue's targets in one run.
# Usage: [GPU_CHECK_STEPS="tests bench runtime full"] scripts/gpu-check.sh [BUILD_DIR] [DATA_DIR] [OUT_DIR]
# (defaults: every step, build, ../shared/data, gpu-check). Each step's log lands in OUT_DIR; nothing
# stops the rest. A device session's commands are limited to 10 minutes each, so GPU_CHECK_STEPS
# lets it run the steps over two calls (say "tests bench", then "runtime full").
set -u
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(realpath "${1:-$root/build}")"
data="$(realpath "${2:-$root/../shared/data}")"
out="${3:-gpu-check}"
mkdir -p "$out"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}" ODESKIN_REQUIRE_GPU=1
odeskin="$build/samples/odeskin"
sample="$build/samples/runtime/odeskin_runtime_sample"
step() { echo "=== $(date +%T) $*"; }
steps=" ${GPU_CHECK_STEPS:-tests bench runtime full} "
wants() { [[ "$steps" == *" $1 "* ]]; }

step "devices"
"$odeskin" info 2>&1 | tee "$out/info.txt"

if wants tests; then
  tests=(device_test buffer_test compute_pipeline_test gpu_deformer_test deform_parity_test pipeline_gpu_test
         render_offscreen_test surfaces.surface_tessellator_test vulkan_soak_test runtime/runtime_vulkan_runtime_test
         runtime/runtime_vulkan_record_test)
  for inputs in texel storage; do
    step "Vulkan tests, $inputs inputs"
    for t in "${tests[@]}"; do
      name="$(basename "$t")"
      ODESKIN_SHADER_INPUTS=$inputs timeout 300 "$build/tests/$t" --gtest_brief=1 > "$out/test_${name}_$inputs.txt" 2>&1
      echo "$name: exit $? $(grep -E '^\[  (PASSED|FAILED|SKIPPED) ' "$out/test_${name}_$inputs.txt" | tr '\n' ' ')"
    done | tee "$out/tests_$inputs.txt"
  done
fi

if wants bench; then
  for round in 1 2; do
    for inputs in texel storage; do
      step "bench, Vulkan only, $inputs inputs, round $round"
      ODESKIN_SHADER_INPUTS=$inputs timeout 300 "$odeskin" bench --no-fit --backends vulkan --sizes 100000,1000000,4000000 \
        --terms 3,9 --min-time 0.5 --data "$data" --json "$out/vulkan_${inputs}_$round.json" > "$out/vulkan_${inputs}_$round.txt" 2>&1
      grep -E "^(device|odeskin |lbs |dqs )" "$out/vulkan_${inputs}_$round.txt" | grep -v " thr "
    done
  done
fi

if wants runtime; then
  for inputs in texel storage; do
    step "runtime sample, 1,000 cats, $inputs inputs"
    ODESKIN_SHADER_INPUTS=$inputs timeout 300 "$sample" --backend vulkan --instances 1000 --seconds 5 -q --data "$data" \
      2>&1 | tee "$out/runtime_$inputs.txt" | grep -E "backend|totals|check"
  done
  for bounds in mapped staged mapped staged; do
    step "runtime sample, 1,000 cats, bounds $bounds"
    timeout 300 "$sample" --backend vulkan --instances 1000 --seconds 2 -q --bounds $bounds --data "$data" \
      2>&1 | tee -a "$out/runtime_bounds_$bounds.txt" | grep -E "backend|totals"
  done
fi

if wants full; then
  step "full harness"
  timeout 540 "$odeskin" bench --no-fit --backends cpu_fast,vulkan --data "$data" --json "$out/full.json" \
    --plot "$out/full.png" > "$out/full.txt" 2>&1
  grep -A100 "^targets" "$out/full.txt"
fi
step "done: $out"
