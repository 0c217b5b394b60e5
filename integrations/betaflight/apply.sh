#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
#
# apply.sh TREE LADRC_REPO_ROOT PARAMS_FILE
#
# Puts the ladrc rate loop into a COPY of a Betaflight source tree, as
# Betaflight's rate controller (docs/betaflight-integration.md):
#   - copies the library (the RATE-ADRC selection of cmake/LadrcVariants.cmake),
#     the adapter (ladrc_rate.{c,h}) and the glue (ladrc_bf_hook.{c,h}) into
#     TREE/src/main/ladrc/, with the airframe's parameters compiled in
#     (ladrc_rate_params.h, generated from PARAMS_FILE);
#   - edits Betaflight's own files at three named hook points:
#       mk/source.mk         after  COMMON_SRC += $(CONFIG_SRC) $(PG_SRC) ...   (the build list)
#       src/main/flight/pid.c after #include "pid.h"                           (the declaration)
#       src/main/flight/pid.c the   pidData[axis].Sum = P + I + D + F + S line  (the rate controller)
#
# Every hook text is looked for before anything is written: one not found
# stops with the file and the text, and the tree is left as it was. A tree
# already carrying the hooks keeps them (each edit is made once) and gets
# the library, the adapter and the parameters afresh: running it again is
# harmless.
#
# PARAMS_FILE: one airframe's rate-loop parameters, "key = value ..." lines,
# '#' starts a comment; every key below is required, once:
#   k_w_per_s            = ROLL PITCH YAW   rate-loop crossover (1/s)
#   wo_rad_s             = ROLL PITCH YAW   rate observer bandwidth (rad/s)
#   b0_rad_s2_per_pidsum = ROLL PITCH YAW   rad/s^2 per pidSum unit
#   pidsum_limit         = ROLL PITCH YAW   Betaflight's pidsum_limit, pidsum_limit_yaw
#   motor_tau_s          = TAU              the motors' lag (s), 0 = none
#   delay_ticks          = N                measurement delay (PID loop ticks)
set -euo pipefail

die() {
    printf '%s\n' "$*" >&2
    exit 1
}

[ $# -eq 3 ] || die "usage: apply.sh TREE LADRC_REPO_ROOT PARAMS_FILE (PARAMS_FILE: the airframe's rate-loop parameters, given to tools/betaflight_sitl.sh as --ladrc-params FILE)"
TREE=$1
REPO=$2
PARAMS=$3

[ -f "$TREE/mk/source.mk" ] || die "$TREE/mk/source.mk: not found (TREE must be a Betaflight source tree)"
[ -f "$TREE/src/main/flight/pid.c" ] || die "$TREE/src/main/flight/pid.c: not found (TREE must be a Betaflight source tree)"
[ -f "$REPO/include/ladrc/axis.h" ] || die "$REPO/include/ladrc/axis.h: not found (LADRC_REPO_ROOT must be the ladrc repository)"
HERE=$REPO/integrations/betaflight
[ -f "$HERE/ladrc_rate.c" ] || die "$HERE/ladrc_rate.c: not found"
[ -f "$PARAMS" ] || die "$PARAMS: not found (the airframe's rate-loop parameters, --ladrc-params FILE)"
command -v cmake >/dev/null || die "apply.sh: cmake not found (it selects the library's sources: $HERE/select_sources.cmake)"

# --- the parameters: parsed and checked before anything is written ---------
# Prints one "key v1 [v2 v3]" line per key; errors as file:line:col.
PARSED=$(awk -v file="$PARAMS" '
    function fail(line, col, msg) { printf "%s:%d:%d: %s\n", file, line, col, msg > "/dev/stderr"; bad = 1; exit 1 }
    BEGIN {
        want["k_w_per_s"] = 3; want["wo_rad_s"] = 3; want["b0_rad_s2_per_pidsum"] = 3
        want["pidsum_limit"] = 3; want["motor_tau_s"] = 1; want["delay_ticks"] = 1
        num = "^[+]?([0-9]+[.]?[0-9]*|[.][0-9]+)([eE][-+]?[0-9]+)?$"
    }
    {
        text = $0
        hash = index(text, "#")
        if (hash > 0) text = substr(text, 1, hash - 1)
        if (text ~ /^[ \t]*$/) next
        eq = index(text, "=")
        if (eq == 0) fail(NR, 1, "expected key = value")
        key = substr(text, 1, eq - 1); gsub(/[ \t]+/, "", key)
        if (!(key in want)) fail(NR, 1, "unknown key \"" key "\" (k_w_per_s, wo_rad_s, b0_rad_s2_per_pidsum, pidsum_limit, motor_tau_s, delay_ticks)")
        if (key in seen) fail(NR, 1, "\"" key "\" given twice (first on line " seen[key] ")")
        seen[key] = NR
        rest = substr(text, eq + 1)
        n = split(rest, v, /[ \t]+/)
        out = key; count = 0; from = eq + 1
        for (i = 1; i <= n; ++i) {
            if (v[i] == "") continue
            col = from - 1 + index(substr(text, from), v[i]); from = col + length(v[i])
            if (v[i] !~ num) fail(NR, col, "\"" v[i] "\" is not a non-negative decimal number")
            if (key == "delay_ticks" && v[i] !~ /^[0-9]+$/) fail(NR, col, "delay_ticks must be a whole number of ticks")
            if (key != "motor_tau_s" && key != "delay_ticks" && v[i] + 0 <= 0) fail(NR, col, key " must be > 0")
            out = out " " v[i]; ++count
        }
        if (count != want[key]) fail(NR, eq + 1, key " takes " want[key] " value(s) (" (want[key] == 3 ? "roll pitch yaw" : "one") "), found " count)
        print out
    }
    END {
        if (bad) exit 1
        for (k in want) if (!(k in seen)) { printf "%s:%d:1: missing key \"%s\"\n", file, NR + 1, k > "/dev/stderr"; exit 1 }
    }' "$PARAMS") || exit 1

param() { printf '%s\n' "$PARSED" | awk -v k="$1" '$1 == k { $1 = ""; sub(/^ /, ""); print }'; }
# "a b c" -> "(float)a, (float)b, (float)c"
floats() { printf '%s\n' "$1" | awk '{ for (i = 1; i <= NF; ++i) printf "%s(float)%s", (i > 1 ? ", " : ""), $i }'; }

# --- the library's selection -------------------------------------------------
SELECTION=$(cmake -DLADRC_ROOT="$REPO" -P "$HERE/select_sources.cmake" 2>&1) || die "$HERE/select_sources.cmake: $SELECTION"
LIB_SOURCES=$(printf '%s\n' "$SELECTION" | sed -n 's/^ladrc-source: //p' | tr '\n' ' ')
LIB_DEFINES=$(printf '%s\n' "$SELECTION" | sed -n 's/^ladrc-define: //p')
[ -n "$LIB_SOURCES" ] || die "$HERE/select_sources.cmake: no sources selected"

# --- the hook points: all found (or already there) before anything is written
MK=$TREE/mk/source.mk
PID=$TREE/src/main/flight/pid.c
# shellcheck disable=SC2016 # make's text, not the shell's
MK_HOOK='COMMON_SRC += $(CONFIG_SRC) $(PG_SRC) $(COMMON_DEVICE_SRC) $(RX_SRC)'
# shellcheck disable=SC2016 # make's text, not the shell's
MK_LINE='include $(SRC_DIR)/ladrc/ladrc.mk # ladrc rate loop (integrations/betaflight/apply.sh)'
INC_HOOK='#include "pid.h"'
INC_LINE='#include "ladrc/ladrc_bf_hook.h" // ladrc rate loop (integrations/betaflight/apply.sh)'
SUM_HOOK='pidData[axis].Sum = pidData[axis].P + pidData[axis].I + pidData[axis].D + pidData[axis].F + pidData[axis].S;'
SUM_NEW='pidData[axis].Sum = ladrcRatePidSum(axis, currentPidSetpoint, gyroRate, pidRuntime.dT, ARMING_FLAG(ARMED) && pidRuntime.pidStabilisationEnabled, pidData[axis].P + pidData[axis].I + pidData[axis].D + pidData[axis].F + pidData[axis].S); // ladrc rate loop (integrations/betaflight/apply.sh)'

# count_lines FILE TEXT: lines holding TEXT exactly (as a substring, no patterns)
count_lines() { awk -v t="$2" 'index($0, t) { ++n } END { print n + 0 }' "$1"; }

# check_hook FILE HOOK EDIT: "absent" when HOOK is on exactly one line and EDIT
# nowhere, "present" when EDIT is on one line, else stops naming file and text.
check_hook() {
    local done_count hook_count
    done_count=$(count_lines "$1" "$3")
    if [ "$done_count" = 1 ]; then
        echo present
        return
    fi
    [ "$done_count" = 0 ] || die "$1: the ladrc edit \"$3\" is there $done_count times (a damaged earlier apply); start from a fresh copy of the tree"
    hook_count=$(count_lines "$1" "$2")
    [ "$hook_count" = 1 ] || die "$1: hook text not found exactly once (found $hook_count times): $2"
    echo absent
}
MK_STATE=$(check_hook "$MK" "$MK_HOOK" "$MK_LINE")
INC_STATE=$(check_hook "$PID" "$INC_HOOK" "$INC_LINE")
SUM_STATE=$(check_hook "$PID" "$SUM_HOOK" "ladrcRatePidSum(axis, currentPidSetpoint, gyroRate")
# the variables the hook's call reads, in the function it goes into
for name in 'const float gyroRate = gyro.gyroADCf[axis];' 'float currentPidSetpoint = getSetpointRate(axis);' 'pidRuntime.pidStabilisationEnabled'; do
    [ "$(count_lines "$PID" "$name")" -ge 1 ] || die "$PID: the hook's call reads a variable this pid.c does not have: $name"
done

# --- write: the library, the adapter, the generated files --------------------
DEST=$TREE/src/main/ladrc
rm -rf "$DEST"
mkdir -p "$DEST/include/ladrc" "$DEST/lib"
cp "$REPO"/include/ladrc/*.h "$DEST/include/ladrc/"
cp "$REPO"/src/*.h "$DEST/lib/"
for source in $LIB_SOURCES; do
    cp "$REPO/src/$source" "$DEST/lib/"
done
cp "$HERE/ladrc_rate.c" "$HERE/ladrc_rate.h" "$HERE/ladrc_bf_hook.c" "$HERE/ladrc_bf_hook.h" "$DEST/"
cp "$REPO/LICENSE" "$DEST/LICENSE"

{
    echo "/* SPDX-License-Identifier: BSD-3-Clause */"
    echo "/* The ladrc library's build-time selection for Betaflight (written by"
    echo " * integrations/betaflight/apply.sh from select_sources.cmake): RATE-ADRC alone. */"
    echo "#ifndef LADRC_BF_CONFIG_H"
    echo "#define LADRC_BF_CONFIG_H"
    printf '%s\n' "$LIB_DEFINES" | awk -F= 'NF == 2 { printf "#define %s %s\n", $1, $2 }'
    echo "#endif"
} >"$DEST/include/ladrc_bf_config.h"

{
    echo "/* SPDX-License-Identifier: BSD-3-Clause */"
    echo "/* The airframe's rate-loop parameters (ladrc_rate.h), written by"
    echo " * integrations/betaflight/apply.sh from $(basename "$PARAMS"). */"
    echo "#ifndef LADRC_RATE_PARAMS_H"
    echo "#define LADRC_RATE_PARAMS_H"
    echo "#define LADRC_BF_RATE_PARAMS                                                         \\"
    echo "    {                                                                                \\"
    echo "        .k_w_per_s = {$(floats "$(param k_w_per_s)")},                                        \\"
    echo "        .wo_rad_s = {$(floats "$(param wo_rad_s)")},                                         \\"
    echo "        .b0_rad_s2_per_pidsum = {$(floats "$(param b0_rad_s2_per_pidsum)")},                 \\"
    echo "        .pidsum_limit = {$(floats "$(param pidsum_limit)")},                                 \\"
    echo "        .motor_tau_s = $(floats "$(param motor_tau_s)"),                                     \\"
    echo "        .delay_ticks = $(param delay_ticks)u                                                 \\"
    echo "    }"
    echo "#endif"
} >"$DEST/ladrc_rate_params.h"

{
    echo "# SPDX-License-Identifier: BSD-3-Clause"
    echo "# The ladrc rate loop in Betaflight's build (written by integrations/betaflight/apply.sh)."
    echo "LADRC_SRC := \$(addprefix ladrc/lib/,$LIB_SOURCES) ladrc/ladrc_rate.c ladrc/ladrc_bf_hook.c"
    echo "COMMON_SRC += \$(LADRC_SRC)"
    echo "SPEED_OPTIMISED_SRC += \$(LADRC_SRC)"
    echo "INCLUDE_DIRS += \$(SRC_DIR)/ladrc/include"
    echo "TARGET_FLAGS += -DLADRC_CONFIG=ladrc_bf_config.h"
} >"$DEST/ladrc.mk"

# --- the hook edits -----------------------------------------------------------
# insert_after FILE HOOK LINE / replace_text FILE HOOK NEW: on the one line found above.
insert_after() {
    awk -v t="$2" -v add="$3" '{ print } index($0, t) { print add }' "$1" >"$1.ladrc.tmp" && mv "$1.ladrc.tmp" "$1"
}
replace_text() {
    awk -v t="$2" -v new="$3" '{ at = index($0, t); if (at) $0 = substr($0, 1, at - 1) new substr($0, at + length(t)); print }' "$1" >"$1.ladrc.tmp" && mv "$1.ladrc.tmp" "$1"
}
[ "$MK_STATE" = present ] || insert_after "$MK" "$MK_HOOK" "$MK_LINE"
[ "$INC_STATE" = present ] || insert_after "$PID" "$INC_HOOK" "$INC_LINE"
[ "$SUM_STATE" = present ] || replace_text "$PID" "$SUM_HOOK" "$SUM_NEW"

echo "apply.sh: ladrc rate loop in $TREE (edits before: source.mk $MK_STATE, pid.c include $INC_STATE, pid.c pidSum $SUM_STATE; now all present; library: $LIB_SOURCES)"
