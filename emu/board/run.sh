#!/usr/bin/env bash
# Board in the loop: boots the shipped F411 firmware ELF (firmware/, the image `cargo run
# --release` flashes) in the Unicorn engine with a model of the STM32F411 peripherals it uses
# (emu/board/f411.py), decodes what it clocks out of SPI through the ST7789 panel model, checks
# every frame against the host's render of the same demo frame bit for bit, and prints the
# estimated frames per second per demo scene (instructions taken as cycles at 100 MHz) and the
# stack's deepest point. Then the same for the Blue Pill's firmware (firmware/bluepill,
# emu/board/f103.py: a Cortex-M3 at 72 MHz with 20 KB of SRAM; a stack that reaches the
# statics fails the run).
#
# Then the same check must FAIL on deliberately broken firmware, built from copies of firmware/
# with one change each (so the check is known to catch them):
#   dc-polarity    command bytes sent with DC high and parameters with DC low;
#   half-row       each row handed to DMA with only its first half encoded (the buffer handed
#                  over before it is full: the rest is stale);
#   no-inversion   the panel's colour inversion (INVON) left out of its initialisation.
#
# Between them, the F411's first frame of each scene again with `--profile`: the cycles each
# function of the shipped ELF took (profile.txt; board.py says how).
#
# usage: emu/board/run.sh [FRAMES_PER_SCENE]   (default 3: 9 frames, the three demo scenes)
# Writes target/board/: the stream files, shipped.txt and bluepill.txt (the tables),
# profile.txt, the mutants' logs.
# Installs python3 and python3-venv with apt-get if missing, and Unicorn, capstone and
# pyelftools (pinned)
# into emu/board/.venv from PyPI.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
per_scene="${1:-3}"
frames=$((3 * per_scene))
# Outside emu/ (whose .cargo/config.toml would add its link flags to the mutants' builds).
out="$root/target/board"
mkdir -p "$out"

sudo_="$( [ "$(id -u)" = 0 ] || echo sudo )"
if ! command -v python3 >/dev/null 2>&1; then
  $sudo_ apt-get update -qq
  $sudo_ env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3 python3-venv >/dev/null
fi
venv="$here/.venv"
if ! "$venv/bin/python" -c 'import unicorn, capstone, elftools' 2>/dev/null; then
  rm -rf "$venv"
  # Debian's python3 makes venvs only with python3-venv installed (ensurepip's wheels).
  if ! python3 -m venv "$venv" >/dev/null 2>&1; then
    $sudo_ apt-get update -qq
    $sudo_ env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-venv >/dev/null
    rm -rf "$venv"
    python3 -m venv "$venv"
  fi
  "$venv/bin/pip" install --quiet --disable-pip-version-check \
    unicorn==2.1.4 capstone==5.0.7 pyelftools==0.33
fi
py="$venv/bin/python"

(cd "$root" && cargo build --release -q -p zrow-st7789 --example replay)
replay="$root/target/release/examples/replay"

# Boots the release ELF of the firmware in directory $1 (package $4, built into target
# directory $3) and checks its frames; the replay's table on stdout. Status 3: it does not
# build.
check() { # dir name target-dir package
  local dir="$1" name="$2" target="$3" package="$4"
  (cd "$dir" && CARGO_TARGET_DIR="$target" cargo build --release -q) || return 3
  local elf="$target/thumbv7em-none-eabihf/release/$package"
  "$py" "$here/f411.py" "$elf" "$out/$name.stream" --frames-per-scene "$per_scene" \
    --frames "$frames" || return 1
  "$replay" "$out/$name.stream"
}

echo "== the peripheral model refuses what it does not model"
(cd "$root/firmware" && cargo build --release -q)
"$py" "$here/f411.py" "$root/firmware/target/thumbv7em-none-eabihf/release/zrow-firmware" --self-test

echo "== the shipped firmware: $frames frames, $per_scene per demo scene"
# Its table is kept for scripts/check-figures.sh (the README quotes it).
# Its own target directory: the ELF `cargo run --release` flashes.
check "$root/firmware" shipped "$root/firmware/target" zrow-firmware | tee "$out/shipped.txt"

echo "== where the shipped F411's cycles go: a frame of each demo scene, by function (--profile)"
"$py" "$here/f411.py" "$root/firmware/target/thumbv7em-none-eabihf/release/zrow-firmware" \
  "$out/profile.stream" --frames-per-scene 1 --frames 3 --profile 20 | tee "$out/profile.txt"
# The blocks are charged to the functions they are in: the renderer's sweep is among the first.
grep -q '^ .*zrow::scanline::Sweep<.*>::resolve_row$' "$out/profile.txt" ||
  { echo "error: the profile does not name the scan-line renderer's resolve_row" >&2; exit 1; }

echo "== the Blue Pill (STM32F103C8): its shipped firmware, $((2 * per_scene)) frames of its two scenes"
bluepill="$root/firmware/bluepill"
(cd "$bluepill" && cargo build --release -q)
bp_elf="$bluepill/target/thumbv7m-none-eabi/release/zrow-bluepill"
"$py" "$here/f103.py" "$bp_elf" --self-test
# Its table and stack peak are kept for scripts/check-figures.sh (the README quotes them).
{ "$py" "$here/f103.py" "$bp_elf" "$out/bluepill.stream" --frames-per-scene "$per_scene" \
    --frames $((2 * per_scene)) --scenes interlocked,cube &&
  "$replay" "$out/bluepill.stream"; } | tee "$out/bluepill.txt"

fail=0
mutant() { # name, then a python snippet editing the text of file $2 in the copy
  local name="$1" file="$2" edit="$3"
  local copy="$out/mutant-$name"
  rm -rf "$copy" && mkdir -p "$copy"
  cp -r "$root/firmware/src" "$root/firmware/Cargo.toml" "$root/firmware/Cargo.lock" \
    "$root/firmware/build.rs" "$root/firmware/.cargo" "$root/firmware/demo" "$copy/"
  # The row sink's crate is copied too (the mutations below edit it); every other path in
  # the copies' manifests points back at the repository's crates.
  cp -r "$root/crates/zrow-st7789" "$copy/zrow-st7789"
  rm -rf "$copy/zrow-st7789/target"
  sed -i "s#path = \"\\.\\./crates/zrow-st7789\"#path = \"zrow-st7789\"#; s#path = \"\\.\\./#path = \"$root/#g" "$copy/Cargo.toml"
  sed -i "s#path = \"\\.\\./\\.\\./crates/zrow-st7789\"#path = \"../zrow-st7789\"#; s#path = \"\\.\\./\\.\\./#path = \"$root/#g" "$copy/demo/Cargo.toml"
  # Outside the repository's workspace: what it inherits from there, spelled out.
  "$py" - "$root" "$copy/zrow-st7789/Cargo.toml" <<'PY'
import re, sys
root, path = sys.argv[1], sys.argv[2]
# `key = value` lines of the workspace's [workspace.package] and [workspace.dependencies]
# (plain lines: no TOML library needed on any Python 3), paths made absolute.
values, section = {}, None
for line in open(f"{root}/Cargo.toml"):
    line = line.strip()
    if line.startswith("["):
        section = line
    elif section in ("[workspace.package]", "[workspace.dependencies]") and " = " in line:
        key, value = line.split(" = ", 1)
        values[key] = value.replace('path = "', f'path = "{root}/')
text = open(path).read()
text = re.sub(r"^([\w-]+)\.workspace = true$", lambda m: f"{m[1]} = {values[m[1]]}", text,
              flags=re.M)
open(path, "w").write(text)
PY
  sed -i "s#\"\\.\\./memory.x\"#\"$root/memory.x\"#g" "$copy/build.rs"
  # Built in the shipped firmware's target directory, whose dependencies (the HAL, the
  # renderer: minutes of compiling from cold) it shares, under another package name so that
  # the shipped ELF is not overwritten.
  sed -i 's/^name = "zrow-firmware"$/name = "zrow-firmware-mutant"/' "$copy/Cargo.toml"
  grep -q '^name = "zrow-firmware-mutant"$' "$copy/Cargo.toml" ||
    { echo "error: the mutant's package rename does not apply" >&2; exit 1; }
  "$py" - "$copy/$file" "$edit" <<'PY'
import sys
path, edit = sys.argv[1], sys.argv[2]
old, new = edit.split("=>", 1)
text = open(path).read()
if old not in text:
    sys.exit(f"mutation does not apply: {old!r} not in {path}")
open(path, "w").write(text.replace(old, new, 1))
PY
  echo "== mutant $name: the check must fail"
  local rc=0
  # Each copy is fresh, so each build relinks its ELF.
  check "$copy" "mutant-$name" "$root/firmware/target" zrow-firmware-mutant \
    >"$out/mutant-$name.log" 2>&1 || rc=$?
  if [ "$rc" = 0 ]; then
    echo "error: mutant $name passed the check" >&2
    fail=1
  elif [ "$rc" = 3 ]; then
    echo "error: mutant $name does not build (see $out/mutant-$name.log)" >&2
    fail=1
  else
    echo "caught: $(grep -m1 -E 'error|differ|protocol|panel ends' "$out/mutant-$name.log" || tail -1 "$out/mutant-$name.log")"
  fi
}
mutant dc-polarity zrow-st7789/src/dma.rs \
  'dc.set_low()?;=>dc.set_high()?;'
mutant half-row zrow-st7789/src/dma.rs \
  'let (_, signature) = encode_row_signed(row.color, buf);=>let (_, signature) = encode_row_signed(row.color, buf); crate::encode_row(&[zrow::pixelcolor::Rgb565::new(0, 0, 0); 120], &mut buf[240..]);'
mutant no-inversion demo/src/lib.rs \
  '.invert_colors(ColorInversion::Inverted)=>'

# The Blue Pill's stack check must catch a stack that reaches the statics: a copy whose RAM
# (its memory.x) holds its statics and only half the stack the shipped frames took, so the
# stack must run into them (however large the renderer grows or shrinks).
echo "== mutant bluepill-stack: the check must fail"
copy="$out/mutant-bluepill-stack"
rm -rf "$copy" && mkdir -p "$copy"
cp -r "$bluepill/src" "$bluepill/Cargo.toml" "$bluepill/Cargo.lock" "$bluepill/build.rs" \
  "$bluepill/memory.x" "$bluepill/.cargo" "$copy/"
sed -i "s#path = \"\\.\\./\\.\\./#path = \"$root/#g; s#path = \"\\.\\./demo\"#path = \"$root/firmware/demo\"#" \
  "$copy/Cargo.toml"
peak=$(sed -n 's/.* stack peak \([0-9]*\) bytes$/\1/p' "$out/bluepill.txt")
# The statics end at cortex-m-rt's `_stack_end` (the stack's floor), counted from RAM's origin.
statics=$("$py" - "$bp_elf" <<'PY'
import sys
from elftools.elf.elffile import ELFFile
symbols = ELFFile(open(sys.argv[1], "rb")).get_section_by_name(".symtab")
print(next(s["st_value"] for s in symbols.iter_symbols() if s.name == "_stack_end") - 0x2000_0000)
PY
)
[ -n "$peak" ] && [ "$peak" -gt 0 ] || { echo "error: no stack peak in $out/bluepill.txt" >&2; exit 1; }
ram=$(( (statics + peak / 2 + 7) / 8 * 8 ))
sed -i "s/LENGTH = 20K/LENGTH = $ram/" "$copy/memory.x"
grep -q "LENGTH = $ram\$" "$copy/memory.x" || { echo "error: the mutation does not apply" >&2; exit 1; }
# In the shipped Blue Pill firmware's target directory under another name, as above.
sed -i 's/^name = "zrow-bluepill"$/name = "zrow-bluepill-mutant"/' "$copy/Cargo.toml"
grep -q '^name = "zrow-bluepill-mutant"$' "$copy/Cargo.toml" ||
  { echo "error: the mutant's package rename does not apply" >&2; exit 1; }
if ! (cd "$copy" && CARGO_TARGET_DIR="$bluepill/target" cargo build --release -q) \
  >"$out/mutant-bluepill-stack.log" 2>&1; then
  echo "error: mutant bluepill-stack does not build (see $out/mutant-bluepill-stack.log)" >&2
  fail=1
elif "$py" "$here/f103.py" "$bluepill/target/thumbv7m-none-eabi/release/zrow-bluepill-mutant" \
  "$out/mutant-bluepill-stack.stream" --frames-per-scene 1 --frames 2 --scenes interlocked,cube \
  >>"$out/mutant-bluepill-stack.log" 2>&1; then
  echo "error: mutant bluepill-stack passed the check" >&2
  fail=1
else
  echo "caught: $(grep -m1 'stack ran into' "$out/mutant-bluepill-stack.log" || tail -1 "$out/mutant-bluepill-stack.log")"
fi
exit "$fail"
