#!/usr/bin/env bash
# The README's measured figures against the commands that measure them: fails, naming the
# figure and both values, when a quoted figure no longer matches its measurement (figures are
# generated, not typed). CI runs it after the firmware size check and the emulated bench
# (it reads emu/target/bench-m4.txt, which `bash emu/run.sh m4` writes, and
# target/board/shipped.txt, which `bash emu/board/run.sh` writes).
#
# Checked: both firmwares' flash and static RAM, the bytes per frame on the wire and the board
# in the loop's frame rates and stack peaks ("On the board"), the converted torus's scan-line RAM
# and the converted icosphere's flash, plain and compact ("Bring your own model"), the emulated cube counts of cull-only and the
# scan-line method ("Methods"), the emulated torus smooth and flat ("Smooth shading") and as hidden lines ("Hidden-line drawings"), and the scan-line RAM column of the methods table against
# docs/methods/foley.md (which its own command writes).
# The commands run as debug builds, which `cargo test` has built already: their figures are
# the same in release (the frames are bit-identical, docs/extremes.md item 21; the rest is
# counting), without a release build of the simulator and the panel crate for them.
set -euo pipefail
cd "$(dirname "$0")/.."
readme=README.md
fail=0

# thousands 132384 -> 132,384
thousands() { echo "$1" | sed ':a;s/\B[0-9]\{3\}\>/,&/;ta'; }

expect() { # what, text that must be in the README
  if grep -qF -- "$2" "$readme"; then
    echo "check-figures: $1: \"$2\" matches"
  else
    echo "check-figures: $1: the README should say \"$2\" (measured now); update it" >&2
    fail=1
  fi
}

# Both firmwares' flash and static RAM.
sizes="$(bash scripts/firmware-size.sh 2>&1 | grep ': flash')"
size_of() { # board name, the README's words before the flash figure
  local out flash ram quoted
  out="$(grep "^$1: flash" <<<"$sizes")"
  flash="$(echo "$out" | sed -E 's/^[a-z]+: flash ([0-9]+) bytes.*/\1/')"
  ram="$(echo "$out" | sed -E 's/.*static RAM ([0-9]+) bytes.*/\1/')"
  # Flash in KB to a tenth, within 0.3 KB: its exact bytes move with the checkout's path, which
  # the panic locations of the crates outside the firmware's workspace carry (a clone in /tmp/ci
  # measured 0.1 KB less than one in /work/main).
  quoted="$(sed -nE "s/.*$2 ([0-9]+\.[0-9]) KB of.*/\1/p" "$readme" | head -1)"
  if [ -n "$quoted" ] && awk -v q="$quoted" -v f="$flash" 'BEGIN { d = q - f / 1024; exit !(d <= 0.3 && d >= -0.3) }'; then
    echo "check-figures: $1 flash: \"$quoted KB\" is within 0.3 KB of $flash bytes"
  else
    echo "check-figures: $1 flash: the README says \"${quoted:-nothing}\" KB, measured $(awk -v f="$flash" 'BEGIN { printf "%.1f", f / 1024 }') KB; update it" >&2
    fail=1
  fi
  expect "$1 static RAM" "$(thousands "$ram") bytes of static RAM"
}
size_of firmware "at this commit"
size_of bluepill "at this commit the Blue Pill's"

# Bytes on the wire per demo frame, whole and changed rows only (the README's table, as the
# example prints it).
while IFS= read -r line; do
  case "$line" in
    "| interlocked"* | "| cube"* | "| mesh1k"*)
      expect "wire bytes, $(echo "$line" | cut -d'|' -f2 | xargs)" "$line" ;;
  esac
done < <(cargo run -q -p zrow-st7789 --example wire)

# The board sink's cost on the emulated M4 (the bench's two `board sink` lines).
sink() { grep "^# board sink, mesh1k: $1" emu/target/bench-m4.txt | sed -E 's/.*instructions=([0-9]+).*/\1/'; }
encode="$(sink "encoding 240 rows for")"
signed="$(sink "encoding 240 rows and")"
expect "board sink, encoding" "takes $(thousands "$encode") instructions"
expect "board sink, signatures" "$(thousands $((signed - encode))) more (about $(awk -v d=$((signed - encode)) 'BEGIN { printf "%.1f", d / 1e5 }') ms"

# The board in the loop's tables and stack peaks (emu/board/run.sh, which CI runs first, keeps
# them).
for board in target/board/shipped.txt target/board/bluepill.txt; do
  if [ -s "$board" ]; then
    while IFS= read -r line; do
      case "$line" in
        "| interlocked"* | "| cube"* | "| mesh1k"*)
          expect "board in the loop, $(basename "$board" .txt), $(echo "$line" | cut -d'|' -f2 | xargs)" "$line" ;;
      esac
    done <"$board"
    peak="$(sed -nE 's/.*stack peak ([0-9]+) bytes.*/\1/p' "$board")"
    expect "stack peak, $(basename "$board" .txt)" "$(thousands "$peak") bytes"
  else
    echo "check-figures: $board missing: run bash emu/board/run.sh first" >&2
    fail=1
  fi
done

# The converted torus's scan-line RAM (the README's convert command).
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
report="$(cargo run -q -p zrow-sim -- convert --model assets/models/torus.off \
  --out "$tmp/torus.rs" --size 240x240 --distance 3 2>&1)"
torus="$(echo "$report" | sed -nE 's/.*RAM: scan-line ([0-9]+) bytes.*/\1/p')"
display="$(echo "$report" | sed -nE 's/.*RAM: scan-line [0-9]+ bytes \(([0-9]+) as a display.*/\1/p')"
expect "converted torus RAM" "torus at 240×240: $(thousands "$torus") bytes"
expect "converted torus RAM, display renderer" "$(thousands "$display") as a display's renderer"

# The converted icosphere's flash as a triangle list, and what its faces would take as a list
# of zrow::Face (12 bytes each instead of the 2 of its one colour).
ico="$(cargo run -q -p zrow-sim -- convert --model assets/models/icosphere.stl \
  --out "$tmp/icosphere.rs" --size 240x240 --distance 3 2>&1 |
  sed -nE 's/.*flash \(32-bit target\): ([0-9]+) bytes = .* faces ([0-9]+) .*/\1 \2/p')"
read -r ico_flash ico_faces <<<"$ico"
ico_listed=$((ico_flash - ico_faces + 12 * $(grep -c '^    \[' "$tmp/icosphere.rs")))
expect "converted icosphere flash" "the icosphere: $(thousands "$ico_flash") bytes of flash where its faces would take $(thousands "$ico_listed")"
# The same with compact positions.
ico_compact="$(cargo run -q -p zrow-sim -- convert --model assets/models/icosphere.stl \
  --out "$tmp/icosphere-compact.rs" --size 240x240 --distance 3 --compact 2>&1 |
  sed -nE 's/.*flash \(32-bit target\): ([0-9]+) bytes = .*/\1/p')"
expect "converted icosphere flash, compact" "the icosphere: $(thousands "$ico_compact") bytes of flash instead of $(thousands "$ico_flash")"

# The emulated cube: cull-only against the scan-line method (Q16.16, M instructions).
bench=emu/target/bench-m4.txt
count() { awk -v m="$1" '$1 == "method=" m && $2 == "scene=cube" && $3 == "format=q16.16" {
  split($5, f, "="); printf "%.2f", f[2] / 1e6 }' "$bench"; }
expect "emulated cube, cull-only" "counts $(count cull-only) M for the cube"
expect "emulated cube, scan-line" "the scan-line method's $(count scanline) M"

# The emulated torus smooth shaded against flat (Q16.16, M instructions; "Smooth shading").
torus() { awk -v s="$1" '$1 == "method=scanline" && $2 == "scene=" s && $3 == "format=q16.16" {
  split($5, f, "="); printf "%.2f", f[2] / 1e6 }' "$bench"; }
expect "emulated torus, smooth and flat" "$(torus mesh1k-smooth) M instructions smooth against $(torus mesh1k) M flat"
# ... and as a hidden-line drawing ("Hidden-line drawings").
expect "emulated torus, hidden lines and flat" "costs $(torus mesh1k-lines) M instructions against $(torus mesh1k) M flat-shaded"
# ... and the display renderer's RAM for it at exact requirements ("Methods").
torus_ram() { awk '$1 == "method=scanline" && $2 == "scene=mesh1k" && $3 == "format=q16.16" {
  split($6, f, "="); print f[2] }' "$bench"; }
expect "emulated torus, display renderer RAM" "torus then needs $(thousands "$(torus_ram)") bytes at exact"

# The methods table's scan-line RAM, as docs/methods/foley.md has it.
ram_cols="$(awk -F'|' '$2 ~ /^ scanline $/ && $5 ~ /KiB/ { gsub(/ |KiB/, "", $5); gsub(/ |KiB/, "", $8); print $5 " / " $8 " KiB"; exit }' docs/methods/foley.md)"
expect "methods table, scan-line RAM @100 / @2,500" "| $ram_cols |"

# Smooth shading against the f64 reference, as docs/presets/presets.md has it (Q16.16 rows).
shade_err() { # the drawing's name: "max mean"
  awk -F'|' -v d="$1" '$2 ~ ("^ " d " \\(") && $3 ~ /q16.16/ {
    match($7, /max [0-9.]+ \/ mean [0-9.]+/); split(substr($7, RSTART, RLENGTH), f, " ");
    print f[2], f[5]; exit }' docs/presets/presets.md
}
read -r g_max g_mean < <(shade_err gouraud)
read -r d_max _ < <(shade_err "gouraud \\+ dither")
expect "smooth torus against the f64 reference" "within $g_max LSB of the f64"
expect "smooth torus, mean and dithered" "($g_mean LSB mean), $d_max LSB dithered"

exit "$fail"
