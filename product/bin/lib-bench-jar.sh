# shellcheck shell=bash
# The runnable jar of tests/sabot.controlml.benchmarks (./sabot bench controlml, ./sabot bench workbench,
# ./sabot load), sourced after lib.sh.

SABOT_CONTROLML_BENCH_MODULES=bundles/sabot.jdkpkgs,bundles/sabot.model,bundles/sabot.controlml,bundles/sabot.identity,bundles/sabot.fleet,tests/sabot.testsupport,tests/sabot.controlml.benchmarks

# Prints the path of the runnable benchmark jar, building it first when missing or older than a source file.
sabot_controlml_bench_jar() {
    local jar="$SABOT_ROOT/tests/sabot.controlml.benchmarks/target/sabot-bench-controlml.jar"
    local stale=""
    if [ -f "$jar" ]; then
        stale=$(find "$SABOT_ROOT/bundles/sabot.model" "$SABOT_ROOT/bundles/sabot.controlml" "$SABOT_ROOT/bundles/sabot.fleet" \
            "$SABOT_ROOT/tests/sabot.testsupport" "$SABOT_ROOT/tests/sabot.controlml.benchmarks" \
            \( -name '*.java' -o -name '*.MF' -o -name '*.xsd' -o -name pom.xml \) -newer "$jar" \
            -not -path '*/target/*' -print -quit 2>/dev/null)
    fi
    if [ ! -f "$jar" ] || [ -n "$stale" ]; then
        sabot_log "building the ControlML benchmark jar${stale:+ ($stale changed)}"
        sabot_mvn -q -DskipTests package -pl "$SABOT_CONTROLML_BENCH_MODULES" >&2 \
            || sabot_die "building the benchmark failed (run: ./mvnw -B package -DskipTests -pl $SABOT_CONTROLML_BENCH_MODULES)"
    fi
    [ -f "$jar" ] || sabot_die "the build did not produce $jar"
    echo "$jar"
}
