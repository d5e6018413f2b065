#!/usr/bin/env bash
# zrow's emulated bench: renders every standard scene in Q16.16 and f32 with the scan-line
# method, the comparison scenes (foley100, foley2500) in Q16.16 with every compared method
# (emu/src/methods.rs), and every preset (zrow::presets, method=preset:NAME) on every preset
# scene (cube, mesh1k, interlocked; emu/src/presets.rs), on a QEMU Cortex-M and prints one line
# per frame,
#   method=NAME scene=NAME format=FMT tris=N instructions=N ram=BYTES hash=HEX
# then a table with an estimated frame time at 100 MHz beside the SPI frame time at 50 MHz.
#
# usage: emu/run.sh [m4|m3]      (default m4)
#   m4: thumbv7em-none-eabihf on qemu-system-arm -M mps2-an386 (Cortex-M4F, hardware f32)
#   m3: thumbv7m-none-eabi    on qemu-system-arm -M mps2-an385 (Cortex-M3, soft-float f32)
#
# Installs what is missing (qemu-system-arm and binutils from apt, the thumb targets from
# rustup), builds the counting plugin (tools/qemu-icount) and the bench ELF in release, reads the
# two marker functions' addresses from the ELF, and runs QEMU with the plugin. The guest prints
# `instructions=?` (it cannot count itself); the plugin prints one count per start/stop pair, in
# order, and this script puts the k-th count into the k-th `?`. The merged output is also written
# to emu/target/bench-CPU.txt (emu/check.sh reads it). Exits non-zero on any failure.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
cpu="${1:-m4}"
case "$cpu" in
  m4) target=thumbv7em-none-eabihf; machine=mps2-an386; label="Cortex-M4F (mps2-an386, hardware single-precision FPU)" ;;
  m3) target=thumbv7m-none-eabi; machine=mps2-an385; label="Cortex-M3 (mps2-an385, no FPU: f32 is soft-float)" ;;
  *) echo "usage: $0 [m4|m3]" >&2; exit 2 ;;
esac
timeout_s="${EMU_TIMEOUT:-300}"

# --- what the run needs -----------------------------------------------------------------------
as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }
apt_updated=""
need() { # need COMMAND DEBIAN-PACKAGE
  command -v "$1" >/dev/null 2>&1 && return 0
  echo "run.sh: $1 not found; installing $2 (apt-get)" >&2
  if [ -z "$apt_updated" ]; then as_root apt-get update -qq >&2; apt_updated=1; fi
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "$2" >&2
}
need qemu-system-arm qemu-system-arm
need readelf binutils
if command -v rustup >/dev/null 2>&1; then
  (cd "$root" && rustup target add thumbv7em-none-eabihf thumbv7m-none-eabi >&2)
fi

# --- build ------------------------------------------------------------------------------------
# Explicit target dirs (the defaults inside tools/ and emu/), so an inherited CARGO_TARGET_DIR
# cannot move the artefacts away from the paths below. cd so each crate's .cargo/config.toml
# applies (the bench's carries the link script).
plugin_dir="$root/tools/qemu-icount"
(cd "$plugin_dir" && cargo build --release --quiet --target-dir "$plugin_dir/target")
plugin="$plugin_dir/target/release/libqemu_icount.so"
(cd "$here" && cargo build --release --quiet --target "$target" --target-dir "$here/target")
elf="$here/target/$target/release/zrow-emu-bench"

symbol() { # the value of ELF symbol $1 (Thumb bit included; the plugin ignores bit 0)
  local v
  v="$(readelf -sW "$elf" | awk -v s="$1" '$8 == s { print $2; exit }')"
  if [ -z "$v" ]; then echo "run.sh: symbol $1 not found in $elf" >&2; exit 1; fi
  echo "0x$v"
}
start="$(symbol zrow_bench_start)"
stop="$(symbol zrow_bench_stop)"

# --- run --------------------------------------------------------------------------------------
out_dir="$here/target"
raw="$out_dir/bench-$cpu.raw"
counts="$out_dir/bench-$cpu.counts"
log="$out_dir/bench-$cpu.qemu.log"
result="$out_dir/bench-$cpu.txt"
rm -f "$raw" "$counts" "$log" "$result"
qemu_version="$(qemu-system-arm --version | head -n 1)"
cmd=(qemu-system-arm -M "$machine" -nographic
  -semihosting-config enable=on,target=native
  -plugin "$plugin,start=$start,stop=$stop,out=$counts"
  -kernel "$elf")
echo "# $label; $qemu_version" >&2
echo "# timeout ${timeout_s}s ${cmd[*]}" >&2
status=0
timeout "$timeout_s" "${cmd[@]}" </dev/null >"$raw" 2>"$log" || status=$?
if [ "$status" -ne 0 ]; then
  echo "run.sh: QEMU exited with status $status (124 = timed out after ${timeout_s}s)" >&2
  cat "$raw" "$log" >&2
  exit 1
fi

# --- merge the plugin's counts into the guest's lines -------------------------------------------
if ! awk -v counts="$counts" '
  BEGIN { n = 0; while ((getline l < counts) > 0) if (match(l, /instructions=[0-9]+/)) c[++n] = substr(l, RSTART + 13, RLENGTH - 13) }
  /instructions=\?/ { k++; if (k > n) { print "run.sh: more frames than counted pairs" > "/dev/stderr"; bad = 1; exit 1 } sub(/instructions=\?/, "instructions=" c[k]) }
  /^# pairs: / { if ($3 != "starts=" n || $4 != "stops=" n) { print "run.sh: guest made " $3 " " $4 " but the plugin counted " n " pairs" > "/dev/stderr"; bad = 1; exit 1 } }
  { print }
  END { if (!bad && k != n) { print "run.sh: " n " counted pairs for " k " frames" > "/dev/stderr"; exit 1 } }
' "$raw" >"$result"; then
  cat "$raw" "$log" >&2
  exit 1
fi
if grep -q '^error' "$result" || ! grep -q '^method=' "$result"; then
  echo "run.sh: the bench reported an error or no frame" >&2
  cat "$result" >&2
  exit 1
fi

# --- report -----------------------------------------------------------------------------------
grep '^method=' "$result"
grep '^# preset .*skipped' "$result" || true # presets in a format the bench does not draw yet
echo
echo "$label; $qemu_version"
awk '
  /^# calibration/ { split($NF, f, "="); cal = f[2] }
  /^# hash sink alone/ { split($NF, f, "="); sink = f[2] }
  /^method=/ {
    for (i = 1; i <= NF; i++) { split($i, f, "="); v[f[1]] = f[2] }
    if (!header) {
      printf "%-20s %-11s %-7s %5s %12s %17s %14s %15s %7s\n", "method", "scene", "format", "tris", "instructions", "est. ms @100 MHz*", "w/o hash ms**", "SPI ms @50 MHz", "ram B"
      header = 1
    }
    # 240x240 RGB565 = 921,600 bits; at 50 MHz: 18.432 ms.
    printf "%-20s %-11s %-7s %5d %12d %17.1f %14.1f %15.1f %7d\n", v["method"], v["scene"], v["format"], v["tris"], v["instructions"], v["instructions"] / 1e5, (v["instructions"] - sink) / 1e5, 240 * 240 * 16 / 50e6 * 1e3, v["ram"]
  }
  END {
    print "*  estimate: instructions / 100e6 s. Instructions are not cycles (wait states, multi-cycle"
    print "   loads and multiplies, divides and soft-float calls differ). Counts are exact guest"
    print "   instructions from the start marker to the stop marker (the markers: " cal " of them)."
    print "** the same less the bench sink'"'"'s FNV-1a hash of 240 rows (" sink " instructions measured"
    print "   alone): about the renderer'"'"'s own share; on the board the sink is the SPI transfer."
  }
' "$result"
