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
# the motion simulation harness and what it drives: the algorithms and the robot's own control loop (OnboardLoop)
SABOT_MOTION_SIM_MODULES=bundles/sabot.jdkpkgs,bundles/sabot.model,bundles/sabot.planner,bundles/sabot.control,bundles/sabot.localization,bundles/sabot.controlml,bundles/sabot.modbus,bundles/sabot.pidstep,bundles/sabot.onboard,bundles/sabot.onboard.motion,tools/sabot.motion.sim
sabot_tools_jar() { # ./sabot plan, ./sabot simulate
    sabot_jar tools tools/sabot.tools/target/sabot-tools.jar "$SABOT_MOTION_SIM_MODULES,tools/sabot.tools" \
        docs/sabot-robot.properties
}
sabot_planner_bench_jar() { # ./sabot bench planner, ./sabot bench navfn
    sabot_jar "planner benchmark" tests/sabot.planner.benchmarks/target/sabot-planner-bench.jar \
        "$SABOT_MOTION_SIM_MODULES,tools/sabot.tools,tests/sabot.planner.benchmarks" docs/sabot-robot.properties
}
sabot_load_jar() { # ./sabot load
    sabot_jar "load" tools/sabot.load/target/sabot-load.jar \
        bundles/sabot.jdkpkgs,bundles/sabot.model,bundles/sabot.controlml,bundles/sabot.identity,bundles/sabot.fleet,tests/sabot.testsupport,tools/sabot.load \
        docs/sabot-robot.properties
}
sabot_controlml_bench_jar() { # ./sabot bench controlml, ./sabot bench workbench
    sabot_jar "ControlML benchmark" tests/sabot.controlml.benchmarks/target/sabot-bench-controlml.jar \
        bundles/sabot.jdkpkgs,bundles/sabot.model,bundles/sabot.controlml,bundles/sabot.identity,bundles/sabot.fleet,tests/sabot.testsupport,tools/sabot.load,tests/sabot.controlml.benchmarks \
        docs/sabot-robot.properties
}
sabot_motion_bench_jar() { # ./sabot bench control
    sabot_jar "motion benchmark" tests/sabot.motion.benchmarks/target/sabot-motion.jar \
        "$SABOT_MOTION_SIM_MODULES,tests/sabot.motion.benchmarks" \
        docs/sabot-robot.properties
}

# --- products -----------------------------------------------------------------------------------------------------
# The folder of the built product NAME (onboard, workbench, director).
sabot_product_dir() { echo "$SABOT_ROOT/product/sabot.$1.product/target/products/sabot-$1/linux/gtk/x86_64"; }

# The Equinox launcher jar of product folder $1.
sabot_launcher_jar() {
    local jar
    jar=$(ls "$1"/plugins/org.eclipse.equinox.launcher_*.jar 2>/dev/null | head -1)
    [ -n "$jar" ] || sabot_die "no Equinox launcher in $1 (rebuild: ./sabot build)"
    echo "$jar"
}

# sabot_module_sources MODULE
# Prints what a product or the update site (MODULE: product/sabot.NAME.product or product/sabot.site) is built from,
# a path a line: its folder, the poms above the bundles and features, the features its .product or category.xml names
# and those they include, and the bundles of those features that are ours (bundles/<id>).
sabot_module_sources() {
    local module=$1 id f p queue=() seen=" "
    echo "$SABOT_ROOT/$module"
    echo "$SABOT_ROOT/pom.xml"; echo "$SABOT_ROOT/bundles/pom.xml"; echo "$SABOT_ROOT/features/pom.xml"
    mapfile -t queue < <(cat "$SABOT_ROOT/$module"/*.product "$SABOT_ROOT/$module"/category.xml 2>/dev/null \
        | grep -o '<feature id="[^"]*"' | sed 's/.*id="//; s/"$//')
    while [ ${#queue[@]} -gt 0 ]; do
        id=${queue[0]}
        queue=("${queue[@]:1}")
        f="$SABOT_ROOT/features/$id"
        case "$seen" in *" $id "*) continue ;; esac
        seen+="$id "
        [ -f "$f/feature.xml" ] || continue
        echo "$f"
        mapfile -t -O ${#queue[@]} queue < <(grep -o '<includes[^>]*id="[^"]*"' "$f/feature.xml" | sed 's/.*id="//; s/"$//')
        for p in $(grep -o '<plugin[^>]*id="[^"]*"' "$f/feature.xml" | sed 's/.*id="//; s/"$//'); do
            [ -d "$SABOT_ROOT/bundles/$p" ] && echo "$SABOT_ROOT/bundles/$p"
        done
    done
}

# sabot_products NAME...
# Builds the products NAME... (onboard, workbench, director; "site": the p2 update site) in one Maven run, tests
# skipped, when one of them is missing or older than a file it is built from (sabot_module_sources).
sabot_products() {
    local name module stamp stale="" modules=()
    for name in "$@"; do
        if [ "$name" = site ]; then
            module=product/sabot.site stamp="$SABOT_ROOT/product/sabot.site/target/repository/content.jar"
        else
            module=product/sabot.$name.product stamp="$(sabot_product_dir "$name")/configuration/config.ini"
        fi
        modules+=("$module")
        if [ ! -f "$stamp" ]; then
            stale=${stale:-"no $stamp"}
        elif [ -z "$stale" ]; then
            local sources; mapfile -t sources < <(sabot_module_sources "$module")
            stale=$(sabot_newer_source "$stamp" "${sources[@]}")
            stale=${stale:+"$stale changed"}
        fi
    done
    [ -n "$stale" ] || return 0
    local list; list=$(IFS=,; echo "${modules[*]}")
    sabot_log "building $* ($stale)"
    sabot_mvn -q verify -DskipTests -pl "$list" -am >&2 \
        || sabot_die "building $* failed (run: ./mvnw -B verify -DskipTests -pl $list -am)"
}

# The configuration of an onboard product driving a simulated robot over serial link $2 on map $3, starting at pose
# $4 (X,Y,THETA in m, m, rad), with XMPP account $1 (full JID) on 127.0.0.1:$5 whose certificate is signed by the CA
# of file $8, its password in file $6, its remote files under folder $7 (./sabot demo's robots, ./sabot bench
# onboard's); with a port $9, its web page there (the portal task, HTTPS with the lab CA's localhost certificate). Who commands it is the server's business: the lab's groups (sabot_grant).
# It joins the fleet lobby fleet@conference.DOMAIN (the private servers' MUC service) and follows the rig's other robots
# there and in its roster (the peers task: their positions for its costmap and collision guard).
sabot_onboard_conf() {
    local jid=$1 link=$2 map=$3 pose=$4 port=$5 pwfile=$6 files=$7 ca=$8 portal=${9:-}
    local x y theta tasks="bus, localizer, planner, tracker, teleop, motion, controlml, peers, remotefs, heartbeat"
    IFS=, read -r x y theta <<<"$pose"
    [ -z "$portal" ] || tasks="$tasks, portal"
    cat <<EOF
# Generated by $(basename "$0"): see docs/USER-GUIDE.md.
robot.name = ${jid%@*}
tasks = $tasks
bus.port = $link
bus.parity = NONE
planner.map = $map
localizer.startX = $x
localizer.startY = $y
localizer.startTheta = $theta
controlml.server = 127.0.0.1
controlml.port = $port
controlml.caFile = $ca
controlml.jid = $jid
controlml.passwordFile = $pwfile
controlml.lobby = fleet@conference.${jid#*@}
remotefs.root = $files
EOF
    # the robot's web page (docs/PORTAL.md) on 127.0.0.1:PORTAL over HTTPS with the lab CA's localhost certificate
    [ -z "$portal" ] || cat <<EOF
portal.bind = 127.0.0.1
portal.port = $portal
portal.tls = true
portal.certificateFile = $(dirname "$(dirname "$ca")")/certs/localhost.crt
portal.keyFile = $(dirname "$(dirname "$ca")")/certs/localhost.key
EOF
}

# Prints the JVM options of an onboard product folder (its etc/jvm.options, comments and blank lines left out), one per
# line; nothing when the file is absent.
sabot_onboard_jvm_options() {
    local file="$1/etc/jvm.options"
    [ -f "$file" ] || return 0
    sed -e 's/#.*//' -e 's/^[[:space:]]*//' -e 's/[[:space:]]*$//' "$file" | grep -v '^$' || true
}

# sabot_onboard_exec [--osgi-area DIR] CONFIG [JVM_OPTION...]
# Runs (exec) the onboard product in its folder with configuration file CONFIG ("": its etc/onboard.conf), its
# etc/jvm.options and the extra JVM options: ./sabot onboard, and the rig's robots (their pid is then the JVM's).
# --osgi-area DIR: the framework's configuration area in DIR instead of the product's configuration/ (which stays the
# shared, read-only part): Config Admin persists the tasks' configurations there, so robots started from one product
# folder at once would read each other's.
sabot_onboard_exec() {
    local args=()
    if [ "$1" = --osgi-area ]; then args=(-configuration "$2"); shift 2; fi
    local config=$1; shift
    local dir jh launcher jvm=()
    dir=$(sabot_product_dir onboard)
    jh=$(sabot_java_home)
    launcher=$(sabot_launcher_jar "$dir")
    mapfile -t jvm < <(sabot_onboard_jvm_options "$dir")
    [ -z "$config" ] || args+=(-config "$config")
    cd "$dir"
    exec "$jh/bin/java" ${jvm[@]+"${jvm[@]}"} "$@" -Dlogback.configurationFile="$dir/etc/logback.xml" -jar "$launcher" \
        -consoleLog ${args[@]+"${args[@]}"}
}

# --- the rig: private XMPP server + sabot-sim on a map + one onboard product per robot ------------------------------
# ./sabot demo's and ./sabot bench onboard's (tests/sabot.system.tests build the same rig in Java from the fixtures
# of sabot.testsupport, which also give a test the simulator's control channel and the product's console).
# The rig's map, the simulator's and every robot's planner's: the lab, unless a caller sets another ROS map_server
# YAML here before sabot_rig_start (./sabot demo --map).
SABOT_RIG_MAP="$SABOT_ROOT/onboard-bridge/maps/lab.yaml"
SABOT_RIG_DOMAIN=sabot.local
SABOT_RIG_OPERATOR=operator SABOT_RIG_OPERATOR_PASSWORD=sabot
SABOT_RIG_OBSERVER=observer SABOT_RIG_OBSERVER_PASSWORD=sabot-observer
SABOT_RIG_MAINTAINER=maintainer SABOT_RIG_MAINTAINER_PASSWORD=sabot-maintainer
# The lab's shared groups: the robots', the robots' asking for access (enrolled, not yet approved: they see no
# group), and one per role. The same names as sabot.fleet.AccessRules (ROBOTS_GROUP, ENROLLING_GROUP, LAB_GROUPS),
# which a robot's configuration takes by default; AccessRulesTest holds the two together.
SABOT_GROUP_ROBOTS=sabot-robots
SABOT_GROUP_ENROLLING=sabot-enrolling
# An enrolment token (sabot-xmpp enrol token) begins with this; a robot that finds one in its password file logs in
# with it once and replaces it with a password of its own (sabot.fleet.Enrolment.TOKEN_PREFIX: the same)
SABOT_ENROL_TOKEN_PREFIX=sabot-enrol-
declare -A SABOT_ROLE_GROUPS=([observer]=sabot-observers [operator]=sabot-operators [maintainer]=sabot-maintainers)
# sabot-sim puts robot i (1-based) at +0.8 (i - 1) m in y from robot 1 (its --help)
SABOT_RIG_ROBOT_SPACING_Y=0.8

# The demo's start poses: robot 1 in the lab's east room facing east, robot i 0.8 (i - 1) m further in y (x 6.0,
# y 2.8..6.0 for five robots), each more than 1.1 m from any wall.
SABOT_DEMO_START=6.0,2.8,0.0

# sabot_patrol_route I: robot I's patrol (./sabot demo --patrol, ./sabot bench patrol), targets for controlml.py
# patrol: along its own lane y = 2.8 + 0.8 (I - 1) in the east room, west to x 4.3 (0.8 m from the partition) and
# back east to x 7.0 (0.5 m short of the bench at x 7.5..9.5, y 5.0..5.5): a stop, a pass, a wait of 1 s, a stop.
# Lanes 0.8 m apart never cross: robots that do not see each other over ControlML cannot meet.
sabot_patrol_route() {
    local y
    y=$(awk -v i="$1" -v d="$SABOT_RIG_ROBOT_SPACING_Y" 'BEGIN { printf "%.2f", 2.8 + d * (i - 1) }')
    echo "4.3,$y,3.1416,stop 5.3,$y,0,pass 7.0,$y,0,wait,1 6.0,$y,3.1416,stop"
}

# sabot_map_key YAML KEY: the value of KEY in a map_server YAML, as sabot-sim reads it (the text after "KEY:", without
# a # comment and the blanks around it; the last such line); nothing when the key is absent.
sabot_map_key() {
    sed -n -E "s/^[[:space:]]*$2[[:space:]]*:[[:space:]]*([^#]*[^#[:space:]])?[[:space:]]*(#.*)?\$/\1/p" "$1" | tail -n 1
}

# sabot_map_copy YAML DIR
# Copies the map YAML into folder DIR as DIR/map.yaml, and the files it names (image, sabot_landmarks) beside it
# under their own base names, the YAML's lines naming them rewritten so: how a robot's remote files hold its map for
# the workbench (sabot.workbench.controlml's RobotMaps: map.yaml, the image in the same folder).
sabot_map_copy() {
    local yaml=$1 dir=$2 key name src base script=""
    for key in image sabot_landmarks; do
        name=$(sabot_map_key "$yaml" "$key")
        [ -n "$name" ] || continue
        case "$name" in /*) src=$name ;; *) src="$(dirname "$yaml")/$name" ;; esac
        [ -f "$src" ] || sabot_die "map $yaml: its $key file $src does not exist"
        base=$(basename "$name")
        cp "$src" "$dir/$base"
        script+="s|^[[:space:]]*$key[[:space:]]*:.*|$key: $(printf '%s' "$base" | sed 's/[\\&|]/\\&/g')|;"
    done
    sed -E "$script" "$yaml" >"$dir/map.yaml"
}

# sabot_patrol_start PYTHON I LOG [--duration SECONDS]: robot I of the rig (sabot_rig_start) patrols its lane
# (sabot_patrol_route) in the background, commanded by the operator through controlml.py patrol (the second ControlML
# implementation, as an operator's script), its output to LOG; sets PATROL_PID.
sabot_patrol_start() {
    local python=$1 i=$2 log=$3 route
    shift 3
    # shellcheck disable=SC2207
    route=($(sabot_patrol_route "$i"))
    "$python" "$SABOT_ROOT/tools/controlml-py/controlml.py" --jid "$SABOT_RIG_OPERATOR@$SABOT_RIG_DOMAIN" \
        --password "$SABOT_RIG_OPERATOR_PASSWORD" --port "$RIG_PORT" --ca-file "$RIG_CA" --timeout 60 \
        patrol "sabot-0$i@$SABOT_RIG_DOMAIN" "$@" -- "${route[@]}" >"$log" 2>&1 &
    PATROL_PID=$!
}

# Builds what the rig runs (the onboard product, sabot-sim) before the first process starts.
sabot_rig_build() {
    sabot_products onboard
    make -s -C "$SABOT_ROOT/onboard-bridge" build/sabot-sim >&2 || sabot_die "building sabot-sim failed"
}

# sabot_rig_start DIR PORT ROBOTS X,Y,THETA[/X,Y,THETA...] [JVM_OPTION...]
# Brings the rig up in folder DIR (made empty first): a private Prosody on 127.0.0.1:PORT (0: a free port) with state
# in DIR/xmpp, the accounts sabot-0I@sabot.local (enrolled: a token in DIR/robotI/password, replaced by the robot)
# and the operator's,
# sabot-sim on map SABOT_RIG_MAP with ROBOTS robots (ground truth DIR/truth.csv, its control channel on a free loopback
# port): robot 1 at X,Y,THETA and robot I SABOT_RIG_ROBOT_SPACING_Y (I - 1) m further in y, or, given a pose per robot
# ('/' between them, as many as ROBOTS), each at its own; and per robot an onboard product on that map from that
# pose (configuration DIR/robotI/onboard.conf, remote files DIR/robotI/files, console DIR/robotI/onboard.log; JVM
# options added). A start pose the simulator warns of (in a wall, on another robot) is the rig's error, the warning
# shown. Returns once they are started, not online (sabot_rig_await_online). With SABOT_RIG_PORTAL_PORT set, robot I serves its web page on 127.0.0.1 at that port + I - 1.
# Sets RIG_DIR, RIG_PORT, RIG_CA (the server's lab CA, PEM), RIG_SIM_PID, RIG_SIM_CONTROL,
# RIG_ROBOT_PIDS (robot I at I-1).
sabot_rig_start() {
    local dir=$1 port=$2 robots=$3 start=$4 i line x y theta links=() poses=() sim_start=()
    shift 4
    if [[ "$start" == */* ]]; then
        IFS=/ read -r -a poses <<<"$start"
        [ ${#poses[@]} = "$robots" ] || sabot_die "the rig's start poses $start: ${#poses[@]} poses for $robots robots"
        sim_start=(--starts "$start")
    else
        IFS=, read -r x y theta <<<"$start"
        for ((i = 1; i <= robots; i++)); do
            poses+=("$x,$(awk -v y="$y" -v d="$SABOT_RIG_ROBOT_SPACING_Y" -v i="$i" 'BEGIN { printf "%.3f", y + d * (i - 1) }'),$theta")
        done
        sim_start=(--start "$start")
    fi
    RIG_DIR=$dir RIG_PORT="" RIG_CA="" RIG_SIM_PID="" RIG_SIM_CONTROL="" RIG_ROBOT_PIDS=()
    rm -rf "$dir"; mkdir -p "$dir"
    line=$("$SABOT_ROOT/product/bin/sabot-xmpp" start --run "$dir/xmpp" --port "$port" \
        --archive "${SABOT_ARCHIVE_STORE:-internal}" --timeout 30) || sabot_die "the private Prosody did not start"
    RIG_PORT=$(sed -n 's/.* port=\([0-9]*\) .*/\1/p' <<<"$line")
    RIG_CA=$(sed -n 's/.* ca=\([^ ]*\).*/\1/p' <<<"$line")
    [ -s "$RIG_CA" ] || sabot_die "the private Prosody named no lab CA file: $line"
    # the robots enrolled as a lab enrols them (docs/SECURITY.md, "Enrolment"): a one-time token in each password file,
    # which the robot replaces with a password of its own at its first login; approved at once (the demo's robots are
    # the lab's), so they obey the lab's roles from their first login on
    for ((i = 1; i <= robots; i++)); do
        mkdir -p "$dir/robot$i/files"
        sabot_rig_enrol "sabot-0$i@$SABOT_RIG_DOMAIN" "$dir/robot$i/password"
    done
    sabot_rig_register "$SABOT_RIG_OPERATOR@$SABOT_RIG_DOMAIN" "$SABOT_RIG_OPERATOR_PASSWORD"
    sabot_rig_register "$SABOT_RIG_OBSERVER@$SABOT_RIG_DOMAIN" "$SABOT_RIG_OBSERVER_PASSWORD"
    sabot_rig_register "$SABOT_RIG_MAINTAINER@$SABOT_RIG_DOMAIN" "$SABOT_RIG_MAINTAINER_PASSWORD"
    # as the lab's administrator: one account per role
    sabot_grant "$dir/xmpp" "$SABOT_RIG_OBSERVER@$SABOT_RIG_DOMAIN" observer
    sabot_grant "$dir/xmpp" "$SABOT_RIG_OPERATOR@$SABOT_RIG_DOMAIN" operator
    sabot_grant "$dir/xmpp" "$SABOT_RIG_MAINTAINER@$SABOT_RIG_DOMAIN" maintainer

    # one simulator process, one pty per robot; its first stdout line (JSON) says they are ready. It runs in a session
    # of its own, as the server does: Linux's scheduler (autogroup, on by default) shares the CPUs between sessions
    # first, and in the script's session (robots, workbench, display) it fell a minute behind the wall clock on a
    # machine loaded by other work, every robot's answers with it (in its own, 11.5 s: docs/ONBOARD.md); it needs a few
    # % of a core. setsid execs in place (a background job of a script is no group leader): the pid is the
    # simulator's, sabot_rig_stop stops it.
    setsid "$SABOT_ROOT/onboard-bridge/build/sabot-sim" --map "$SABOT_RIG_MAP" --robots "$robots" --seed 1 "${sim_start[@]}" \
        --link "$dir/sim-robot" --truth "$dir/truth.csv" --control 0 >"$dir/sim.out" 2>"$dir/sim.log" &
    RIG_SIM_PID=$!
    sabot_await_line "$dir/sim.out" '"robots"' 10 "$RIG_SIM_PID" "the simulator" "$dir/sim.log"
    ! grep -q warning "$dir/sim.log" || { cat "$dir/sim.log" >&2; sabot_die "the simulator refused the start pose(s)"; }
    mapfile -t links < <(head -n 1 "$dir/sim.out" | python3 -c 'import json, sys
j = json.load(sys.stdin)
print(j["control"])
for r in j["robots"]: print(r["link"])')
    RIG_SIM_CONTROL=${links[0]}
    links=("${links[@]:1}")
    [ ${#links[@]} = "$robots" ] || sabot_die "the simulator announced ${#links[@]} robots, not $robots: $(head -n 1 "$dir/sim.out")"
    sabot_log "simulator: $robots robot(s) on the map $SABOT_RIG_MAP (pid $RIG_SIM_PID), buses ${links[*]}, control channel 127.0.0.1:$RIG_SIM_CONTROL, ground truth $dir/truth.csv"

    for ((i = 1; i <= robots; i++)); do
        sabot_onboard_conf "sabot-0$i@$SABOT_RIG_DOMAIN" "${links[$((i - 1))]}" "$SABOT_RIG_MAP" "${poses[$((i - 1))]}" \
            "$RIG_PORT" "$dir/robot$i/password" "$dir/robot$i/files" "$RIG_CA" \
            "${SABOT_RIG_PORTAL_PORT:+$((SABOT_RIG_PORTAL_PORT + i - 1))}" >"$dir/robot$i/onboard.conf"
        (sabot_onboard_exec --osgi-area "$dir/robot$i/osgi" "$dir/robot$i/onboard.conf" "$@") \
            >"$dir/robot$i/onboard.log" 2>&1 &
        RIG_ROBOT_PIDS+=($!)
        sabot_log "robot sabot-0$i@$SABOT_RIG_DOMAIN (pid $!): config $dir/robot$i/onboard.conf, log $dir/robot$i/onboard.log"
    done
}

# sabot_group add|remove RUN GROUP JID: a change of a shared group of the private server of state folder RUN.
sabot_group() {
    "$SABOT_ROOT/product/bin/sabot-xmpp" group "$1" --run "$2" "$3" "$4" >&2 \
        || sabot_die "could not $1 $4 $([ "$1" = add ] && echo to || echo from) group $3 (see $2)"
}

# sabot_grant RUN JID ROLE [remove]: gives JID the role (observer, operator, maintainer) on the lab's robots, or takes
# it away: the role's shared group on the private server of state folder RUN.
sabot_grant() {
    local group=${SABOT_ROLE_GROUPS[$3]:-}
    [ -n "$group" ] || sabot_die "'$3' is not a role: observer, operator or maintainer"
    sabot_group "${4:-add}" "$1" "$group" "$2"
}

sabot_rig_enrol() { # JID PASSWORD_FILE: the token written there (mode 600), the robot approved
    local token
    token=$("$SABOT_ROOT/product/bin/sabot-xmpp" enrol token --run "$RIG_DIR/xmpp" "$1" 2>/dev/null) \
        || sabot_die "could not enrol $1 (see $RIG_DIR/xmpp)"
    (umask 077; printf '%s\n' "$token" >"$2")
    "$SABOT_ROOT/product/bin/sabot-xmpp" enrol approve --run "$RIG_DIR/xmpp" "$1" >/dev/null 2>&1 \
        || sabot_die "could not approve $1 (see $RIG_DIR/xmpp)"
}

sabot_rig_register() { # JID PASSWORD
    "$SABOT_ROOT/product/bin/sabot-xmpp" register --run "$RIG_DIR/xmpp" "$1" "$2" >/dev/null 2>&1 \
        || sabot_die "could not register $1 (see $RIG_DIR/xmpp)"
}

# sabot_rig_await_online I TIMEOUT: waits until robot I's ControlML session is online.
sabot_rig_await_online() {
    sabot_await_line "$RIG_DIR/robot$1/onboard.log" 'XMPP session online' "$2" "${RIG_ROBOT_PIDS[$(($1 - 1))]}" \
        "the onboard product of sabot-0$1"
}

# sabot_rig_stop [PID...]
# Stops the rig: the PIDs (its clients) together with the robots (their JVMs stop in parallel; a robot brakes on
# SIGTERM), then the simulator they drove, then the server. Each step waits for its processes (SIGKILL after 20 s).
sabot_rig_stop() {
    sabot_terminate 20 "$@" ${RIG_ROBOT_PIDS[@]+"${RIG_ROBOT_PIDS[@]}"}
    RIG_ROBOT_PIDS=()
    sabot_terminate 20 "${RIG_SIM_PID:-}"
    RIG_SIM_PID=""
    [ -z "${RIG_DIR:-}" ] || "$SABOT_ROOT/product/bin/sabot-xmpp" stop --run "$RIG_DIR/xmpp" >/dev/null 2>&1 || true
}

# --- processes ----------------------------------------------------------------------------------------------------
# sabot_await_line FILE REGEX TIMEOUT PID NAME [LOG]
# Waits until FILE has a line matching the extended regex REGEX, at most TIMEOUT s, while process PID (NAME) lives;
# else dies with the end of LOG (default FILE), where that process says why.
sabot_await_line() {
    local file=$1 re=$2 timeout=$3 pid=$4 name=$5 log=${6:-$1} deadline=$((SECONDS + $3))
    while ! grep -Eqa -- "$re" "$file" 2>/dev/null; do
        kill -0 "$pid" 2>/dev/null || { tail -n 40 "$log" >&2; sabot_die "$name exited before printing /$re/ (log $log)"; }
        [ $SECONDS -lt $deadline ] || { tail -n 40 "$log" >&2; sabot_die "$name: no line /$re/ within ${timeout}s (log $log)"; }
        # a log file has no "line written" event to wait on; a background sleep lets a signal's trap run at once
        sleep 0.1 & wait $!
    done
}

# sabot_terminate GRACE PID...
# Stops child processes of the calling shell together: SIGTERM, SIGKILL to those left after GRACE s; returns when
# all have exited (empty PIDs and processes already gone are skipped).
sabot_terminate() {
    local grace=$1 p guard group=()
    shift
    for p in "$@"; do
        [ -n "$p" ] && kill -TERM "$p" 2>/dev/null && group+=("$p")
    done
    [ ${#group[@]} -gt 0 ] || return 0
    (sleep "$grace"; kill -KILL "${group[@]}" 2>/dev/null) & guard=$!
    for p in "${group[@]}"; do wait "$p" 2>/dev/null || true; done
    kill "$guard" 2>/dev/null || true
    wait "$guard" 2>/dev/null || true
}

# The screen of every virtual display (xvfb-run's, ./sabot demo's Xvfb): large enough for the workbench.
SABOT_XVFB_SCREEN=(-screen 0 1400x900x24 -nolisten tcp)

# Runs a command (exec) on a virtual display of its own.
sabot_xvfb_exec() {
    command -v xvfb-run >/dev/null || sabot_die "xvfb-run missing: apt-get install -y xvfb xauth"
    exec xvfb-run -a -s "${SABOT_XVFB_SCREEN[*]}" "$@"
}

# psql on the ControlML archive of a private ejabberd started with --archive sql (product/bin/sabot-xmpp): DIR/pg's
# database "ejabberd" as its owner over 127.0.0.1, the rest of the arguments passed to psql (docs/ARCHIVE.md).
sabot_archive_sql() { # DIR PSQL-ARGUMENTS...
    local pg=$1/pg
    shift
    PGPASSWORD=$(cat "$pg/password") psql -X -q -h 127.0.0.1 -p "$(cat "$pg/port")" -U ejabberd -d ejabberd \
        -v ON_ERROR_STOP=1 "$@"
}

# The archive's command-line arguments, shared by sabot-log and sabot-stats (docs/ARCHIVE.md, docs/STATISTICS.md).
SABOT_ARCHIVE_TIME_HINT="expected an ISO 8601 time (2026-11-29T08:00:00Z) or an age like 90s, 15m, 2h, 7d"
# A TIME argument (ISO 8601, or an age: that long ago) as "age:N unit" or "at:ISO"; fails on anything else.
sabot_archive_time() { # VALUE
    local unit
    if [[ "$1" =~ ^([0-9]{1,7})([smhd])$ ]]; then
        case "${BASH_REMATCH[2]}" in s) unit=seconds ;; m) unit=minutes ;; h) unit=hours ;; d) unit=days ;; esac
        echo "age:${BASH_REMATCH[1]} $unit"
    elif [[ "$1" =~ ^[0-9]{4}-[0-9]{2}-[0-9]{2}([T\ ][0-9]{2}:[0-9]{2}(:[0-9]{2}(\.[0-9]{1,9})?)?)?(Z|[+-][0-9]{2}(:?[0-9]{2})?)?$ ]]; then
        echo "at:$1"
    else
        return 1
    fi
}
# A TIME from sabot_archive_time, held in the psql variable NAME, as an SQL expression (DEFAULT when empty): the value
# reaches SQL as a psql variable (:'NAME' quotes it), never spliced into the query's text.
sabot_archive_bound() { # NAME VALUE DEFAULT
    case "$2" in
        "") echo "$3" ;;
        age:*) echo "now() - :'$1'::interval" ;;
        at:*) echo ":'$1'::timestamptz" ;;
    esac
}
# A device argument as a bare JID (USER alone: @sabot.local); fails on anything else.
sabot_archive_device() { # ARGUMENT
    [[ "$1" =~ ^[A-Za-z0-9._-]+(@[A-Za-z0-9.-]+)?$ ]] || return 1
    if [[ "$1" == *@* ]]; then echo "$1"; else echo "$1@$SABOT_RIG_DOMAIN"; fi
}
# Dies with why unless DIR's server keeps an archive whose PostgreSQL is running.
sabot_archive_running() { # DIR
    [ -s "$1/pg/port" ] && [ -s "$1/pg/password" ] \
        || sabot_die "no archive in $1: start the server with it (./sabot xmpp start --server ejabberd --archive sql)"
    local port; port=$(cat "$1/pg/port")
    ( { exec {fd}<>"/dev/tcp/127.0.0.1/$port"; } 2>/dev/null ) \
        || sabot_die "the archive's PostgreSQL (127.0.0.1:$port) is not running: it runs with the server (./sabot xmpp start --server ejabberd --archive sql)"
}
