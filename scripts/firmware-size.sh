#!/usr/bin/env bash
# Builds the board firmware and prints its flash and static RAM; fails past the budgets (the
# measured figures plus about 10 %: lower them when work lands, raise them only with a reason in
# the commit) or if the renderer's static is initialised from flash (`.data`) instead of zeroed
# (`.bss`), which would cost its size twice. Needs `size` and `nm` from binutils (any host build
# reads ARM ELF files).
set -euo pipefail
cd "$(dirname "$0")/../firmware"
cargo build --release
elf=target/thumbv7em-none-eabihf/release/zrow-firmware
read -r flash ram < <(size -A "$elf" | awk '
  $1 == ".vector_table" || $1 == ".text" || $1 == ".rodata" { flash += $2 }
  $1 == ".data" { flash += $2; ram += $2 }
  $1 == ".bss" || $1 == ".uninit" { ram += $2 }
  END { print flash, ram }')
# The budgets: the figures measured when they were last set, plus about 10 % (the README quotes
# the current figures; scripts/check-figures.sh keeps them true).
flash_budget=$((84 * 1024))
ram_budget=$((29 * 1024))
awk -v f="$flash" -v r="$ram" -v fb="$flash_budget" -v rb="$ram_budget" 'BEGIN {
  printf "firmware: flash %d bytes (%.1f KB of %d KB), static RAM %d bytes (%.1f KB of %d KB)\n",
    f, f / 1024, fb / 1024, r, r / 1024, rb / 1024 }'
test "$flash" -le "$flash_budget" || { echo "error: flash over $((flash_budget / 1024)) KB" >&2; exit 1; }
test "$ram" -le "$ram_budget" || { echo "error: static RAM over $((ram_budget / 1024)) KB" >&2; exit 1; }
# The renderer must be zero-initialised (.bss: nm type b/B), not copied from flash (.data: d/D).
kind="$(nm -C "$elf" | awk '$3 == "zrow_firmware::RENDERER" { print $2 }')"
case "$kind" in
  b | B) echo "firmware: the renderer is in .bss (zeroed at reset, not copied from flash)" ;;
  *) echo "error: zrow_firmware::RENDERER is in section type '$kind', not .bss" >&2; exit 1 ;;
esac
