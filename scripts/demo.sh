#!/usr/bin/env bash
# Opens the simulator window (README "Run"). Installs SDL2's development files first if they
# are missing (apt-get, through sudo only when not root, so it works as root in a container as
# well as a user on a desktop). Without a display the simulator says so in one line and writes
# zrow-demo.png instead. Arguments go to the simulator (e.g. `--model assets/models/torus.off`).
set -euo pipefail
cd "$(dirname "$0")/.."
if ! [ -e /usr/include/SDL2/SDL.h ]; then
  if [ "$(id -u)" -eq 0 ]; then sudo_=""; else sudo_="sudo"; fi
  $sudo_ apt-get update -qq
  $sudo_ env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libsdl2-dev
fi
# Its own target directory: the window build turns on features the headless commands leave
# off, and sharing one directory would rebuild the simulator at every switch between them.
exec env CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-target/window}" \
  cargo run --release -p zrow-sim --features window -- "$@"
