#!/usr/bin/env bash
# Builds the board firmware and prints its flash and static RAM; fails past the limits
# (issue 4: static RAM 64 KB, flash 256 KB). Needs `size` from binutils (any host build reads
# ARM ELF section headers).
set -euo pipefail
cd "$(dirname "$0")/../firmware"
cargo build --release
elf=target/thumbv7em-none-eabihf/release/zrow-firmware
read -r flash ram < <(size -A "$elf" | awk '
  $1 == ".vector_table" || $1 == ".text" || $1 == ".rodata" { flash += $2 }
  $1 == ".data" { flash += $2; ram += $2 }
  $1 == ".bss" || $1 == ".uninit" { ram += $2 }
  END { print flash, ram }')
awk -v f="$flash" -v r="$ram" 'BEGIN {
  printf "firmware: flash %d bytes (%.1f KB of 256 KB), static RAM %d bytes (%.1f KB of 64 KB)\n",
    f, f / 1024, r, r / 1024 }'
test "$flash" -le $((256 * 1024)) || { echo "error: flash over 256 KB" >&2; exit 1; }
test "$ram" -le $((64 * 1024)) || { echo "error: static RAM over 64 KB" >&2; exit 1; }
