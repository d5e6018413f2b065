#!/usr/bin/env bash
# The emulated bench's instruction budget: one ceiling per frame line, checked in as
# emu/budget-CPU.txt. Instruction counts under QEMU repeat exactly, so this is a count check,
# not a timed test.
#
# usage: emu/budget.sh check  [m4|m3]   fails if a frame exceeds its ceiling by more than 1 %,
#                                        or has no ceiling (default m4)
#        emu/budget.sh update [m4|m3]   rewrites the ceilings from the last run (after work
#                                        that lowers them lands; raising one needs a reason in
#                                        the commit)
#
# Reads emu/target/bench-CPU.txt, which emu/run.sh writes (emu/check.sh runs both).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mode="${1:-check}"
cpu="${2:-m4}"
result="$here/target/bench-$cpu.txt"
budget="$here/budget-$cpu.txt"
if [ ! -s "$result" ]; then
  echo "budget.sh: no bench output ($result): run emu/run.sh $cpu first" >&2
  exit 1
fi

# One "method scene format instructions" line per frame, in bench order.
frames="$(awk '/^method=/ {
  for (i = 1; i <= NF; i++) { split($i, f, "="); v[f[1]] = f[2] }
  print v["method"], v["scene"], v["format"], v["instructions"]
}' "$result")"

case "$mode" in
  update)
    {
      echo "# Instruction ceilings of the emulated bench ($cpu): method scene format ceiling."
      echo "# emu/budget.sh check fails when a frame exceeds its ceiling by more than 1 %."
      echo "# Written by emu/budget.sh update from a run of emu/run.sh $cpu; lower them when work lands."
      echo "$frames"
    } >"$budget"
    echo "budget.sh: wrote $(echo "$frames" | wc -l) ceilings to $budget"
    ;;
  check)
    if [ ! -s "$budget" ]; then
      echo "budget.sh: no budget file $budget (emu/budget.sh update $cpu writes one)" >&2
      exit 1
    fi
    echo "$frames" | awk -v budget="$budget" '
      BEGIN {
        while ((getline l < budget) > 0) {
          if (l ~ /^#/ || l == "") continue
          split(l, f, " "); ceiling[f[1] " " f[2] " " f[3]] = f[4]
        }
      }
      {
        key = $1 " " $2 " " $3; n++
        if (!(key in ceiling)) { printf "budget: %s has no ceiling (emu/budget.sh update)\n", key; bad++; next }
        c = ceiling[key]
        if ($4 > c * 1.01) {
          printf "budget: %s: %d instructions, %.2f %% over its ceiling %d\n", key, $4, ($4 / c - 1) * 100, c
          bad++
        } else if ($4 < c * 0.95) {
          printf "budget: %s: %d instructions, %.1f %% under its ceiling %d (lower it: emu/budget.sh update)\n", key, $4, (1 - $4 / c) * 100, c
        }
      }
      END {
        printf "budget: %d frames, %d over their ceiling by more than 1 %% or without one\n", n, bad
        exit bad > 0
      }'
    ;;
  *)
    echo "usage: $0 check|update [m4|m3]" >&2
    exit 2
    ;;
esac
