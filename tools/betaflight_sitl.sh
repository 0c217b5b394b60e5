#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Build Betaflight's SITL in lockstep from a user's Betaflight checkout.
# docs/betaflight-sitl.md explains the build, the hook edits, the CLI file and the protocol.
set -euo pipefail

usage() {
    cat <<'EOF'
Usage: tools/betaflight_sitl.sh CHECKOUT OUTDIR [--ladrc --ladrc-params FILE] [--cli FILE]...

Builds Betaflight's SITL (make TARGET=SITL) in lockstep with a simulator:
one motor packet per FDM packet, micros()/millis() following the packets'
timestamps, so that two runs fed the same packets give the same motor outputs.

  CHECKOUT    a Betaflight source tree (git clone with the libcanard submodule,
              lib/modules/dronecan/libcanard, checked out); it is only read
  OUTDIR      created if missing; receives
                tree/                 the build copy (sources + our hook edits)
                betaflight_SITL.elf   the lockstep SITL
                eeprom.bin            its configuration (tools/betaflight/sitl.cli)
                sitl_config.cli       the CLI lines loaded into eeprom.bin
                BUILD_INFO            the checkout's commit and the build options
  --ladrc     add the ladrc library as the rate controller with
              integrations/betaflight/apply.sh TREE LADRC_REPO_ROOT PARAMS_FILE
  --ladrc-params FILE
              the airframe's rate-loop parameters for --ladrc (required with it;
              e.g. integrations/betaflight/params/paper_quadp.params)
  --cli FILE  more CLI lines, loaded after tools/betaflight/sitl.cli (repeatable;
              e.g. tools/betaflight/adrc_fork.cli for the ADRC fork of Betaflight)

Then run the SITL in OUTDIR (it reads eeprom.bin from its working directory):
  (cd OUTDIR && ./betaflight_SITL.elf)
and check it with /usr/bin/python3 tools/betaflight_sitl_check.py --launch OUTDIR.
Environment: JOBS (make -j, default 2).
EOF
}

die() {
    echo "betaflight_sitl.sh: $*" >&2
    exit 1
}

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO_ROOT="$(cd "$HERE/.." && pwd)"
TREE_MARKER=".betaflight_sitl_tree"

checkout=""
outdir=""
ladrc=0
ladrc_params=""
extra_cli=()
while [ $# -gt 0 ]; do
    case "$1" in
    -h | --help)
        usage
        exit 0
        ;;
    --ladrc)
        ladrc=1
        ;;
    --ladrc-params)
        [ $# -ge 2 ] || { usage >&2; echo "betaflight_sitl.sh: --ladrc-params needs a FILE" >&2; exit 2; }
        [ -f "$2" ] || { echo "betaflight_sitl.sh: --ladrc-params $2: no such file" >&2; exit 2; }
        ladrc_params="$(cd "$(dirname "$2")" && pwd)/$(basename "$2")"
        shift
        ;;
    --cli)
        [ $# -ge 2 ] || { usage >&2; echo "betaflight_sitl.sh: --cli needs a FILE" >&2; exit 2; }
        [ -f "$2" ] || { echo "betaflight_sitl.sh: --cli $2: no such file" >&2; exit 2; }
        extra_cli+=("$(cd "$(dirname "$2")" && pwd)/$(basename "$2")")
        shift
        ;;
    -*)
        usage >&2
        echo "betaflight_sitl.sh: unknown option $1" >&2
        exit 2
        ;;
    *)
        if [ -z "$checkout" ]; then
            checkout="$1"
        elif [ -z "$outdir" ]; then
            outdir="$1"
        else
            usage >&2
            echo "betaflight_sitl.sh: one CHECKOUT and one OUTDIR, got a third argument: $1" >&2
            exit 2
        fi
        ;;
    esac
    shift
done
if [ -z "$checkout" ] || [ -z "$outdir" ]; then
    usage >&2
    exit 2
fi
[ -d "$checkout" ] || { echo "betaflight_sitl.sh: CHECKOUT $checkout: not a directory" >&2; exit 2; }
checkout="$(cd "$checkout" && pwd)"

# What the SITL build reads from the checkout.
for need in Makefile mk src/main src/platform/SIMULATOR/sitl.c lib/main/MAVLink lib/main/dyad lib/main/google; do
    [ -e "$checkout/$need" ] || die "$checkout/$need: not found: CHECKOUT must be a Betaflight source tree with a SITL target"
done
[ -f "$checkout/lib/modules/dronecan/libcanard/canard.c" ] ||
    die "$checkout/lib/modules/dronecan/libcanard/canard.c: not found: check out the submodule (git -C $checkout submodule update --init lib/modules/dronecan/libcanard)"
if [ "$ladrc" = 1 ] && [ -z "$ladrc_params" ]; then
    usage >&2
    echo "betaflight_sitl.sh: --ladrc needs --ladrc-params FILE (the airframe's rate-loop parameters)" >&2
    exit 2
fi
if [ "$ladrc" = 0 ] && [ -n "$ladrc_params" ]; then
    usage >&2
    echo "betaflight_sitl.sh: --ladrc-params is for --ladrc" >&2
    exit 2
fi
apply="$REPO_ROOT/integrations/betaflight/apply.sh"
if [ "$ladrc" = 1 ] && [ ! -f "$apply" ]; then
    die "--ladrc: $apply not found: this checkout of ladrc has no Betaflight integration yet"
fi
for tool in make gcc python3; do
    command -v "$tool" >/dev/null || die "$tool: not found: the SITL build needs make, gcc and python3"
done

mkdir -p "$outdir"
outdir="$(cd "$outdir" && pwd)"
case "$outdir/" in
"$checkout"/*) die "OUTDIR $outdir is inside CHECKOUT $checkout: choose a directory outside it (the checkout is never written)" ;;
esac
tree="$outdir/tree"
if [ -e "$tree" ]; then
    [ -f "$tree/$TREE_MARKER" ] || die "$tree exists and was not made by this script: remove it or choose another OUTDIR"
    rm -rf "$tree"
fi
rm -f "$outdir/betaflight_SITL.elf" "$outdir/eeprom.bin" "$outdir/sitl_config.cli" "$outdir/BUILD_INFO"

# The build copy. Submodule directories get an empty .git file: the Makefile then
# takes them as hydrated and does not run git in a tree that is not a repository.
echo "copying the SITL's sources from $checkout to $tree"
mkdir -p "$tree/lib/main" "$tree/lib/modules/dronecan" "$tree/src"
touch "$tree/$TREE_MARKER"
cp -a "$checkout/Makefile" "$checkout/mk" "$tree/"
cp -a "$checkout/src/main" "$checkout/src/platform" "$tree/src/"
[ -d "$checkout/src/utils" ] && cp -a "$checkout/src/utils" "$tree/src/"
mkdir -p "$tree/src/config"
for lib in MAVLink dyad google; do
    cp -a "$checkout/lib/main/$lib" "$tree/lib/main/"
done
cp -a "$checkout/lib/modules/dronecan/libcanard" "$tree/lib/modules/dronecan/"
for sub in lib/modules/dronecan/libcanard src/config; do
    rm -rf "${tree:?}/$sub/.git"
    : >"$tree/$sub/.git"
done

echo "applying the lockstep hook edits"
patch_report="$(python3 "$HERE/betaflight/patch_sitl.py" "$tree")" || die "the hook edits failed (above): see docs/betaflight-sitl.md"
echo "$patch_report"

if [ "$ladrc" = 1 ]; then
    echo "adding the ladrc rate controller: $apply"
    bash "$apply" "$tree" "$REPO_ROOT" "$ladrc_params" || die "--ladrc: $apply failed"
fi

options="SITL_LOCKSTEP=1"
jobs="${JOBS:-2}"
echo "building: make TARGET=SITL OPTIONS=\"$options\" -j$jobs (log: $outdir/build.log)"
if ! make -C "$tree" TARGET=SITL OPTIONS="$options" -j"$jobs" >"$outdir/build.log" 2>&1; then
    tail -n 30 "$outdir/build.log" >&2
    die "make failed: see $outdir/build.log"
fi
[ -f "$tree/obj/main/betaflight_SITL.elf" ] || die "$tree/obj/main/betaflight_SITL.elf: not built: see $outdir/build.log"
cp "$tree/obj/main/betaflight_SITL.elf" "$outdir/betaflight_SITL.elf"

# One CLI file for --config: ours, then the extra ones, a single save at the end
# (the first save ends the --config run).
{
    for f in "$HERE/betaflight/sitl.cli" ${extra_cli[@]+"${extra_cli[@]}"}; do
        echo "# ---- $(basename "$f")"
        grep -v -E '^[[:space:]]*save[[:space:]]*$' "$f"
    done
    echo "save"
} >"$outdir/sitl_config.cli"
echo "configuring: betaflight_SITL.elf --config sitl_config.cli (log: $outdir/config.log)"
(cd "$outdir" && ./betaflight_SITL.elf --config sitl_config.cli) >"$outdir/config.log" 2>&1 ||
    die "the --config run failed: see $outdir/config.log"
if grep -q '###ERROR' "$outdir/config.log"; then
    grep '###ERROR' "$outdir/config.log" >&2
    rm -f "$outdir/eeprom.bin"
    die "the SITL refused CLI lines (above): see $outdir/config.log"
fi
grep -q 'EEPROM saved' "$outdir/config.log" || die "the --config run saved no eeprom.bin: see $outdir/config.log"

if git -C "$checkout" rev-parse --git-dir >/dev/null 2>&1; then
    commit="$(git -C "$checkout" rev-parse HEAD)"
    if [ -n "$(git -C "$checkout" status --porcelain --untracked-files=no 2>/dev/null)" ]; then
        commit="$commit (with uncommitted changes)"
    fi
else
    commit="unknown"
fi
{
    echo "checkout: $checkout"
    echo "commit: $commit"
    echo "make: make TARGET=SITL OPTIONS=\"$options\""
    echo "hook edits (tools/betaflight/patch_sitl.py):"
    echo "$patch_report" | sed 's/^/  /'
    echo "ladrc rate controller: $([ "$ladrc" = 1 ] && echo "yes, parameters $ladrc_params" || echo no)"
    echo "cli: sitl.cli$(for f in ${extra_cli[@]+"${extra_cli[@]}"}; do printf ' %s' "$(basename "$f")"; done)"
    echo "built: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
} >"$outdir/BUILD_INFO"
cat "$outdir/BUILD_INFO"
echo "done: $outdir/betaflight_SITL.elf and $outdir/eeprom.bin"
