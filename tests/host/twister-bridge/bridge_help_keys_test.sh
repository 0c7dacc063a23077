#!/bin/sh
# twister-bridge --help lists every key (issue 25): the camera's, H, Tab, C and the
# command keys Z, Y, M, S, N, U, each on its own line; and the --hud and --spectator options.
set -eu
bin="$1/bin/twister-bridge"
out=$("$bin" --help)
for key in Z Y M S N U H Tab C; do
  printf '%s\n' "$out" | grep -q "^  $key  " || { echo "key $key not in --help"; exit 1; }
done
for option in --hud --spectator; do
  printf '%s\n' "$out" | grep -q -- "$option" || { echo "$option not in --help"; exit 1; }
done
echo "twister-bridge --help lists every key"
