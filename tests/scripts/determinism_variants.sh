#!/usr/bin/env bash
# Determinism beyond one machine. Every shipped replay, and a 10,000-tick random script per
# shipped level recorded by the normal build, must verify tick for tick (every state hash) in
# builds that compute differently:
#   scalar  glam's scalar-math feature: no SIMD, so no sums in a SIMD-dependent order
#           (avian #1030: enhanced-determinism physics diverging between x86 and ARM);
#   native  RUSTFLAGS='-C target-cpu=native': other instructions (FMA, wider vectors).
# Each variant builds into its own target folder (its first build takes as long as a cold one:
# about 15 minutes on 2 cores). Too slow for the test command: run it before each change to the
# simulation, the physics or the math they use.
#
#   tests/scripts/determinism_variants.sh [scalar|native|all]    (default: all)
set -euo pipefail
cd "$(dirname "$0")/../.."
which=${1:-all}
case "$which" in scalar|native|all) ;; *) echo "usage: $0 [scalar|native|all]" >&2; exit 2;; esac

echo "== the normal build"
cargo build --release -p game
normal=target/release/headlamp
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# A random walk through each level (every action, turning, jumping, the lamp), recorded by the
# normal build: the variants must reproduce its hashes.
random_script() {
    awk -v seed="$1" -v ticks=10000 'BEGIN {
        srand(seed); split("forward,back,left,right,forward sprint,forward jump,crouch forward,wait", a, ",");
        for (total = 0; total < ticks; total += n) {
            n = 1 + int(rand() * 90); lamp = "";
            r = int(rand() * 12); if (r == 0) lamp = " lamp toggle"; else if (r == 1) lamp = " lamp detach";
            printf "%d %s turn %.2f look %.2f%s\n", n, a[1 + int(rand() * 8)], rand() * 240 - 120, rand() * 40 - 20, lamp;
        }
    }'
}
replays=(tests/replays/*.replay)
for toml in levels/*/level.toml; do
    level=$(dirname "$toml")
    id=$(basename "$level")
    random_script 7 > "$work/random_$id.txt"
    "$normal" script "$work/random_$id.txt" --level "$level" --out "$work/random_$id.replay" --seed 7 > /dev/null
    replays+=("$work/random_$id.replay")
done

verify_with() {
    local name=$1 binary=$2 failed=0
    for r in "${replays[@]}"; do
        if out=$("$binary" replay "$r" --verify 2>&1); then
            echo "$name: $(basename "$r"): $out"
        else
            echo "$name: $(basename "$r"): DIVERGED: $out"
            failed=1
        fi
    done
    return $failed
}

status=0
verify_with normal "$normal" || status=1
if [[ $which == scalar || $which == all ]]; then
    echo "== glam scalar-math (target/determinism-scalar)"
    CARGO_TARGET_DIR=target/determinism-scalar cargo build --release -p game --features glam/scalar-math
    verify_with scalar target/determinism-scalar/release/headlamp || status=1
fi
if [[ $which == native || $which == all ]]; then
    echo "== target-cpu=native (target/determinism-native)"
    CARGO_TARGET_DIR=target/determinism-native RUSTFLAGS='-C target-cpu=native' cargo build --release -p game
    verify_with native target/determinism-native/release/headlamp || status=1
fi
if [[ $status == 0 ]]; then echo "determinism: every replay verifies in every build"; else echo "determinism: DIVERGED (see above)"; fi
exit $status
