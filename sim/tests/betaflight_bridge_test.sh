#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# ladrc_sil's BETAFLIGHT bridge against a stand-in SITL that speaks Betaflight's packets
# (fake_bf_sitl.c): it flies in lockstep (one exchange per control tick), the same run twice
# gives the same bytes, and every way a SITL fails is an error naming the SITL, the exchange and
# the simulator's time, never a hang or a number: missing, refusing to start, dying, falling
# silent, answering garbage or a motor output that is not a number, never arming, ports taken.
# Usage: betaflight_bridge_test.sh LADRC_SIL FAKE_SITL
set -uo pipefail
sil=$1
fake=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
check() { # name, condition exit code
    if [ "$2" -eq 0 ]; then echo "betaflight_bridge_test.sh:$1:PASS"; else echo "betaflight_bridge_test.sh:$1:FAIL"; failures=$((failures + 1)); fi
}
mkdir -p "$work/sitl"
cp "$fake" "$work/sitl/betaflight_SITL.elf"
printf 'stand-in configuration\n' > "$work/sitl/eeprom.bin"

# A 3 s flight at 1 kHz, the paper's airframe on real rotors, a 10 deg roll step and a pitch
# cosine, BETAFLIGHT beside LADRC.
cat > "$work/hover.ini" <<'INI'
[run]
duration_s = 3
control_dt_s = 0.001
controllers = BETAFLIGHT LADRC
[rotors]
ideal = no
w2_min_rad2_s2 = 1e4
w2_max_rad2_s2 = 1.5e6
motor_tau_s = 0.02
[sensors]
rate_noise_std_deg_s = 0.2
use_rate = yes
[reference]
roll = 10*step(t - 0.5)
pitch = 5*cos(pi*t)
yaw = 0
[metrics]
settle_band_deg = 1
settle_window_s = 0.5 3
INI

sil_run() { # out dir, extra args...: exit status in $rc, stderr in $work/err
    local out=$1
    shift
    "$sil" "$work/hover.ini" --quiet --out "$out" "$@" > "$work/stdout" 2> "$work/err"
    rc=$?
}

# 1. It flies: exit 0, BETAFLIGHT's row in the tables and metrics.csv, its RMS error finite and
# small. Bound 3 deg: the stand-in's rate P loop with the pilot's angle loop settles a 10 deg step
# in some 0.5 s; a bridge with a sign or motor-order error diverges (90 deg) instead.
sil_run "$work/a" --betaflight "$work/sitl"
check flies "$([ $rc -eq 0 ] && echo 0 || echo 1)"
cat "$work/err"
rms=$(awk -F, '$2 == "BETAFLIGHT" && $4 == "error_rms_deg" && $5 == "roll" { print $6 }' "$work/a/hover/metrics.csv" 2>/dev/null)
echo "BETAFLIGHT rms roll: ${rms:-none}"
check rms_small "$(awk -v r="${rms:-nan}" 'BEGIN { exit !(r + 0 == r && r < 3.0) }'; echo $?)"
check time_series "$([ -s "$work/a/hover/BETAFLIGHT.csv" ] && echo 0 || echo 1)"

# 2. The same run twice: the same bytes (the stand-in, like the SITL in lockstep, is a function
# of the packets it gets).
sil_run "$work/b" --betaflight "$work/sitl"
check deterministic "$(cmp -s "$work/a/hover/BETAFLIGHT.csv" "$work/b/hover/BETAFLIGHT.csv"; echo $?)"

# 3. The same with the folder from the environment.
LADRC_BETAFLIGHT_SITL="$work/sitl" sil_run "$work/c"
check environment "$(cmp -s "$work/a/hover/BETAFLIGHT.csv" "$work/c/hover/BETAFLIGHT.csv"; echo $?)"

# 4. No SITL given, or a folder without it: refused before anything flies (exit 2, nothing written).
sil_run "$work/d"
check none_given "$([ $rc -eq 2 ] && grep -q 'BETAFLIGHT needs a Betaflight SITL' "$work/err" && [ ! -e "$work/d" ] && echo 0 || echo 1)"
sil_run "$work/e" --betaflight "$work/missing"
check missing "$([ $rc -eq 2 ] && grep -q 'missing' "$work/err" && grep -q 'tools/betaflight_sitl.sh' "$work/err" && [ ! -e "$work/e" ] && echo 0 || echo 1)"
cat "$work/err"

# 5. Each failure of the SITL: exit 1 and the message, no hang; the scenario's outputs are not
# written (a failed run leaves nothing, as every failed run does).
fault() { # name, FAKE_BF_FAULT, text the message must hold, extra --set...
    local name=$1 what=$2 text=$3
    shift 3
    FAKE_BF_FAULT=$what sil_run "$work/f_$name" --betaflight "$work/sitl" "$@"
    sed -n '1,3p' "$work/err"
    check "$name" "$([ $rc -eq 1 ] && grep -qF -- "$text" "$work/err" && [ ! -e "$work/f_$name" ] && echo 0 || echo 1)"
}
fault no_start no-start "stopped while starting (exit status 1); its last output: 'fake SITL: refusing to start as asked'"
# at the SITL's time 3 s: the boot's packet, 2 s of warm-up (the stand-in's calibration wants
# 0.5 s), one tick arming, then t = 0.998 s of the scenario
fault dies die@3 "BETAFLIGHT at t = 0.998 s: Betaflight SITL $work/sitl/betaflight_SITL.elf exited with status 3 at its time 3 s (exchange 3000)"
fault silent silent@3 "BETAFLIGHT at t = 0.998 s: Betaflight SITL $work/sitl/betaflight_SITL.elf: no motor packet within 300 ms" --set controller:BETAFLIGHT.timeout_ms=300
fault garbage garbage@3 "a packet of 7 bytes on port 9002 at its time 3 s"
fault not_a_number nan@3 "motor 3 output nan at its time 3 s"
fault never_arms never-arm "did not arm within 2 s"

# 6. Faults of every kind at times drawn from a fixed seed (BF_FAULT_RUNS of them, 12 by
# default; docs/reliability.md has a long form): each run ends, exit 0 (the fault after the
# flight's end, or junk that happens to decode as four outputs in [0, 1]) or exit 1 with the
# SITL named and the exchange counted; never a hang (the exchange timeout 300 ms bounds each).
RANDOM=40
runs=${BF_FAULT_RUNS:-12}
located=0 clean=0 other=0
kinds=(die silent garbage nan junk)
for _ in $(seq "$runs"); do
    kind=${kinds[$((RANDOM % 5))]}
    at=$(awk -v r=$RANDOM 'BEGIN { printf "%.4f", 2.0 + 3.2 * r / 32768 }')
    FAKE_BF_FAULT="$kind@$at" sil_run "$work/r" --betaflight "$work/sitl" --set controller:BETAFLIGHT.timeout_ms=300
    if [ $rc -eq 1 ] && grep -q "Betaflight SITL $work/sitl.*(exchange [0-9]*)" "$work/err"; then
        located=$((located + 1))
    elif [ $rc -eq 0 ]; then
        clean=$((clean + 1))
    else
        other=$((other + 1))
        echo "fault $kind@$at: exit $rc: $(head -c 400 "$work/err")"
    fi
    rm -rf "$work/r"
done
echo "random faults: $runs runs, $located located errors, $clean flights to the end, $other otherwise"
check random_faults "$([ $other -eq 0 ] && [ $located -gt 0 ] && echo 0 || echo 1)"

# 7. The motor port taken by another process: refused with the port named.
/usr/bin/python3 -c '
import socket, sys, time
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.bind(("127.0.0.1", 9002))
open(sys.argv[1], "w").close(); time.sleep(30)' "$work/held" &
holder=$!
for _ in $(seq 100); do [ -e "$work/held" ] && break; sleep 0.1; done
sil_run "$work/g" --betaflight "$work/sitl"
kill "$holder" 2>/dev/null
wait "$holder" 2>/dev/null
check port_taken "$([ $rc -eq 1 ] && grep -q 'UDP port 9002' "$work/err" && echo 0 || echo 1)"

# 8. No SITL process left behind by any of the above.
check none_left "$(pgrep -f "$work/" > /dev/null && echo 1 || echo 0)"

[ "$failures" -eq 0 ] && echo "betaflight_bridge_test.sh: all passed" || echo "betaflight_bridge_test.sh: $failures failed"
exit $((failures > 0))
