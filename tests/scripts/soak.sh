#!/usr/bin/env bash
# Soak test: `headlamp play` in a virtual X display (Xvfb) under random input for SECONDS
# (default 600): walking, looking, firing, the lamp toggled, set down, thrown and picked up,
# the pause menu, restarts, F3, F5 and live reloads of an edited level.toml, the window
# shrunk to 1x1 and back. Samples the process's resident memory every 15 s (on lavapipe the
# GPU's allocations are the process's too) and fails if the game dies, logs an error, or its
# resident memory at the end is more than 10 % above what it was at 2 minutes (a leak: the
# first two minutes are warm-up, caches and pools filling). SECONDS must be at least 180.
# Too long for the test command; run before a release and after changes to the frame loop,
# the renderer or level loading. Needs Xvfb and xdotool (apt-get install xvfb xdotool).
#
#   tests/scripts/soak.sh [SECONDS]    prints "t_s,rss_mib" lines, then a summary
#   tests/scripts/soak.sh --judge-memory T:MIB...
#                                      only the memory verdict, on samples given (for its test)
set -euo pipefail
cd "$(dirname "$0")/../.."

# The memory verdict on "t_s:rss_mib" samples: the last against the first at 2 minutes or later.
judge_memory() {
    local settled="" last="" s
    for s in "$@"; do
        [[ -z $settled ]] && (( ${s%%:*} >= 120 )) && settled=${s#*:}
        last=${s#*:}
    done
    [[ -n $settled ]] || { echo "soak: no memory sample at 2 minutes or later" >&2; return 1; }
    local growth
    growth=$(awk -v a="$settled" -v b="$last" 'BEGIN { printf "%.1f", (b - a) * 100 / a }')
    echo "soak: resident memory ${settled} MiB at 2 min, ${last} MiB at the end: grew ${growth} % (limit 10 %)"
    (( last * 10 <= settled * 11 )) || { echo "soak: resident memory grew more than 10 % after warm-up: a leak" >&2; return 1; }
}
if [[ ${1:-} == --judge-memory ]]; then
    shift
    judge_memory "$@"
    exit
fi

seconds=${1:-600}
(( seconds >= 180 )) || { echo "soak: run for at least 180 s (memory is compared from minute 2 to the end)" >&2; exit 2; }
for tool in Xvfb xdotool; do
    command -v "$tool" >/dev/null || { echo "soak: needs $tool (apt-get install xvfb xdotool)" >&2; exit 2; }
done
cargo build --release -p game >&2
work=$(mktemp -d)
cp -r levels/cellar "$work/level"
display=:$((90 + RANDOM % 9))
Xvfb "$display" -screen 0 1280x800x24 >/dev/null 2>&1 &
xvfb=$!
export DISPLAY=$display XDG_RUNTIME_DIR=$work HEADLAMP_CONFIG=$work/config.toml XDG_CACHE_HOME=$work XDG_DATA_HOME=$work
sleep 1
target/release/headlamp play --level "$work/level" >"$work/play.log" 2>&1 &
game=$!
cleanup() { kill "$game" "$xvfb" 2>/dev/null || true; rm -rf "$work"; }
trap cleanup EXIT
sleep 8
window=$(xdotool search --sync --name '^Headlamp$' | head -1)
alive() { kill -0 "$game" 2>/dev/null; }
focus() { xdotool windowfocus "$window" 2>/dev/null || true; }
# Menu buttons in the 1280x720 window: main menu Play; pause menu Resume and Restart.
play() { xdotool mousemove 640 337 click 1; }
resume() { xdotool mousemove 640 302 click 1; }
restart() { xdotool mousemove 640 345 click 1; }
focus
play
rss() { awk '/VmRSS/ { printf "%.0f", $2 / 1024 }' "/proc/$game/status"; }
echo "t_s,rss_mib"
start=$SECONDS
next_sample=0
samples=()
counts=()
while (( SECONDS - start < seconds )); do
    alive || { echo "soak: the game died after $((SECONDS - start)) s:" >&2; tail -5 "$work/play.log" >&2; exit 1; }
    t=$((SECONDS - start))
    if (( t >= next_sample )); then
        m=$(rss); echo "$t,$m"; samples+=("$t:$m"); next_sample=$((next_sample + 15))
    fi
    focus
    action=$((RANDOM % 14))
    counts[$action]=$(( ${counts[$action]:-0} + 1 ))
    case $action in
        0|1|2) key=$(printf 'w\na\ns\nd' | shuf -n1); xdotool keydown "$key"; sleep "0.$((RANDOM % 9 + 1))"; xdotool keyup "$key" ;;
        3|4) xdotool mousemove_relative -- $((RANDOM % 201 - 100)) $((RANDOM % 41 - 20)) ;;
        5) xdotool click 1 ;;
        6) xdotool key "$(printf 'f\ng\nq\nr\nspace\nc' | shuf -n1)" ;;
        7) xdotool key Escape; sleep 0.5; resume ;;
        8) xdotool key Escape; sleep 0.5; restart ;;
        9) xdotool key F5 ;;
        10) echo "# soak edit $t" >>"$work/level/level.toml" ;;
        11) xdotool windowsize "$window" 1 1; sleep 1; xdotool windowsize "$window" 1280 720 ;;
        12) xdotool key F3 ;;
        13) play ;;  # back into the game if a death or a click left the main menu up
    esac
    sleep 0.2
done
alive || { echo "soak: the game died at the end" >&2; exit 1; }
errors=$(grep -cE "ERROR|panicked" "$work/play.log" || true)
first=${samples[0]#*:}; last=${samples[-1]#*:}
max=0; for s in "${samples[@]}"; do (( ${s#*:} > max )) && max=${s#*:}; done
c() { echo "${counts[$1]:-0}"; }
echo "soak: input: $(( $(c 0) + $(c 1) + $(c 2) )) walks, $(( $(c 3) + $(c 4) )) looks, $(c 5) shots, $(c 6) lamp/reload/jump/crouch keys, $(c 7) pauses, $(c 8) restarts, $(c 9) F5 reloads, $(c 10) level.toml edits, $(c 11) resizes to 1x1, $(c 12) F3, $(c 13) clicks on Play"
echo "soak: ${seconds} s, ${#samples[@]} samples; RSS ${first} MiB at start, ${last} MiB at the end, ${max} MiB at most; ${errors} errors logged"
(( errors == 0 )) || { grep -E "ERROR|panicked" "$work/play.log" | head -5 >&2; exit 1; }
judge_memory "${samples[@]}"
