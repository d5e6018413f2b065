#!/usr/bin/env bash
# Time and peak memory of the host simulator and converter by model size, on generated tori
# (host-sim/examples/torus.rs; nothing large is committed). Prints a Markdown table; every row
# also checks that the scan-line frame equals the z-buffer's (bit for bit, as PNG).
#
#   bash scripts/host-scale.sh [TRIANGLES ...]     (default: 20000 200000 1000000)
#
# Wall-clock seconds and peak resident memory come from GNU time on this machine (installed
# when missing); they are figures of the machine that runs the script, not budgets.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! [ -x /usr/bin/time ]; then
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo=sudo
  $sudo apt-get install -y -qq time >/dev/null
fi
sizes=("$@"); [ ${#sizes[@]} -gt 0 ] || sizes=(20000 200000 1000000)
cargo build --release -q -p zrow-sim --bin zrow-sim --example torus
bin=target/release/zrow-sim
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
measure() { # label, command... -> "seconds s / MB MB"
  /usr/bin/time -f "%e %M" -o "$tmp/time" "$@" >/dev/null 2>"$tmp/err" || { cat "$tmp/err" >&2; exit 1; }
  read -r s kb <"$tmp/time"
  printf '%s s / %d MB' "$s" $((kb / 1024))
}
echo "| triangles | OFF file | scanline | zbuffer | auto | convert | scanline = zbuffer |"
echo "|---|---|---|---|---|---|---|"
for n in "${sizes[@]}"; do
  off="$tmp/t$n.off"
  target/release/examples/torus "$n" "$off" >/dev/null
  tris=$(sed -n 2p "$off" | cut -d' ' -f2)
  mb=$(awk -v b="$(stat -c %s "$off")" 'BEGIN { printf "%.1f", b / 1e6 }')
  row="| $tris | $mb MB |"
  for algo in scanline zbuffer auto; do
    row+=" $(measure $bin render-model --model "$off" --algo "$algo" --size 240x240 --out "$tmp/$algo.png") |"
  done
  if [ "$(sed -n 2p "$off" | cut -d' ' -f1)" -le 65536 ]; then
    row+=" $(measure $bin convert --model "$off" --out "$tmp/m.rs") |"
  else
    row+=" (more than 65,536 vertices: the firmware's u16 indices) |"
  fi
  if cmp -s "$tmp/scanline.png" "$tmp/zbuffer.png"; then row+=" yes |"; else row+=" **no** |"; fi
  echo "$row"
done
