/*
 * sabot-sim: SabotOne robots on a host. Each robot's RS-485 bus appears as a
 * pseudo-terminal (symlinked to a stable name) and as Modbus RTU framing over TCP on
 * loopback; the first line on stdout is JSON naming them. Stops on SIGTERM/SIGINT.
 *
 * Time: the simulation advances in control periods of 50 us. It is locked to the
 * wall clock times a speed factor (1 = real time, for live use), or free-running
 * in --bench. Everything random derives from --seed.
 */
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <getopt.h>
#include <limits.h>
#include <math.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "control.h"
#include "robot.h"

#define MAX_ROBOTS 16
#define MAX_CLIENTS 8          /* TCP connections per robot */
/* Nothing outside the process sees the simulation between bus events and control commands: it sleeps until a
 * master's byte, a command, a request's end or an answer due, and then steps the simulated time up to the wall
 * clock in one go (the same 50 us steps, computed late). With nothing due it still wakes every IDLE_WAKE_US of
 * simulated time, so that the ground-truth log stays current. */
#define IDLE_WAKE_US 50000
#define CLOCK_CHECK_STEPS 20   /* steps between looks at the wall clock while catching up */
#define CATCH_UP_SLICE_S 0.005 /* the longest stretch of stepping without I/O when behind */
#define LATE_WAKE_S 0.020      /* this far behind the wall clock at a wake-up is logged (at most once a second) */
#define TRUTH_PERIOD_US 10000  /* ground-truth log at 100 Hz */
#define START_SPACING_Y 0.8    /* m in y between robots placed from --start (or the map centre) */
#define POSE_TEXT_MAX 128      /* the longest X,Y,THETA of --starts */

typedef struct {
    int pty_master, pty_slave;
    char pty_path[128], link_path[PATH_MAX];
    int listen_fd, tcp_port;
    int client[MAX_CLIENTS];
} transports_t;

typedef struct {
    const char *map_path;
    double start_x, start_y, start_theta;
    bool start_given;
    double starts[MAX_ROBOTS][3];  /* x, y, theta of each robot: --starts, else filled in from the start pose */
    int n_starts;                  /* poses --starts gave, 0 without it */
    uint64_t seed;
    double speed;
    int tcp_port;               /* -1: no TCP */
    int control_port;           /* -1: no control channel */
    int robots;
    bool robots_given;
    bus_faults_t faults;
    double gear_ratio, track;
    const char *truth_path;
    const char *link_prefix;
    double duration;            /* simulated seconds, 0 = until signalled */
    bool bench;
    double bench_seconds;
    battery_params_t battery;      /* every robot's pack */
    double battery_soc[MAX_ROBOTS]; /* each robot's state of charge at start */
    int n_socs;                    /* values --battery-soc gave, 0 without it */
} options_t;

static volatile sig_atomic_t stop_requested;

static void on_signal(int sig)
{
    (void)sig;
    stop_requested = 1;
}

static double wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* Files shipped beside the binary: <source>/maps, <repo>/docs. Resolved from the
 * executable's location so a moved checkout still finds them. */
static void source_path(char *out, size_t len, const char *relative)
{
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = '\0';   /* .../onboard-bridge/build */
            char joined[2 * PATH_MAX], resolved[PATH_MAX];
            snprintf(joined, sizeof joined, "%s/../%s", exe, relative);
            if (realpath(joined, resolved)) {
                snprintf(out, len, "%s", resolved);
                return;
            }
        }
    }
    snprintf(out, len, "%s/%s", SABOT_SOURCE_DIR, relative);
}

static void usage(FILE *f)
{
    battery_params_t battery_defaults;
    battery_params_default(&battery_defaults);
    fprintf(f,
            "usage: sabot-sim [options]\n"
            "  --map FILE.yaml        ROS map_server map (default maps/lab.yaml)\n"
            "  --start X,Y,THETA      start pose of robot 1 in m, m, rad; others %g m apart in y\n"
            "                         (default: the map centre)\n"
            "  --starts X,Y,THETA/... one start pose per robot, '/' between them; sets the number of robots\n"
            "                         (with --robots N: N poses); not with --start\n"
            "  --seed N               seed of every random process (default 1)\n"
            "  --speed F              simulated seconds per wall second (default 1)\n"
            "  --realtime             same as --speed 1\n"
            "  --tcp PORT             Modbus RTU over TCP on 127.0.0.1:PORT+i (0 = any free port)\n"
            "  --control PORT         control channel (obstacles, people, boards, truth, battery) on 127.0.0.1:PORT\n"
            "                         (0 = any free port; see README.md)\n"
            "  --robots N             robots in this process, each with its own bus (default 1)\n"
            "  --fault-crc P          probability that an answer's CRC is corrupted\n"
            "  --fault-drop P         probability that an answer is lost\n"
            "  --fault-latency MS     extra delay before each answer\n"
            "  --gear-ratio R         gearhead ratio (default %g, docs/sabot-robot.properties)\n"
            "  --track M              distance between the wheels in m (default %g, same file)\n"
            "  --truth FILE.csv       ground truth at 100 Hz\n"
            "  --link PREFIX          pty symlinks PREFIX1..N (default /tmp/sabot-robot)\n"
            "  --duration S           stop after S simulated seconds\n"
            "  --battery-capacity AH  every robot's battery capacity in Ah (default %g; 0.001..65.535)\n"
            "  --battery-soc F[/F...] state of charge at start, 0..1: one for every robot, or one per robot\n"
            "                         with '/' between them (default 1)\n"
            "  --battery-base-load W  power drawn besides the motors (default %g)\n"
            "  --battery-charge A     the docks' charging current (default %g)\n"
            "  --bench [S]            run one robot flat out for S simulated s (default 20), print JSON\n"
            "  --map-file             print the path of the Modbus register map and exit\n",
            START_SPACING_Y, (double)SABOT_ROBOT_GEAR_RATIO, (double)SABOT_ROBOT_TRACK_WIDTH_M,
            battery_defaults.capacity_ah, battery_defaults.base_load_w, battery_defaults.charge_current);
}

/* Argument parsers: each refuses anything but the whole argument as the expected kind. */
static bool arg_double(const char *option, const char *text, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(text, &end);
    if (end == text || *end || errno || !isfinite(v)) {
        fprintf(stderr, "sabot-sim: %s wants a number, got '%s'\n", option, text);
        return false;
    }
    *out = v;
    return true;
}

static bool arg_range(const char *option, const char *text, double lo, double hi, bool lo_open, double *out)
{
    if (!arg_double(option, text, out))
        return false;
    if (*out < lo || (lo_open && *out == lo) || *out > hi) {
        if (lo_open && hi == INFINITY)
            fprintf(stderr, "sabot-sim: %s wants a number > %g, got '%s'\n", option, lo, text);
        else if (hi == INFINITY)
            fprintf(stderr, "sabot-sim: %s wants a number >= %g, got '%s'\n", option, lo, text);
        else
            fprintf(stderr, "sabot-sim: %s wants a number in %g..%g, got '%s'\n", option, lo, hi, text);
        return false;
    }
    return true;
}

static bool arg_integer(const char *option, const char *text, long long lo, long long hi, long long *out)
{
    char *end;
    errno = 0;
    long long v = strtoll(text, &end, 10);
    if (end == text || *end || errno || v < lo || v > hi) {
        fprintf(stderr, "sabot-sim: %s wants an integer in %lld..%lld, got '%s'\n", option, lo, hi, text);
        return false;
    }
    *out = v;
    return true;
}

static bool arg_port(const char *option, const char *text, int *port)
{
    long long v;
    if (!arg_integer(option, text, 0, 65535, &v))
        return false;
    *port = (int)v;
    return true;
}

/* X,Y,THETA: three finite numbers and nothing else. */
static bool parse_pose(const char *text, double pose[3])
{
    char extra;
    return sscanf(text, "%lf,%lf,%lf%c", &pose[0], &pose[1], &pose[2], &extra) == 3 && isfinite(pose[0]) &&
           isfinite(pose[1]) && isfinite(pose[2]);
}

/* --starts X,Y,THETA/X,Y,THETA/...: one pose per robot, at most MAX_ROBOTS. */
static bool parse_starts(const char *text, options_t *o)
{
    int n = 0;
    for (const char *p = text;; n++) {
        const char *slash = strchr(p, '/');
        size_t len = slash ? (size_t)(slash - p) : strlen(p);
        if (n == MAX_ROBOTS) {
            fprintf(stderr, "sabot-sim: --starts gives more than %d poses (at most %d robots), got '%s'\n", MAX_ROBOTS,
                    MAX_ROBOTS, text);
            return false;
        }
        char pose[POSE_TEXT_MAX];
        snprintf(pose, sizeof pose, "%.*s", (int)(len < sizeof pose ? len : sizeof pose - 1), p);
        if (len >= sizeof pose || !parse_pose(pose, o->starts[n])) {
            fprintf(stderr, "sabot-sim: --starts wants X,Y,THETA (three numbers) per robot, '/' between them; "
                            "pose %d is '%.*s' in '%s'\n", n + 1, (int)len, p, text);
            return false;
        }
        if (!slash)
            break;
        p = slash + 1;
    }
    o->n_starts = n + 1;
    return true;
}

/* --battery-soc F/F/...: one state of charge 0..1 per robot (or one for all), at most MAX_ROBOTS. */
static bool parse_socs(const char *text, options_t *o)
{
    int n = 0;
    for (const char *p = text;; n++) {
        const char *slash = strchr(p, '/');
        size_t len = slash ? (size_t)(slash - p) : strlen(p);
        if (n == MAX_ROBOTS) {
            fprintf(stderr, "sabot-sim: --battery-soc gives more than %d values (at most %d robots), got '%s'\n",
                    MAX_ROBOTS, MAX_ROBOTS, text);
            return false;
        }
        char word[POSE_TEXT_MAX], *end;
        snprintf(word, sizeof word, "%.*s", (int)(len < sizeof word ? len : sizeof word - 1), p);
        errno = 0;
        double v = strtod(word, &end);
        if (len == 0 || len >= sizeof word || end == word || *end || errno || !(v >= 0 && v <= 1)) {
            fprintf(stderr, "sabot-sim: --battery-soc wants a number in 0..1 per robot, '/' between them; "
                            "value %d is '%.*s' in '%s'\n", n + 1, (int)len, p, text);
            return false;
        }
        o->battery_soc[n] = v;
        if (!slash)
            break;
        p = slash + 1;
    }
    o->n_socs = n + 1;
    return true;
}

static int parse_options(int argc, char **argv, options_t *o)
{
    enum { O_MAP = 256, O_START, O_STARTS, O_SEED, O_SPEED, O_REALTIME, O_TCP, O_CONTROL, O_ROBOTS, O_CRC, O_DROP, O_LATENCY,
           O_GEAR, O_TRACK, O_TRUTH, O_LINK, O_DURATION, O_BENCH, O_MAPFILE, O_HELP, O_BATTERY_CAPACITY,
           O_BATTERY_SOC, O_BATTERY_BASE_LOAD, O_BATTERY_CHARGE };
    static const struct option longopts[] = {
        { "map", required_argument, 0, O_MAP },        { "start", required_argument, 0, O_START },
        { "starts", required_argument, 0, O_STARTS },
        { "seed", required_argument, 0, O_SEED },      { "speed", required_argument, 0, O_SPEED },
        { "realtime", no_argument, 0, O_REALTIME },    { "tcp", required_argument, 0, O_TCP },
        { "control", required_argument, 0, O_CONTROL },
        { "robots", required_argument, 0, O_ROBOTS },  { "fault-crc", required_argument, 0, O_CRC },
        { "fault-drop", required_argument, 0, O_DROP }, { "fault-latency", required_argument, 0, O_LATENCY },
        { "gear-ratio", required_argument, 0, O_GEAR }, { "track", required_argument, 0, O_TRACK },
        { "truth", required_argument, 0, O_TRUTH },    { "link", required_argument, 0, O_LINK },
        { "duration", required_argument, 0, O_DURATION }, { "bench", optional_argument, 0, O_BENCH },
        { "map-file", no_argument, 0, O_MAPFILE },     { "help", no_argument, 0, O_HELP },
        { "battery-capacity", required_argument, 0, O_BATTERY_CAPACITY },
        { "battery-soc", required_argument, 0, O_BATTERY_SOC },
        { "battery-base-load", required_argument, 0, O_BATTERY_BASE_LOAD },
        { "battery-charge", required_argument, 0, O_BATTERY_CHARGE },
        { 0, 0, 0, 0 },
    };
    int c;
    long long n;
    double v;
    opterr = 0;   /* getopt's own messages do not name the option well enough; ours below do */
    while ((c = getopt_long(argc, argv, ":", longopts, NULL)) != -1) {
        switch (c) {
        case O_MAP: o->map_path = optarg; break;
        case O_START: {
            double pose[3];
            if (!parse_pose(optarg, pose)) {
                fprintf(stderr, "sabot-sim: --start wants X,Y,THETA (three numbers), got '%s'\n", optarg);
                return -1;
            }
            o->start_x = pose[0];
            o->start_y = pose[1];
            o->start_theta = pose[2];
            o->start_given = true;
            break;
        }
        case O_STARTS:
            if (!parse_starts(optarg, o))
                return -1;
            break;
        case O_SEED: {
            char *end;
            errno = 0;
            unsigned long long seed = strtoull(optarg, &end, 10);
            if (!isdigit((unsigned char)optarg[0]) || *end || errno) {
                fprintf(stderr, "sabot-sim: --seed wants an integer in 0..%llu, got '%s'\n", ULLONG_MAX, optarg);
                return -1;
            }
            o->seed = seed;
            break;
        }
        case O_SPEED:
            if (!arg_range("--speed", optarg, 0, INFINITY, true, &o->speed))
                return -1;
            break;
        case O_REALTIME: o->speed = 1.0; break;
        case O_TCP:
            if (!arg_port("--tcp", optarg, &o->tcp_port))
                return -1;
            break;
        case O_CONTROL:
            if (!arg_port("--control", optarg, &o->control_port))
                return -1;
            break;
        case O_ROBOTS:
            if (!arg_integer("--robots", optarg, 1, MAX_ROBOTS, &n))
                return -1;
            o->robots = (int)n;
            o->robots_given = true;
            break;
        case O_CRC:
            if (!arg_range("--fault-crc", optarg, 0, 1, false, &o->faults.crc_error_rate))
                return -1;
            break;
        case O_DROP:
            if (!arg_range("--fault-drop", optarg, 0, 1, false, &o->faults.drop_rate))
                return -1;
            break;
        case O_LATENCY:
            if (!arg_range("--fault-latency", optarg, 0, 60000, false, &v))
                return -1;
            o->faults.latency_us = (uint32_t)lround(v * 1000.0);
            break;
        case O_GEAR:
            if (!arg_range("--gear-ratio", optarg, 0, INFINITY, true, &o->gear_ratio))
                return -1;
            break;
        case O_TRACK:
            if (!arg_range("--track", optarg, 0, INFINITY, true, &o->track))
                return -1;
            break;
        case O_TRUTH: o->truth_path = optarg; break;
        case O_LINK:
            if (!optarg[0]) {
                fprintf(stderr, "sabot-sim: --link wants a path prefix\n");
                return -1;
            }
            o->link_prefix = optarg;
            break;
        case O_DURATION:
            if (!arg_range("--duration", optarg, 0, INFINITY, true, &o->duration))
                return -1;
            break;
        case O_BENCH:
            o->bench = true;
            if (optarg) {
                if (!arg_range("--bench", optarg, 0, INFINITY, true, &o->bench_seconds))
                    return -1;
            } else if (optind < argc && argv[optind][0] != '-') {
                if (!arg_range("--bench", argv[optind++], 0, INFINITY, true, &o->bench_seconds))
                    return -1;
            }
            break;
        case O_BATTERY_CAPACITY:
            /* The power board reports it in whole mAh in one register. */
            if (!arg_range("--battery-capacity", optarg, 0.001, 65.535, false, &o->battery.capacity_ah))
                return -1;
            break;
        case O_BATTERY_SOC:
            if (!parse_socs(optarg, o))
                return -1;
            break;
        case O_BATTERY_BASE_LOAD:
            if (!arg_range("--battery-base-load", optarg, 0, 1000, false, &o->battery.base_load_w))
                return -1;
            break;
        case O_BATTERY_CHARGE:
            if (!arg_range("--battery-charge", optarg, 0, INFINITY, true, &o->battery.charge_current))
                return -1;
            break;
        case O_MAPFILE: {
            char path[PATH_MAX];
            source_path(path, sizeof path, "../docs/sact-modbus-map.json");
            printf("%s\n", path);
            exit(0);
        }
        case O_HELP: usage(stdout); exit(0);
        case ':':
            fprintf(stderr, "sabot-sim: %s wants an argument\n", argv[optind - 1]);
            return -1;
        default:
            fprintf(stderr, "sabot-sim: unknown option '%s' (--help lists them)\n", argv[optind - 1]);
            return -1;
        }
    }
    if (optind < argc) {
        fprintf(stderr, "sabot-sim: unexpected argument '%s' (--help lists the options)\n", argv[optind]);
        return -1;
    }
    if (o->n_starts && o->start_given) {
        fprintf(stderr, "sabot-sim: --start and --starts: give one or the other\n");
        return -1;
    }
    if (o->n_starts && o->robots_given && o->n_starts != o->robots) {
        fprintf(stderr, "sabot-sim: --starts gives %d pose%s for %d robot%s (--robots %d)\n", o->n_starts,
                o->n_starts == 1 ? "" : "s", o->robots, o->robots == 1 ? "" : "s", o->robots);
        return -1;
    }
    if (o->n_starts)
        o->robots = o->n_starts;
    if (o->n_socs > 1 && o->n_socs != o->robots) {
        fprintf(stderr, "sabot-sim: --battery-soc gives %d values for %d robot%s: give one, or one per robot\n",
                o->n_socs, o->robots, o->robots == 1 ? "" : "s");
        return -1;
    }
    if (o->tcp_port > 0 && o->tcp_port + o->robots - 1 > 65535) {
        fprintf(stderr, "sabot-sim: --tcp %d with %d robots needs ports up to %d, beyond 65535\n", o->tcp_port,
                o->robots, o->tcp_port + o->robots - 1);
        return -1;
    }
    return 0;
}

static int open_pty(transports_t *t, int id, const char *prefix)
{
    t->pty_master = posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (t->pty_master < 0 || grantpt(t->pty_master) || unlockpt(t->pty_master))
        return -1;
    snprintf(t->pty_path, sizeof t->pty_path, "%s", ptsname(t->pty_master));
    /* Hold the slave open: without it the master reads EIO between client sessions.
     * Raw mode, so nothing echoes or translates before a client sets its own. */
    t->pty_slave = open(t->pty_path, O_RDWR | O_NOCTTY);
    if (t->pty_slave < 0)
        return -1;
    struct termios tio;
    tcgetattr(t->pty_slave, &tio);
    cfmakeraw(&tio);
    tcsetattr(t->pty_slave, TCSANOW, &tio);
    snprintf(t->link_path, sizeof t->link_path, "%s%d", prefix, id);
    unlink(t->link_path);
    if (symlink(t->pty_path, t->link_path)) {
        fprintf(stderr, "sabot-sim: cannot link %s: %s\n", t->link_path, strerror(errno));
        t->link_path[0] = '\0';
    }
    return 0;
}

static int open_tcp(transports_t *t, int port)
{
    t->listen_fd = socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    int one = 1;
    setsockopt(t->listen_fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    struct sockaddr_in a = { .sin_family = AF_INET, .sin_port = htons((uint16_t)port),
                             .sin_addr.s_addr = htonl(INADDR_LOOPBACK) };
    if (bind(t->listen_fd, (struct sockaddr *)&a, sizeof a) || listen(t->listen_fd, 4))
        return -1;
    socklen_t len = sizeof a;
    getsockname(t->listen_fd, (struct sockaddr *)&a, &len);
    t->tcp_port = ntohs(a.sin_port);
    return 0;
}

/* Port ids on a robot's bus: 0 = pty, 1 + k = TCP client k. */
static int port_fd(const transports_t *t, int port) { return port == 0 ? t->pty_master : t->client[port - 1]; }

static void flush_answers(robot_t *r, transports_t *t)
{
    bus_frame_t f;
    while (robot_bus_take(r, &f)) {
        int fd = f.port >= 0 ? port_fd(t, f.port) : -1;
        if (fd >= 0 && write(fd, f.data, f.len) < 0 && errno != EAGAIN)
            fprintf(stderr, "sabot-sim: robot %d: write: %s\n", r->cfg.id, strerror(errno));
    }
}

static void read_requests(robot_t *r, transports_t *t, struct pollfd *pfd)
{
    uint8_t buf[512];
    if (pfd[0].revents & POLLIN) {
        ssize_t n = read(t->pty_master, buf, sizeof buf);
        if (n > 0)
            robot_bus_write(r, 0, buf, (size_t)n);
    }
    if (t->listen_fd >= 0 && (pfd[1].revents & POLLIN)) {
        int fd = accept4(t->listen_fd, NULL, NULL, SOCK_NONBLOCK | SOCK_CLOEXEC);
        for (int k = 0; fd >= 0 && k < MAX_CLIENTS; k++) {
            if (t->client[k] < 0) {
                t->client[k] = fd;
                fd = -1;
            }
        }
        if (fd >= 0)
            close(fd);   /* all client slots taken */
    }
    for (int k = 0; k < MAX_CLIENTS; k++) {
        if (t->client[k] < 0 || !(pfd[2 + k].revents & (POLLIN | POLLHUP | POLLERR)))
            continue;
        ssize_t n = read(t->client[k], buf, sizeof buf);
        if (n > 0) {
            robot_bus_write(r, 1 + k, buf, (size_t)n);
        } else if (n == 0 || errno != EAGAIN) {
            close(t->client[k]);
            t->client[k] = -1;
        }
    }
}

/* Simulated time follows the wall clock (times the speed factor) in control periods. */
typedef struct {
    robot_t *robots;
    transports_t *tr;
    int n_robots;
    scene_t *scene;
    FILE *truth;                /* NULL: no ground-truth log */
    uint64_t sim_us, next_truth_us;
    double start, speed;        /* wall clock at simulated time 0; simulated seconds per wall second */
} sim_run_t;

static void step_all(sim_run_t *run)
{
    for (int i = 0; i < run->n_robots; i++)
        robot_step(&run->robots[i]);
    scene_step(run->scene, SACT_TS_US * 1e-6);
    run->sim_us += SACT_TS_US;
    if (run->truth && run->sim_us >= run->next_truth_us) {
        run->next_truth_us += TRUTH_PERIOD_US;
        for (int i = 0; i < run->n_robots; i++) {
            const body_state_t *b = &run->robots[i].body;
            fprintf(run->truth, "%.3f,%d,%.5f,%.5f,%.5f,%.5f,%.5f,%.4f,%.4f,%.4f,%.4f,%llu\n",
                    run->sim_us * 1e-6, i + 1, b->x, b->y, b->theta, b->v, b->omega, b->wheel[0].omega,
                    b->wheel[1].omega, b->wheel[0].current, b->wheel[1].current,
                    (unsigned long long)b->collisions);
        }
    }
    /* Each answer leaves at the period its last byte is on the line, not at the end of a slice. */
    for (int i = 0; i < run->n_robots; i++)
        flush_answers(&run->robots[i], &run->tr[i]);
}

/* Steps the simulation up to the wall clock's time. When far behind (a high speed factor, a starved
 * CPU) it stops after CATCH_UP_SLICE_S of work so that the bus and the control channel stay served. */
static void catch_up(sim_run_t *run, uint64_t end_us)
{
    double began = wall_seconds();
    uint64_t target_us = (uint64_t)((began - run->start) * run->speed * 1e6);
    if (target_us > end_us)
        target_us = end_us;
    for (unsigned k = 1; run->sim_us + SACT_TS_US <= target_us && !stop_requested; k++) {
        step_all(run);
        if (k % CLOCK_CHECK_STEPS == 0 && wall_seconds() - began > CATCH_UP_SLICE_S)
            break;
    }
}

static int run_bench(const options_t *o, const world_t *world, robot_config_t *cfg)
{
    robot_t *r = calloc(1, sizeof *r);
    robot_t *list[1] = { r };
    arena_t arena = { world, list, 1, NULL };
    robot_init(r, cfg, &arena);
    /* A gentle arc (both wheels, different speeds) so every path of the step runs:
     * ramps, PID, both motors, sensors, collisions checks. */
    sact_write_register(&r->sact, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_LEFT, 400);
    sact_write_register(&r->sact, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_RIGHT, 600);
    uint64_t steps = (uint64_t)(o->bench_seconds * 1e6 / SACT_TS_US);
    double t0 = wall_seconds();
    for (uint64_t i = 0; i < steps; i++)
        robot_step(r);
    double wall = wall_seconds() - t0;

    /* The firmware's share: the control interrupt alone, on the same state. */
    const uint64_t isr_calls = 2000000;
    double t1 = wall_seconds();
    for (uint64_t i = 0; i < isr_calls; i++)
        sact_control_isr(&r->sact);
    double isr_wall = wall_seconds() - t1;

    printf("{\"speed_factor\": %.1f, \"step_ns\": %.1f, \"control_isr_ns\": %.1f, \"steps\": %llu, "
           "\"simulated_s\": %.3f, \"wall_s\": %.3f, \"pose\": [%.4f, %.4f, %.4f]}\n",
           o->bench_seconds / wall, wall * 1e9 / (double)steps, isr_wall * 1e9 / (double)isr_calls,
           (unsigned long long)steps, o->bench_seconds, wall, r->body.x, r->body.y, r->body.theta);
    free(r);
    return 0;
}

/* A robot whose footprint, where it starts, overlaps the map's obstacles (or its edge) or another robot's footprint is
 * a warning on stderr, naming the robot and its pose; the simulation still runs (robots in contact can part). The rig
 * refuses to go on after such a warning (product/bin/lib.sh, sabot_rig_start). */
static void warn_start_poses(const options_t *o, const world_t *world, double radius)
{
    for (int i = 0; i < o->robots; i++) {
        const double *p = o->starts[i];
        if (world_clearance(world, p[0], p[1]) < radius)
            fprintf(stderr, "sabot-sim: warning: robot %d starts inside an obstacle: its footprint (radius %g m) at "
                            "(%g, %g) overlaps the map's obstacles or edge\n", i + 1, radius, p[0], p[1]);
        for (int j = 0; j < i; j++) {
            const double *q = o->starts[j];
            double apart = hypot(p[0] - q[0], p[1] - q[1]);
            if (apart < 2 * radius)
                fprintf(stderr, "sabot-sim: warning: robot %d at (%g, %g) overlaps robot %d at (%g, %g): %.3f m "
                                "apart, their footprints (radius %g m) need %g m\n", i + 1, p[0], p[1], j + 1, q[0],
                        q[1], apart, radius, 2 * radius);
        }
    }
}

int main(int argc, char **argv)
{
    options_t o = { .seed = 1, .speed = 1.0, .tcp_port = -1, .control_port = -1, .robots = 1, .gear_ratio = SABOT_ROBOT_GEAR_RATIO,
                    .track = SABOT_ROBOT_TRACK_WIDTH_M, .link_prefix = "/tmp/sabot-robot", .bench_seconds = 20.0 };
    battery_params_default(&o.battery);
    if (parse_options(argc, argv, &o))
        return 2;

    char default_map[PATH_MAX], map_file[PATH_MAX], err[256];
    source_path(default_map, sizeof default_map, "maps/lab.yaml");
    source_path(map_file, sizeof map_file, "../docs/sact-modbus-map.json");
    const char *map_path = o.map_path ? o.map_path : default_map;
    world_t world;
    if (world_load(&world, map_path, err, sizeof err)) {
        fprintf(stderr, "sabot-sim: %s\n", err);
        return 2;
    }
    if (!o.n_starts) {
        if (!o.start_given) {
            /* Default start: map centre. */
            o.start_x = world.origin_x + world.width * world.resolution / 2.0;
            o.start_y = world.origin_y + world.height * world.resolution / 2.0;
        }
        for (int i = 0; i < o.robots; i++) {
            o.starts[i][0] = o.start_x;
            o.starts[i][1] = o.start_y + START_SPACING_Y * i;
            o.starts[i][2] = o.start_theta;
        }
    }

    robot_config_t base;
    robot_config_default(&base);
    base.params.gear_ratio = o.gear_ratio;
    base.params.track = o.track;
    base.faults = o.faults;
    base.seed = o.seed;
    base.x = o.starts[0][0];
    base.y = o.starts[0][1];
    base.theta = o.starts[0][2];
    base.battery = o.battery;
    base.battery_soc = o.n_socs ? o.battery_soc[0] : 1.0;
    if (o.bench)
        return run_bench(&o, &world, &base);
    warn_start_poses(&o, &world, base.params.radius);

    static robot_t robots[MAX_ROBOTS];
    static robot_t *robot_list[MAX_ROBOTS];
    static transports_t tr[MAX_ROBOTS];
    static scene_t scene;
    arena_t arena = { &world, robot_list, o.robots, &scene };
    for (int i = 0; i < o.robots; i++) {
        robot_config_t cfg = base;
        cfg.id = i + 1;
        cfg.seed = o.seed * 7919u + (uint64_t)i;   /* distinct, reproducible streams per robot */
        cfg.x = o.starts[i][0];
        cfg.y = o.starts[i][1];
        cfg.theta = o.starts[i][2];
        if (o.n_socs > 1)
            cfg.battery_soc = o.battery_soc[i];
        robot_list[i] = &robots[i];
        robot_init(&robots[i], &cfg, &arena);
        transports_t *t = &tr[i];
        t->listen_fd = -1;
        for (int k = 0; k < MAX_CLIENTS; k++)
            t->client[k] = -1;
        if (open_pty(t, i + 1, o.link_prefix)) {
            fprintf(stderr, "sabot-sim: pty: %s\n", strerror(errno));
            return 1;
        }
        if (o.tcp_port >= 0 && open_tcp(t, o.tcp_port ? o.tcp_port + i : 0)) {
            fprintf(stderr, "sabot-sim: tcp port %d: %s\n", o.tcp_port + i, strerror(errno));
            return 1;
        }
    }

    sim_run_t run = { robots, tr, o.robots, &scene, NULL, 0, 0, 0.0, o.speed };
    control_server_t control = { .listen_fd = -1 };
    control_target_t target = { &scene, robots, o.robots, &run.sim_us };
    if (o.control_port >= 0 && control_open(&control, o.control_port)) {
        fprintf(stderr, "sabot-sim: control port %d: %s\n", o.control_port, strerror(errno));
        return 1;
    }

    FILE *truth = NULL;
    if (o.truth_path) {
        truth = fopen(o.truth_path, "w");
        if (!truth) {
            fprintf(stderr, "sabot-sim: %s: %s\n", o.truth_path, strerror(errno));
            return 1;
        }
        fprintf(truth, "t_s,robot,x_m,y_m,theta_rad,v_m_s,omega_rad_s,wheel_left_rad_s,wheel_right_rad_s,"
                       "current_left_a,current_right_a,collisions\n");
    }

    /* Handlers before the announcement: a supervisor may signal as soon as it reads it. */
    struct sigaction sa = { .sa_handler = on_signal };
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGINT, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);
    printf("{\"robots\": [");
    for (int i = 0; i < o.robots; i++) {
        printf("%s{\"id\": %d, \"pty\": \"%s\", \"link\": \"%s\", \"tcp\": %d, "
               "\"slaves\": {\"sact\": %d, \"ins\": %d, \"sonar\": %d, \"landmark\": %d, \"power\": %d}}",
               i ? ", " : "", i + 1, tr[i].pty_path, tr[i].link_path, o.tcp_port >= 0 ? tr[i].tcp_port : -1,
               MB_SACT_ADDRESS, MB_INS_ADDRESS, MB_SONAR_ADDRESS, MB_LANDMARK_ADDRESS, MB_POWER_ADDRESS);
    }
    printf("], \"seed\": %llu, \"speed\": %g, \"map\": \"%s\", \"map_file\": \"%s\", \"baud\": %d, "
           "\"landmarks\": %d, \"docks\": %d",
           (unsigned long long)o.seed, o.speed, map_path, map_file, MB_SERIAL_BAUD, world.n_landmarks, world.n_docks);
    if (control.listen_fd >= 0)
        printf(", \"control\": %d", control.port);
    printf("}\n");
    fflush(stdout);


    run.truth = truth;
    /* Wake for a bus event when it is due, not up to 50 µs later (the default timer slack). */
    prctl(PR_SET_TIMERSLACK, 1UL);
    run.start = wall_seconds();
    uint64_t end_us = o.duration > 0 ? (uint64_t)(o.duration * 1e6) : UINT64_MAX;
    unsigned late_wakes = 0;
    double last_late_report = 0;
    while (!stop_requested && run.sim_us < end_us) {
        catch_up(&run, end_us);

        /* Sleep until a bus needs a step (a request's end, an answer due), or IDLE_WAKE_US; a master's bytes or
         * a control command wake it sooner. */
        struct pollfd pfd[MAX_ROBOTS][2 + MAX_CLIENTS];
        struct pollfd flat[MAX_ROBOTS * (2 + MAX_CLIENTS) + CONTROL_POLLFDS];
        int nfds = 0;
        uint64_t wake_us = run.sim_us + IDLE_WAKE_US;
        if (wake_us > end_us)
            wake_us = end_us;
        for (int i = 0; i < o.robots; i++) {
            pfd[i][0] = (struct pollfd){ tr[i].pty_master, POLLIN, 0 };
            pfd[i][1] = (struct pollfd){ tr[i].listen_fd, POLLIN, 0 };
            for (int k = 0; k < MAX_CLIENTS; k++)
                pfd[i][2 + k] = (struct pollfd){ tr[i].client[k], POLLIN, 0 };
            for (int k = 0; k < 2 + MAX_CLIENTS; k++)
                flat[nfds++] = pfd[i][k];
            uint64_t event = robot_bus_next_event(&robots[i]);
            if (event < wake_us)
                wake_us = event;
        }
        struct pollfd *control_pfd = &flat[nfds];
        control_pollfds(&control, control_pfd);
        nfds += CONTROL_POLLFDS;
        /* The step that reaches an event ends at the first period boundary at or after it. */
        wake_us = (wake_us + SACT_TS_US - 1) / SACT_TS_US * SACT_TS_US;
        double wait_s = run.start + (double)wake_us * 1e-6 / run.speed - wall_seconds();
        if (wait_s < 0)
            wait_s = 0;
        struct timespec timeout = { (time_t)wait_s, (long)((wait_s - floor(wait_s)) * 1e9) };
        double due = run.start + (double)wake_us * 1e-6 / run.speed;
        int ready = ppoll(flat, (nfds_t)nfds, &timeout, NULL);
        double late = wall_seconds() - due;
        if (ready == 0 && late > LATE_WAKE_S) {
            /* The host did not run the simulator in time, or it cannot keep up with --speed: answers due meanwhile
             * left late too, so a master's timeouts then are the host's, not the bus's. */
            if (wall_seconds() - last_late_report >= 1.0) {
                fprintf(stderr, "sabot-sim: woke %.0f ms late at t=%.3f s: answers due meanwhile left late "
                                "(%u such wake-ups so far)\n", late * 1e3, run.sim_us * 1e-6, late_wakes + 1);
                last_late_report = wall_seconds();
            }
            late_wakes++;
        }
        if (ready > 0) {
            /* Bring the simulation to now first: a request's bytes reach the line when they came. */
            catch_up(&run, end_us);
            for (int i = 0; i < o.robots; i++) {
                for (int k = 0; k < 2 + MAX_CLIENTS; k++)
                    pfd[i][k].revents = flat[i * (2 + MAX_CLIENTS) + k].revents;
                read_requests(&robots[i], &tr[i], pfd[i]);
            }
            control_serve(&control, control_pfd, &target);
        }
    }

    if (truth) {
        /* The simulation may have slept since the last bus event or command, the last instant anyone observed: the
         * log goes on to its next row, so that a reader finds rows either side of that instant. */
        for (uint64_t row = run.next_truth_us; run.sim_us < row;)
            step_all(&run);
    }
    control_close(&control);

    for (int i = 0; i < o.robots; i++) {
        if (tr[i].link_path[0])
            unlink(tr[i].link_path);
        close(tr[i].pty_slave);
        close(tr[i].pty_master);
        if (tr[i].listen_fd >= 0)
            close(tr[i].listen_fd);
        for (int k = 0; k < MAX_CLIENTS; k++)
            if (tr[i].client[k] >= 0)
                close(tr[i].client[k]);
    }
    if (truth)
        fclose(truth);
    world_free(&world);
    return 0;
}
