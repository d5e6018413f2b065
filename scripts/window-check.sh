#!/usr/bin/env bash
# window-check: opens the simulator window under Xvfb, takes a screenshot and checks that it
# shows the expected frame (not a blank or black window).
#
#   scripts/window-check.sh
#
# 1. installs libsdl2-dev, xvfb, imagemagick and x11-utils if missing (apt-get, via sudo
#    unless root);
# 2. builds `zrow-sim --features window` (a debug build: the check is of the window, not of
#    speed, and after `cargo test` only the window's crates and zrow-sim compile) and writes
#    the expected first frame with `zrow-sim --dump-expected` (headless, 480x480: the window
#    shows 240x240 at 2x);
# 3. starts `Xvfb :99`, runs `zrow-sim --paused` (frozen on that first frame), waits for its
#    window (xwininfo, at most ~30 s), takes `import -window root`;
# 4. cuts the window's 480x480 out of the screenshot (its position from xwininfo) and compares
#    it with the expected frame below the status line (whose render time differs run to run):
#    at least 95 % of those pixels must match (ImageMagick `compare -metric AE -fuzz 3%`), and
#    the window must not be blank (below the status line, at least half as many non-black
#    pixels as the expected frame, which has at least 2 %, and at least 8 colours).
#
# Leaves shot.png, window.png and expected.png in $WINDOW_CHECK_OUT (default
# target/window-check). Exits non-zero with a message on failure.
set -euo pipefail
cd "$(dirname "$0")/.."

OUT=${WINDOW_CHECK_OUT:-target/window-check}
DISPLAY_NUM=${WINDOW_CHECK_DISPLAY:-99}
TITLE="zrow-sim demo"
SIDE=480          # 240 pixels at scale 2
STATUS=44         # the status line's 22 rows at scale 2
MIN_MATCH=95      # per cent

fail() { echo "window-check: FAIL: $*" >&2; exit 1; }

need=()
dpkg -s libsdl2-dev >/dev/null 2>&1 || need+=(libsdl2-dev)
command -v Xvfb >/dev/null || need+=(xvfb)
command -v import >/dev/null || need+=(imagemagick)
command -v xwininfo >/dev/null || need+=(x11-utils)
if [ ${#need[@]} -gt 0 ]; then
    echo "window-check: installing ${need[*]}"
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo=sudo
    $sudo apt-get update -qq
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${need[@]}" >/dev/null
fi

# ImageMagick's own convert (Debian names it convert-im6.q16), not any other `convert` on PATH.
CONVERT=$(command -v convert-im6.q16 || command -v convert)

cargo build -p zrow-sim --features window
bin="${CARGO_TARGET_DIR:-target}/debug/zrow-sim"
[ -x "$bin" ] || fail "no binary at $bin"

mkdir -p "$OUT"
rm -f "$OUT"/shot.png "$OUT"/window.png "$OUT"/expected.png
"$bin" --dump-expected "$OUT/expected.png"

xpid="" app=""
cleanup() {
    [ -z "$app" ] || kill "$app" 2>/dev/null || true
    [ -z "$xpid" ] || kill "$xpid" 2>/dev/null || true
    wait 2>/dev/null || true
}
trap cleanup EXIT

Xvfb ":$DISPLAY_NUM" -screen 0 800x600x24 -nolisten tcp >"$OUT/xvfb.log" 2>&1 &
xpid=$!
export DISPLAY=":$DISPLAY_NUM"
for _ in $(seq 50); do
    xwininfo -root >/dev/null 2>&1 && break
    kill -0 "$xpid" 2>/dev/null || fail "Xvfb :$DISPLAY_NUM did not start: $(cat "$OUT/xvfb.log")"
    sleep 0.2
done
xwininfo -root >/dev/null 2>&1 || fail "Xvfb :$DISPLAY_NUM does not answer"

"$bin" --paused >"$OUT/app.log" 2>&1 &
app=$!

# Wait for the window, then for it to show the frame (it is mapped before its first paint).
total=$((SIDE * (SIDE - STATUS)))
result=""
for _ in $(seq 60); do
    sleep 0.5
    kill -0 "$app" 2>/dev/null || fail "zrow-sim exited: $(cat "$OUT/app.log")"
    info=$(xwininfo -name "$TITLE" 2>/dev/null) || continue
    x=$(awk '/Absolute upper-left X:/ {print $4}' <<<"$info")
    y=$(awk '/Absolute upper-left Y:/ {print $4}' <<<"$info")
    w=$(awk '/Width:/ {print $2}' <<<"$info")
    h=$(awk '/Height:/ {print $2}' <<<"$info")
    [ "$w" = "$SIDE" ] && [ "$h" = "$SIDE" ] || fail "window is ${w}x${h}, expected ${SIDE}x${SIDE}"
    import -window root "$OUT/shot.png"
    "$CONVERT" "$OUT/shot.png" -crop "${SIDE}x${SIDE}+${x}+${y}" +repage "$OUT/window.png"
    # Pixels that differ below the status line.
    below="-crop ${SIDE}x$((SIDE - STATUS))+0+${STATUS} +repage"
    # shellcheck disable=SC2086
    diff=$(compare -metric AE -fuzz 3% \( "$OUT/window.png" $below \) \( "$OUT/expected.png" $below \) null: 2>&1 || true)
    diff=$(awk '{printf "%d", $1}' <<<"$diff")
    match=$(( (total - diff) * 100 / total ))
    # Not blank: below the status line, at least half as many non-black pixels as expected.
    # shellcheck disable=SC2086
    lit=$("$CONVERT" "$OUT/window.png" $below -fill white +opaque black -format '%[fx:int(mean*1000)]' info:)
    # shellcheck disable=SC2086
    want=$("$CONVERT" "$OUT/expected.png" $below -fill white +opaque black -format '%[fx:int(mean*1000)]' info:)
    # shellcheck disable=SC2086
    colours=$("$CONVERT" "$OUT/window.png" $below -format '%k' info:)
    result="window at +$x+$y: $match % of $total pixels below the status line match the expected frame; $((lit / 10)).$((lit % 10)) % of them not black (expected $((want / 10)).$((want % 10)) %); $colours colours"
    if [ "$match" -ge "$MIN_MATCH" ] && [ "$want" -ge 20 ] && [ $((2 * lit)) -ge "$want" ] && [ "$colours" -ge 8 ]; then
        echo "window-check: OK: $result"
        exit 0
    fi
done
[ -n "$result" ] || fail "no window called '$TITLE' appeared within 30 s"
fail "$result (need >= $MIN_MATCH % matching, >= half the expected non-black pixels, >= 8 colours); see $OUT/"
