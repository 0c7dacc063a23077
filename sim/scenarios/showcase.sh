#!/usr/bin/env bash
# The README's showcase: the paper's figures made by the programs (twister-station on
# the simulator in virtual time, scripted buttons -> Unix-socket link ->
# twister-bridge --offscreen -> PNG; `twister replay` of the journal). Figure 8, the
# comparison of the warp methods, is `twister figure8` (docs/figure8.md).
#   sim/scenarios/showcase.sh WHAT [BUILD_DIR] [OUT_DIR]     (defaults: build docs/pictures)
# WHAT:
#   spork    Figure 1: spork-0-sphere.png, spork-1..5.png (the model after each stroke),
#            spork-live-2..5.png (the live warp of the strokes that turn: pink axes)
#   figure2  figure2.png: a flat sheet, one hand: translation; translation + rotation
#            about the translation; translation + screw about a perpendicular axis
#   figure3  figure3.png: two hands: translation only; with screws; bending
#   figure6  figure6-twist.png, figure6-bend.png (host/twister-bridge/figure6.sh)
#   figure9  figure9.png: three objects from a sphere (horn, mushroom, boat)
#   movie    spork.gif: the spork session as an animation (ImageMagick)
#   all      every one of the above, then the stamp: OUT_DIR/showcase.sha256 (the
#            generators' and scenarios' hashes the pictures were made from)
#   check    no program run: the committed pictures are not stale (the stamp matches
#            the generators and scenarios; gen_spork.py and gen_figures.py write the
#            committed scenarios) and each one passes the structural checks
# Every run must end with the station's, the display's and the replay's meshes equal
# (checksums), the scenario's @expect checks must hold (a grab point follows its hand;
# the surface around it turned by the hand's angle), and every picture must show a
# model (and the pink screw axis where a hand turned): sim/scenarios/picture_check.py.
set -euo pipefail
cd "$(dirname "$0")/../.."
what="${1:?usage: showcase.sh spork|figure2|figure3|figure6|figure9|movie|all|check [BUILD_DIR] [OUT_DIR]}"
build="${2:-build}"
out="${3:-docs/pictures}"
mkdir -p "$out"
work="$(mktemp -d)"
trap '[[ -n "${TWISTER_KEEP:-}" ]] || rm -rf "$work"' EXIT
export EGL_PLATFORM=surfaceless
unset DISPLAY WAYLAND_DISPLAY
scn=sim/scenarios
size=400x300
for tool in convert montage identify; do
  command -v "$tool" > /dev/null || { echo "showcase: $tool missing (apt-get install imagemagick; make deps)" >&2; exit 1; }
done

die() { echo "showcase: $*" >&2; exit 1; }

# run SCENARIO NAME [run_scenario options]: checksums and @expect checks, or fail.
run() {
  local scenario="$1" name="$2"
  shift 2
  if ! python3 "$scn/run_scenario.py" "$scenario" --bin "$build/bin" --out "$work/$name" \
      --bridge --size "$size" "$@" > "$work/$name.txt"; then
    cat "$work/$name.txt" >&2
    die "$name: a program failed, the checksums differ or a check failed"
  fi
  grep '^check ' "$work/$name.txt" | sed "s/^/  $name: /" || true
}

# check PICTURE [picture_check options]
check() { python3 "$scn/picture_check.py" "$@" > /dev/null || python3 "$scn/picture_check.py" "$@" >&2 || die "$1"; }

spork() {
  run "$scn/spork.scn" spork --no-hud
  local pics="$work/spork/pictures"
  check "$pics/rest.png"
  cp "$pics/rest.png" "$out/spork-0-sphere.png"
  for k in 1 2 3 4 5; do
    check "$pics/commit-$((k + 1)).png"
    cp "$pics/commit-$((k + 1)).png" "$out/spork-$k.png"
  done
  # Strokes 2 to 5 turn the hands (45, 50, 60, 60 degrees): their live pictures show
  # the screw axes in pink, along each axis where the display projected it.
  for k in 2 3 4 5; do
    check "$pics/live-$((k + 1)).png" --pink 100 --yellow 20 --cues "$pics/live-$((k + 1)).cues"
    cp "$pics/live-$((k + 1)).png" "$out/spork-live-$k.png"
  done
  echo "$out/spork-{0-sphere,1,2,3,4,5}.png $out/spork-live-{2,3,4,5}.png"
}

# row OUT NAME:CAPTION:PINK... : each scenario's live picture (with cues), captioned.
row() {
  local target="$1"
  shift
  local tiles=()
  for spec in "$@"; do
    IFS=: read -r name caption pink <<< "$spec"
    run "$scn/figures/$name.scn" "$name" --no-hud
    local pic="$work/$name/pictures/live-2.png"
    check "$pic" --pink "$pink" --yellow 20
    tiles+=(-label "$caption" "$pic")
  done
  montage -font DejaVu-Sans -pointsize 14 -fill '#e8e8e8' -background '#202229' \
    "${tiles[@]}" -tile "$#x1" -geometry +2+2 "$target"
  check "$target"
  echo "$target"
}

figure2() {
  row "$out/figure2.png" "figure2_translate:translation along OO':0" \
    "figure2_twist:+ rotation about OO' (90 degrees):100" \
    "figure2_screw:+ screw about an axis perpendicular to OO' (60):100"
}

figure3() {
  row "$out/figure3.png" "figure3_translate:translation only:0" \
    "figure3_screws:translation and screws (40 degrees):100" \
    "figure3_bend:bending with two hands (+45 / -45):100"
}

figure9() {
  local tiles=()
  for spec in "figure9_horn:a horn (2 strokes)" "figure9_mushroom:a mushroom (2 strokes)" \
      "figure9_boat:a boat (2 strokes)"; do
    IFS=: read -r name caption <<< "$spec"
    run "$scn/figures/$name.scn" "$name" --plain
    check "$work/$name/pictures/final.png"
    tiles+=(-label "$caption" "$work/$name/pictures/final.png")
  done
  montage -font DejaVu-Sans -pointsize 14 -fill '#e8e8e8' -background '#202229' \
    "${tiles[@]}" -tile 3x1 -geometry +2+2 "$out/figure9.png"
  check "$out/figure9.png"
  echo "$out/figure9.png"
}

figure6() {
  host/twister-bridge/figure6.sh "$build" "$out" > /dev/null
  check "$out/figure6-twist.png" --pink 100
  check "$out/figure6-bend.png" --pink 100
  echo "$out/figure6-twist.png $out/figure6-bend.png"
}

# The spork session at 320x240: a frame every 12th hands update (the station sends at
# most one per 8 ms of its clock, so about one frame per 0.1 s of motion), 10 frames a
# second, the last frame held 2 s; under 3 MB.
movie() {
  size=320x240
  run "$scn/spork.scn" movie --no-hud --movie-every 12
  size=400x300
  local frames=("$work/movie/pictures"/frame-*.png)
  (( ${#frames[@]} >= 100 )) || die "movie: only ${#frames[@]} frames"
  check "${frames[-1]}"
  convert -delay 10 -loop 0 "${frames[@]}" -delay 200 "$work/movie/pictures/final.png" \
    -fuzz 2% -layers Optimize "$out/spork.gif"
  local bytes
  bytes="$(stat -c %s "$out/spork.gif")"
  (( bytes < 3000000 )) || die "movie: $out/spork.gif is $bytes bytes (>= 3 MB)"
  echo "$out/spork.gif (${#frames[@]} frames, $bytes bytes)"
}

# What the pictures are made from (the programs aside: their own tests cover them).
inputs() {
  printf '%s\n' "$scn/showcase.sh" "$scn/gen_spork.py" "$scn/spork.scn" "$scn/gen_figures.py" \
    "$scn"/figures/*.scn host/twister-bridge/figure6.sh host/twister-bridge/figure6/*.scn
}
pictures=(spork-0-sphere.png spork-{1,2,3,4,5}.png spork-live-{2,3,4,5}.png figure2.png
  figure3.png figure6-twist.png figure6-bend.png figure9.png spork.gif)

stamp() {
  inputs | xargs sha256sum > "$out/showcase.sha256"
  echo "$out/showcase.sha256"
}

check_current() {
  local stale=0
  if ! sha256sum --check --quiet "$out/showcase.sha256"; then
    echo "showcase: pictures in $out are stale: a generator or scenario changed since" \
      "they were made (sim/scenarios/showcase.sh all)" >&2
    stale=1
  fi
  if ! diff <(inputs | sort) <(awk '{print $2}' "$out/showcase.sha256" | sort) > /dev/null; then
    echo "showcase: the stamp does not list the current inputs (sim/scenarios/showcase.sh all)" >&2
    stale=1
  fi
  python3 "$scn/gen_spork.py" > "$work/spork.scn"
  diff -q "$work/spork.scn" "$scn/spork.scn" > /dev/null ||
    { echo "showcase: spork.scn differs from what gen_spork.py writes" >&2; stale=1; }
  python3 "$scn/gen_figures.py" "$work/figures"
  diff -qr "$work/figures" "$scn/figures" > /dev/null ||
    { echo "showcase: sim/scenarios/figures/ differs from what gen_figures.py writes" >&2; stale=1; }
  for p in "${pictures[@]}"; do
    [[ -s "$out/$p" ]] || { echo "showcase: $out/$p missing" >&2; stale=1; continue; }
    case "$p" in
      spork-live-* | figure6-*) check "$out/$p" --pink 100 ;;
      *.gif) check "${out}/${p}[0]" ;;
      *) check "$out/$p" ;;
    esac
  done
  (( $(stat -c %s "$out/spork.gif") < 3000000 )) || { echo "showcase: spork.gif >= 3 MB" >&2; stale=1; }
  (( stale == 0 )) || exit 1
  echo "showcase: ${#pictures[@]} pictures in $out are current"
}

case "$what" in
  spork | figure2 | figure3 | figure6 | figure9 | movie) "$what" ;;
  all)
    for w in spork figure2 figure3 figure6 figure9 movie; do "$w"; done
    stamp
    ;;
  check) check_current ;;
  *) die "unknown picture '$what'" ;;
esac
