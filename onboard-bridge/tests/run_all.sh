#!/usr/bin/env bash
# Runs every onboard-bridge test: the C suites (release and ASan/UBSan builds), a
# bounded libFuzzer run, and the pymodbus interoperability suite. Each suite prints
# "<suite>: N passed, N failed"; this script adds them up and prints the total as its
# last line. Exit status: 0 only when nothing failed.
set -u
BUILD=${1:-build}
cd "$(dirname "$0")/.."
TMP=$BUILD/tmp
mkdir -p "$TMP"
passed=0
failed=0

# run_suite NAME COMMAND...: runs it, shows its output, adds its counts. A suite that
# crashes or exits non-zero without reporting a failure counts as one failure.
run_suite() {
    local name=$1 log=$TMP/$1.log rc line p f
    shift
    echo "== $name"
    "$@" >"$log" 2>&1 </dev/null
    rc=$?
    cat "$log"
    line=$(grep -E '^[A-Za-z0-9_-]+: [0-9]+ passed, [0-9]+ failed$' "$log" | tail -n 1)
    if [ -n "$line" ]; then
        p=$(echo "$line" | sed -E 's/.*: ([0-9]+) passed, ([0-9]+) failed/\1/')
        f=$(echo "$line" | sed -E 's/.*: ([0-9]+) passed, ([0-9]+) failed/\2/')
    else
        p=0
        f=0
    fi
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        echo "$name: exited with status $rc"
        f=1
    fi
    passed=$((passed + p))
    failed=$((failed + f))
}

# Bounded fuzzing: a fixed seed and a fixed number of runs (deterministic), capped
# in time; a fresh corpus each time, started from the checked-in seeds.
fuzz() {
    local corpus=$TMP/fuzz-corpus
    rm -rf "$corpus"
    mkdir -p "$corpus"
    if "$BUILD"/fuzz_slave -seed=1 -runs="${FUZZ_RUNS:-400000}" -max_total_time="${FUZZ_SECONDS:-30}" \
        -print_final_stats=1 "$corpus" tests/corpus/fuzz_slave >"$TMP/fuzz.out" 2>&1; then
        grep -E 'Done|number_of_executed_units|new_units_added' "$TMP/fuzz.out"
        echo "fuzz_slave: 1 passed, 0 failed"
    else
        tail -n 40 "$TMP/fuzz.out"
        echo "fuzz_slave: 0 passed, 1 failed"
    fi
}
# The fuzzer keeps one core busy for its whole run: it runs beside the C suites (each single-threaded) and its
# report is read after them.
fuzz >"$TMP/fuzz_slave.report" 2>&1 </dev/null &
fuzz_pid=$!

for t in "$BUILD"/test_*; do
    [ -x "$t" ] || continue
    run_suite "$(basename "$t")" "$t"
done
for t in "$BUILD"/san/test_*; do
    [ -x "$t" ] || continue
    case "$t" in *.o) continue ;; esac
    run_suite "san_$(basename "$t")" env ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 "$t"
done

wait "$fuzz_pid"
run_suite fuzz_slave cat "$TMP/fuzz_slave.report"

# Interoperability with an independent Modbus implementation (pinned in
# tests/requirements-interop.txt), in a venv under build/.
interop() {
    local venv=$BUILD/venv
    if [ ! -x "$venv/bin/python" ] || ! cmp -s tests/requirements-interop.txt "$venv/requirements.txt"; then
        rm -rf "$venv"
        python3 -m venv "$venv" || return 1
        "$venv/bin/pip" install --quiet --disable-pip-version-check -r tests/requirements-interop.txt || return 1
        cp tests/requirements-interop.txt "$venv/requirements.txt"
    fi
    "$venv/bin/python" tests/interop_pymodbus.py "$BUILD/sabot-sim"
}
if [ -f tests/interop_pymodbus.py ]; then
    run_suite interop_pymodbus interop
fi

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
