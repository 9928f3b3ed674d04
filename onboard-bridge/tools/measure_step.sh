#!/usr/bin/env bash
# Host instruction count of one control step, with valgrind's callgrind.
# Runs `sabot-sim --bench 0.5` (10 000 simulated steps, then 2 000 000 calls of the
# control interrupt alone) and divides the inclusive instruction counts by the calls.
set -euo pipefail
cd "$(dirname "$0")/.."
make -s build/sabot-sim
out=build/tmp/callgrind.out
mkdir -p build/tmp
valgrind --tool=callgrind --callgrind-out-file="$out" build/sabot-sim --bench 0.5 >/dev/null 2>&1
steps=10000
isr_calls=$((steps + 2000000))
callgrind_annotate --inclusive=yes "$out" >"$out.txt" 2>/dev/null
incl() { awk -v pat="$1" 'index($0, pat) { gsub(",", "", $1); print $1; exit }' "$out.txt"; }
isr=$(incl ':sact_control_isr')
sim=$(incl ':robot_step')
echo "{\"control_isr_instructions\": $((isr / isr_calls)), \"motor_step_instructions\": $((isr / isr_calls / 2)), \"sim_step_instructions\": $((sim / steps))}"
