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

# The planner commands (sabot-plan, sabot-bench-planner) run from the shaded planner benchmark jar.
SABOT_PLANNER_MODULES=bundles/sabot.jdkpkgs,bundles/sabot.model,bundles/sabot.planner,tests/sabot.planner.benchmarks

# Prints the path of sabot-planner-bench.jar, building it first when it is missing or older than a planner source.
sabot_planner_jar() {
    local jar="$SABOT_ROOT/tests/sabot.planner.benchmarks/target/sabot-planner-bench.jar"
    local stale=""
    if [ -f "$jar" ]; then
        stale=$(find "$SABOT_ROOT/bundles/sabot.model/src" "$SABOT_ROOT/bundles/sabot.model/META-INF" \
            "$SABOT_ROOT/bundles/sabot.planner" "$SABOT_ROOT/tests/sabot.planner.benchmarks/src" \
            "$SABOT_ROOT/tests/sabot.planner.benchmarks/pom.xml" \
            \( -name '*.java' -o -name '*.MF' -o -name '*.properties' -o -name pom.xml \) -newer "$jar" \
            -not -path '*/target/*' -print -quit 2>/dev/null)
    fi
    if [ ! -f "$jar" ] || [ -n "$stale" ]; then
        sabot_log "building the planner jar (${stale:+$stale changed; }first run downloads JMH from Maven Central)"
        sabot_mvn -q -DskipTests package -pl "$SABOT_PLANNER_MODULES" >&2 \
            || sabot_die "building the planner jar failed (run: ./mvnw -B package -DskipTests -pl $SABOT_PLANNER_MODULES)"
    fi
    [ -f "$jar" ] || sabot_die "the build did not produce $jar"
    echo "$jar"
}

# Prints the JVM options of an onboard product folder (its etc/jvm.options, comments and blank lines left out), one per
# line; nothing when the file is absent.
sabot_onboard_jvm_options() {
    local file="$1/etc/jvm.options"
    [ -f "$file" ] || return 0
    sed -e 's/#.*//' -e 's/^[[:space:]]*//' -e 's/[[:space:]]*$//' "$file" | grep -v '^$' || true
}
