#!/usr/bin/env bash
# CI's check of the emulated bench: every frame the Cortex-M renders under QEMU must hash the
# same as the host's render of the same scene, format and method or preset (same core,
# different instruction set; docs/extremes.md item 22).
#
# usage: emu/check.sh [m4|m3]      (default m4)
#
# Runs emu/run.sh (which prints the bench lines and the table), computes the host's lines with
# emu/host_hash, and compares method, scene, format, face count and frame hash line by line (ram= is the
# guest's alone: table entries may be laid out differently on a 64-bit host). Then checks every
# frame's instruction count against its ceiling in emu/budget-CPU.txt (emu/budget.sh: more than
# 1 % over fails). Exits non-zero on any difference, on a missing frame, on a frame over its
# ceiling, or if either side fails.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cpu="${1:-m4}"

bash "$here/run.sh" "$cpu"

host_dir="$here/host_hash"
host="$here/target/host-hashes.txt"
emu="$here/target/emu-hashes-$cpu.txt"
# cd so host_hash/.cargo/config.toml (build.target = host-tuple) overrides the bench's thumb
# default; its own target dir, as in run.sh.
(cd "$host_dir" && cargo run --release --quiet --target-dir "$host_dir/target") >"$host"
awk '/^method=/ {
  for (i = 1; i <= NF; i++) { split($i, f, "="); v[f[1]] = f[2] }
  printf "method=%s scene=%s format=%s tris=%s hash=%s\n", v["method"], v["scene"], v["format"], v["tris"], v["hash"]
}' "$here/target/bench-$cpu.txt" >"$emu"

echo
frames="$(wc -l <"$host")"
if [ "$frames" -eq 0 ]; then
  echo "check.sh: the host printed no frame" >&2
  exit 1
fi
if diff -u --label "host" --label "emulated $cpu" "$host" "$emu"; then
  echo "emulated $cpu frames equal the host's: $frames frames (method, scene, format, tris, hash)"
  echo "emu-check: $frames passed, 0 failed"
else
  failed="$(diff "$host" "$emu" | grep -c '^>' || true)"
  echo "check.sh: emulated $cpu frame hashes differ from the host's (above)" >&2
  echo "emu-check: $((frames - failed)) passed, $failed failed"
  exit 1
fi

# The instruction budget: every frame within 1 % of its checked-in ceiling.
echo
bash "$here/budget.sh" check "$cpu"
