# Shared shell functions of the ./sabot launcher and the product/bin/sabot-* commands. Source it; don't run it.
# SABOT_ROOT is the repository root.
SABOT_ROOT=${SABOT_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
export SABOT_ROOT

sabot_log() { printf '[sabot] %s\n' "$*" >&2; }
sabot_die() { printf '[sabot] error: %s\n' "$*" >&2; exit 1; }

# Major version of a java binary, e.g. 21 or 25 (0 when it does not run).
sabot_java_major() {
    local v
    v=$("$1" -XshowSettings:properties -version 2>&1 | sed -n 's/^ *java\.specification\.version = //p')
    echo "${v%%.*}" | grep -E '^[0-9]+$' || echo 0
}

# Prints the JAVA_HOME of a JDK >= 21: $SABOT_JAVA_HOME, $JAVA_HOME, $TEMURIN25_HOME, then /usr/lib/jvm/*
# (newest first). Exits with the install command when there is none.
sabot_java_home() {
    local c
    for c in "${SABOT_JAVA_HOME:-}" "${JAVA_HOME:-}" "${TEMURIN25_HOME:-}" $(ls -d "${SABOT_JVM_DIR:-/usr/lib/jvm}"/*/ 2>/dev/null | sort -rV); do
        c=${c%/}
        [ -n "$c" ] && [ -x "$c/bin/javac" ] || continue
        if [ "$(sabot_java_major "$c/bin/java")" -ge 21 ]; then echo "$c"; return 0; fi
    done
    sabot_die "no JDK >= 21 found (looked at \$SABOT_JAVA_HOME, \$JAVA_HOME, \$TEMURIN25_HOME, ${SABOT_JVM_DIR:-/usr/lib/jvm}/*).
  Debian 12 packages only JDK 17; install Temurin from Adoptium's Debian repository:
    apt-get install -y wget gpg && wget -qO- https://packages.adoptium.net/artifactory/api/gpg/key/public | gpg --dearmor -o /usr/share/keyrings/adoptium.gpg && echo 'deb [signed-by=/usr/share/keyrings/adoptium.gpg] https://packages.adoptium.net/artifactory/deb bookworm main' > /etc/apt/sources.list.d/adoptium.list && apt-get update && apt-get install -y temurin-25-jdk
  or point SABOT_JAVA_HOME at an unpacked JDK >= 21."
}

# Runs the Maven wrapper with the right JDK; extra arguments are passed through.
sabot_mvn() {
    local jh; jh=$(sabot_java_home) || exit 1
    (cd "$SABOT_ROOT" && JAVA_HOME="$jh" ./mvnw -B -ntp "$@")
}

# Prints the first file under the given files or folders (target/ folders and dot files left out) that is newer than
# file $1; nothing when none is, or when $1 does not exist (then everything is stale: the caller checks -f itself).
sabot_newer_source() {
    local stamp=$1; shift
    find "$@" \( -name target -o -name '.*' \) -prune -o -type f -newer "$stamp" -print -quit 2>/dev/null
}

# sabot_jar NAME JAR MODULES [EXTRA_SOURCE...]
# Prints the path of the runnable jar JAR (relative to the repository root), building it first with Maven when it is
# missing or older than a file of one of MODULES (comma-separated reactor folders, built in that order without -am)
# or of an EXTRA_SOURCE (a file or folder read by the build). NAME says what is built, in the log line.
sabot_jar() {
    local name=$1 jar="$SABOT_ROOT/$2" modules=$3; shift 3
    local sources=() m stale=""
    for m in ${modules//,/ }; do sources+=("$SABOT_ROOT/$m"); done
    for m in "$@"; do sources+=("$SABOT_ROOT/$m"); done
    [ -f "$jar" ] && stale=$(sabot_newer_source "$jar" "${sources[@]}")
    if [ ! -f "$jar" ] || [ -n "$stale" ]; then
        sabot_log "building the $name jar${stale:+ ($stale changed)}"
        sabot_mvn -q -DskipTests package -pl "$modules" >&2 \
            || sabot_die "building the $name jar failed (run: ./mvnw -B package -DskipTests -pl $modules)"
    fi
    [ -f "$jar" ] || sabot_die "the build did not produce $jar"
    echo "$jar"
}

# The runnable jars of the commands (one place for each jar's modules).
sabot_tools_jar() { # ./sabot plan, ./sabot simulate
    sabot_jar tools tools/sabot.tools/target/sabot-tools.jar \
        bundles/sabot.jdkpkgs,bundles/sabot.model,bundles/sabot.planner,bundles/sabot.control,bundles/sabot.localization,tools/sabot.motion.sim,tools/sabot.tools \
        docs/sabot-robot.properties
}
sabot_planner_bench_jar() { # ./sabot bench planner, ./sabot bench navfn
    sabot_jar "planner benchmark" tests/sabot.planner.benchmarks/target/sabot-planner-bench.jar \
        bundles/sabot.jdkpkgs,bundles/sabot.model,bundles/sabot.planner,bundles/sabot.control,bundles/sabot.localization,tools/sabot.motion.sim,tools/sabot.tools,tests/sabot.planner.benchmarks \
        docs/sabot-robot.properties
}
sabot_controlml_bench_jar() { # ./sabot bench controlml, ./sabot bench workbench, ./sabot load
    sabot_jar "ControlML benchmark" tests/sabot.controlml.benchmarks/target/sabot-bench-controlml.jar \
        bundles/sabot.jdkpkgs,bundles/sabot.model,bundles/sabot.controlml,bundles/sabot.identity,bundles/sabot.fleet,tests/sabot.testsupport,tests/sabot.controlml.benchmarks \
        docs/sabot-robot.properties
}
sabot_motion_bench_jar() { # ./sabot bench control
    sabot_jar "motion benchmark" tests/sabot.motion.benchmarks/target/sabot-motion.jar \
        bundles/sabot.jdkpkgs,bundles/sabot.model,bundles/sabot.control,bundles/sabot.localization,tools/sabot.motion.sim,tests/sabot.motion.benchmarks \
        docs/sabot-robot.properties
}

# Prints the JVM options of an onboard product folder (its etc/jvm.options, comments and blank lines left out), one per
# line; nothing when the file is absent.
sabot_onboard_jvm_options() {
    local file="$1/etc/jvm.options"
    [ -f "$file" ] || return 0
    sed -e 's/#.*//' -e 's/^[[:space:]]*//' -e 's/[[:space:]]*$//' "$file" | grep -v '^$' || true
}
