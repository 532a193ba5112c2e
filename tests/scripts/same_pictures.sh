#!/usr/bin/env bash
# Renders the same frames with two builds of `headlamp` and says whether each is bit-identical:
# for changes that must not change a picture (a refactor of the passes, bindings, constants).
# Views cover both GI methods, visibility, two bounces, the detached lamp, the debug views and
# all three levels; linear EXR where values matter, PNG for the tonemapped ones.
#
#   tests/scripts/same_pictures.sh OLD_HEADLAMP NEW_HEADLAMP [SIZE]    (SIZE default 320x180)
#
# The GPU reference (reference_screen) costs the square of the pixels: keep SIZE small.
# Build the old one from the commit before (`git worktree add`, `cargo build --release`, copy
# target/release/headlamp). Exit status 1 when any picture differs.
set -euo pipefail
cd "$(dirname "$0")/../.."
[ $# -ge 2 ] || { echo "usage: $0 OLD_HEADLAMP NEW_HEADLAMP [SIZE]" >&2; exit 2; }
old=$1 new=$2 size=${3:-320x180}
out=$(mktemp -d)
[ -n "${XDG_RUNTIME_DIR:-}" ] || export XDG_RUNTIME_DIR="$out"
cases=(
    "final.exr --level levels/cellar"
    "indirect.exr --level levels/cellar --view indirect"
    "visibility.exr --level levels/cellar --view indirect --set gi.visibility=1"
    "article.exr --level levels/cellar --view indirect --set gi.method=article"
    "article_visibility.exr --level levels/cellar --view indirect --set gi.method=article --set gi.visibility=1"
    "two_bounces.exr --level levels/cellar --view indirect --set gi.bounces=2"
    "three_bounces_visibility.exr --level levels/cellar --view indirect --set gi.bounces=3 --set gi.visibility=1"
    "flux_gi_off.exr --level levels/cellar --view flux --gi off"
    "lights_gi_off.png --level levels/cellar --view lights --gi off"
    "detached.exr --level levels/cellar --lamp 0,2.6,-5:-0.4,0,-5.2 --set gi.visibility=1"
    "reference_screen.exr --level levels/cellar --view reference_screen"
    "lights.png --level levels/cellar --view lights"
    "flux.exr --level levels/cellar --view flux"
    "room.exr --level levels/cellar --camera=-2,1.6,-5.5:-7.4,2,-5"
    "gallery.png --level levels/gallery"
    "hall.exr --level levels/hall --camera=0,1.6,0:3,1.5,-4"
)
differ=0
for c in "${cases[@]}"; do
    read -r name args <<< "$c"
    # shellcheck disable=SC2086 # the arguments are words
    "$old" render $args --size "$size" --out "$out/old_$name" > /dev/null
    # shellcheck disable=SC2086
    "$new" render $args --size "$size" --out "$out/new_$name" > /dev/null
    if cmp -s "$out/old_$name" "$out/new_$name"; then
        echo "same:   $name ($args)"
    else
        echo "DIFFER: $name ($args): $out/old_$name, $out/new_$name"
        differ=1
    fi
done
exit $differ
