#!/usr/bin/env bash
# Builds both board firmwares and prints their flash and static RAM; fails past the budgets
# (the measured figures plus about 10 % where the chip leaves room: lower them when work
# lands, raise them only with a reason in the commit) or if a renderer's static is
# initialised from flash (`.data`) instead of zeroed (`.bss`), which would cost its size twice.
# The Blue Pill's budgets are its chip's: 64 KB of flash, and 20 KB of RAM less the stack its
# board-in-the-loop run measures (emu/board/run.sh: 3,048 bytes at its deepest, checked there
# against the statics on every run). Needs `size` and `nm` from binutils (any host build reads
# ARM ELF files).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"

# board name, directory, ELF, renderer symbol, flash budget, static RAM budget (bytes)
check() {
  local board="$1" dir="$2" elf="$3" renderer="$4" flash_budget="$5" ram_budget="$6"
  (cd "$root/$dir" && cargo build --release)
  elf="$root/$dir/$elf"
  read -r flash ram < <(size -A "$elf" | awk '
    $1 == ".vector_table" || $1 == ".text" || $1 == ".rodata" { flash += $2 }
    $1 == ".data" { flash += $2; ram += $2 }
    $1 == ".bss" || $1 == ".uninit" { ram += $2 }
    END { print flash, ram }')
  awk -v b="$board" -v f="$flash" -v r="$ram" -v fb="$flash_budget" -v rb="$ram_budget" 'BEGIN {
    printf "%s: flash %d bytes (%.1f KB of %.1f KB), static RAM %d bytes (%.1f KB of %.1f KB)\n",
      b, f, f / 1024, fb / 1024, r, r / 1024, rb / 1024 }'
  test "$flash" -le "$flash_budget" || { echo "error: $board flash over its budget" >&2; exit 1; }
  test "$ram" -le "$ram_budget" || { echo "error: $board static RAM over its budget" >&2; exit 1; }
  # The renderer must be zero-initialised (.bss: nm type b/B), not copied from flash (.data).
  local kind
  kind="$(nm -C "$elf" | awk -v s="$renderer" '$3 == s { print $2 }')"
  case "$kind" in
    b | B) echo "$board: the renderer is in .bss (zeroed at reset, not copied from flash)" ;;
    *) echo "error: $renderer is in section type '$kind', not .bss" >&2; exit 1 ;;
  esac
}

# The F411 (512 KB flash, 128 KB RAM): its demo, the three scenes' meshes included, in 64 KB
# of flash (65,212 bytes when set: the budget is the target, not the figure plus 10 %), and
# static RAM at the figure plus about 10 % (24,004 bytes when set).
check firmware firmware target/thumbv7em-none-eabihf/release/zrow-firmware \
  zrow_firmware::RENDERER $((64 * 1024)) $((26 * 1024))
# The Blue Pill (64 KB flash, 20 KB RAM).
check bluepill firmware/bluepill target/thumbv7m-none-eabi/release/zrow-bluepill \
  zrow_bluepill::RENDERER $((64 * 1024)) $((20 * 1024 - 3048))
