#!/usr/bin/env bash
# The test command on a machine without lavapipe (Mesa's software Vulkan driver), on whatever
# adapter it has. The goldens and the GI's figures were measured on lavapipe, and the tests that
# compare with them open lavapipe by its driver name (`Gpu::lavapipe`): without it they fail
# with install advice. This runs every other test, skipping those by name and printing a line
# for each, so nothing is skipped silently. On a machine with both a GPU and lavapipe, run the
# test command itself: those tests take lavapipe and the rest the adapter wgpu picks.
#
#   tests/scripts/other_adapter.sh [ADAPTER]    (ADAPTER: part of an adapter's name, as
#                                                WGPU_ADAPTER_NAME takes it; default: wgpu's pick)
set -euo pipefail
cd "$(dirname "$0")/../.."
[ $# -gt 0 ] && export WGPU_ADAPTER_NAME="$1"

# The tests of every test file that opens lavapipe (directly, or through the GI tests' `gpu()`),
# and the one that runs `headlamp replay --goldens`.
skips=()
skip() {
    echo "skipped (compared with what lavapipe measured): $1: $2"
    skips+=(--skip "$2")
}
while IFS= read -r file; do
    for name in $(awk '/#\[test\]/ { t = 1; next } t && /fn [a-z0-9_]+/ { match($0, /fn [a-z0-9_]+/); print substr($0, RSTART + 3, RLENGTH - 3); t = 0 }' "$file"); do
        skip "$file" "$name"
    done
done < <( (grep -rlE --include='*.rs' 'Gpu::lavapipe|render_replay_ticks|render_level_shot' game/tests tests;
           grep -rl --include='*.rs' '= gpu();' plugin_gi/tests) | sort -u)
skip game/tests/replay_cli.rs goldens_are_written_then_compared_and_a_changed_frame_fails
echo "${#skips[@]} arguments: $(( ${#skips[@]} / 2 )) tests skipped"

cargo test --workspace --release --locked -- --exact "${skips[@]}"
