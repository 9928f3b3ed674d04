/*
 * A real sabot-sim process, driven as tests and demos drive it: its command line,
 * its control channel (obstacles, people, board links, ground truth) and its bus over
 * TCP. The simulator beside this binary is used (build/sabot-sim, or the sanitized
 * build/san/sabot-sim for the sanitized suite). Every wait is on a condition with a
 * deadline; the only fixed waits are the ones that prove silence on the bus.
 */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "bus_client.h"
#include "check.h"

#define DEADLINE_S 5.0
/* encoder counts per metre of wheel rim, for the described robot */
#define COUNTS_PER_M (4.0 * SABOT_ROBOT_ENCODER_LINES * SABOT_ROBOT_GEAR_RATIO / (2 * M_PI * SABOT_ROBOT_WHEEL_RADIUS_M))
#define SILENCE_MS 150       /* an answer takes ~1 ms at 115200 baud; 150 ms of nothing is silence */

static char sim_path[PATH_MAX], tmp_dir[PATH_MAX];

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

typedef struct {
    pid_t pid;
    int out_fd, err_fd;
    char first_line[2048];
    int control_port, tcp_port;
} sim_t;

/* Reads fd until a newline or EOF or the deadline; returns the bytes read. */
static size_t read_until_newline(int fd, char *buf, size_t len, double deadline)
{
    size_t n = 0;
    while (n + 1 < len && now_s() < deadline) {
        struct pollfd p = { fd, POLLIN, 0 };
        if (poll(&p, 1, (int)((deadline - now_s()) * 1000) + 1) <= 0)
            continue;
        ssize_t k = read(fd, buf + n, 1);
        if (k <= 0)
            break;
        if (buf[n++] == '\n')
            break;
    }
    buf[n] = '\0';
    return n;
}

/* Starts sabot-sim with the given arguments (NULL-terminated) and reads its first line. */
static bool sim_start(sim_t *s, const char *const *args)
{
    const char *argv[32];
    int n = 0;
    argv[n++] = sim_path;
    for (int i = 0; args[i]; i++)
        argv[n++] = args[i];
    argv[n] = NULL;
    int out[2], err[2];
    if (pipe(out) || pipe(err))
        return false;
    s->pid = fork();
    if (s->pid == 0) {
        dup2(out[1], 1);
        dup2(err[1], 2);
        close(out[0]);
        close(err[0]);
        execv(sim_path, (char *const *)argv);
        _exit(127);
    }
    close(out[1]);
    close(err[1]);
    s->out_fd = out[0];
    s->err_fd = err[0];
    read_until_newline(s->out_fd, s->first_line, sizeof s->first_line, now_s() + DEADLINE_S);
    const char *c = strstr(s->first_line, "\"control\": ");
    s->control_port = c ? atoi(c + 11) : -1;
    const char *t = strstr(s->first_line, "\"tcp\": ");
    s->tcp_port = t ? atoi(t + 7) : -1;
    return s->first_line[0] == '{';
}

/* Exit status after SIGTERM (or of an exited process), -1 if it did not end in time. */
static int sim_stop(sim_t *s)
{
    kill(s->pid, SIGTERM);
    int status = 0;
    double deadline = now_s() + DEADLINE_S;
    pid_t done = 0;
    while ((done = waitpid(s->pid, &status, WNOHANG)) == 0 && now_s() < deadline) {
        struct pollfd p = { s->err_fd, POLLIN, 0 };   /* wakes on the pipe closing at exit */
        if (poll(&p, 1, 20) > 0) {
            char sink[256];
            if (read(s->err_fd, sink, sizeof sink) <= 0)
                p.fd = -1;
        }
    }
    close(s->out_fd);
    close(s->err_fd);
    if (done != s->pid) {
        kill(s->pid, SIGKILL);
        waitpid(s->pid, &status, 0);
        return -1;
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

static bool sim_alive(const sim_t *s)
{
    int status;
    return waitpid(s->pid, &status, WNOHANG) == 0;
}

static int connect_to(int port)
{
    int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    struct sockaddr_in a = { .sin_family = AF_INET, .sin_port = htons((uint16_t)port),
                             .sin_addr.s_addr = htonl(INADDR_LOOPBACK) };
    if (connect(fd, (struct sockaddr *)&a, sizeof a)) {
        close(fd);
        return -1;
    }
    return fd;
}

/* Sends one control command and returns its answer line (without the newline). */
static const char *command(int fd, const char *fmt, ...)
{
    static char answer[8192];
    char line[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line - 1, fmt, ap);
    va_end(ap);
    strcat(line, "\n");
    if (write(fd, line, strlen(line)) != (ssize_t)strlen(line))
        return "(write failed)";
    size_t n = read_until_newline(fd, answer, sizeof answer, now_s() + DEADLINE_S);
    if (n == 0 || answer[n - 1] != '\n')
        return "(no answer)";
    answer[n - 1] = '\0';
    return answer;
}

typedef struct {
    double t, x, y, theta, v, omega;
    unsigned long long contacts;
} truth_t;

static bool truth(int fd, int robot, truth_t *out)
{
    const char *a = command(fd, "truth %d", robot);
    return sscanf(a, "ok t=%lf x=%lf y=%lf theta=%lf v=%lf omega=%lf contacts=%llu", &out->t, &out->x, &out->y,
                  &out->theta, &out->v, &out->omega, &out->contacts) == 7;
}

/* One Modbus RTU exchange over TCP; returns the answer length, 0 on silence. */
static size_t modbus(int fd, const frame_t *req, frame_t *ans, int silence_ms)
{
    if (write(fd, req->data, req->len) != (ssize_t)req->len)
        return 0;
    ans->len = 0;
    size_t want = 3;
    double deadline = now_s() + silence_ms / 1000.0;
    while (ans->len < want && now_s() < deadline) {
        struct pollfd p = { fd, POLLIN, 0 };
        if (poll(&p, 1, (int)((deadline - now_s()) * 1000) + 1) <= 0)
            continue;
        ssize_t k = read(fd, ans->data + ans->len, want - ans->len);
        if (k <= 0)
            return 0;
        ans->len += (size_t)k;
        if (ans->len >= 3)
            want = (ans->data[1] & 0x80) ? 5 : 3 + ans->data[2] + 2u;
    }
    return ans->len == want ? ans->len : 0;
}

static long tcp_read(int fd, uint8_t address, uint16_t file, uint16_t record)
{
    frame_t req = read_request(address, file, record, 1), ans;
    if (modbus(fd, &req, &ans, 1000) != 9 || answer_exception(&ans) != 0)
        return -1;
    return (ans.data[5] << 8) | ans.data[6];
}

static int tcp_write(int fd, uint8_t address, uint16_t file, uint16_t record, const uint16_t *values, uint16_t n)
{
    frame_t req = write_request(address, file, record, values, n), ans;
    if (modbus(fd, &req, &ans, 1000) == 0)
        return -1;
    return answer_exception(&ans);
}

/* The board at `address` answers nothing within SILENCE_MS. */
static bool silent(int fd, uint8_t address)
{
    frame_t req = read_request(address, 2, 0, 1), ans;
    return modbus(fd, &req, &ans, SILENCE_MS) == 0;
}

/* Sonar centre sensor (1): range in mm, 0 when no echo. */
static long centre_range(int bus)
{
    return tcp_read(bus, MB_SONAR_ADDRESS, MB_SONAR_FILE_LATEST, 6 + 2);
}

/* Waits (polling the bus) until the centre sensor has pinged twice more and its
 * range satisfies lo <= range <= hi; returns the last range read. */
static long await_centre_range(int bus, long lo, long hi)
{
    double deadline = now_s() + DEADLINE_S;
    long seq0 = tcp_read(bus, MB_SONAR_ADDRESS, MB_SONAR_FILE_LATEST, 6), range = -1;
    while (now_s() < deadline) {
        long seq = tcp_read(bus, MB_SONAR_ADDRESS, MB_SONAR_FILE_LATEST, 6);
        range = centre_range(bus);
        if (seq >= 0 && ((seq - seq0) & 0xFFFF) >= 2 && range >= lo && range <= hi)
            return range;
    }
    return range;
}

#define SIM_ARGS(...) ((const char *const[]){ __VA_ARGS__, NULL })

static void start_lab_robot(sim_t *s, const char *truth_csv)
{
    char link[PATH_MAX + 16];
    snprintf(link, sizeof link, "%s/ctl-robot", tmp_dir);
    bool ok = truth_csv ? sim_start(s, SIM_ARGS("--control", "0", "--tcp", "0", "--start", "6,6.5,0", "--link", link,
                                                "--truth", truth_csv))
                        : sim_start(s, SIM_ARGS("--control", "0", "--tcp", "0", "--start", "6,6.5,0", "--link", link));
    CHECK(ok && s->control_port > 0 && s->tcp_port > 0, "first line: %s", s->first_line);
}

#define FOUR_POSES "1,1,0/1,1,0/1,1,0/1,1,0/"
#define SEVENTEEN_POSES FOUR_POSES FOUR_POSES FOUR_POSES FOUR_POSES "1,1,0"

static void badArgumentsAreRefusedWithStatusTwoAndAMessage(void)
{
    static const struct {
        const char *args[5];
        const char *message;
    } cases[] = {
        { { "--tcp", "99999" }, "--tcp wants an integer in 0..65535" },
        { { "--tcp", "-1" }, "--tcp wants an integer in 0..65535" },
        { { "--control", "http" }, "--control wants an integer in 0..65535" },
        { { "--fault-crc", "1.5" }, "--fault-crc wants a number in 0..1" },
        { { "--fault-drop", "-0.1" }, "--fault-drop wants a number in 0..1" },
        { { "--speed", "0" }, "--speed wants a number > 0" },
        { { "--gear-ratio", "-43" }, "--gear-ratio wants a number > 0" },
        { { "--track", "wide" }, "--track wants a number" },
        { { "--robots", "17" }, "--robots wants an integer in 1..16" },
        { { "--seed", "1x" }, "--seed wants an integer" },
        { { "--start", "1,2" }, "--start wants X,Y,THETA" },
        { { "--starts", "1,1,0/1,2" }, "pose 2 is '1,2' in '1,1,0/1,2'" },
        { { "--starts", "1,1,0/" }, "pose 2 is '' in '1,1,0/'" },
        { { "--starts", "1,1,0/2,2,0", "--robots", "3" }, "--starts gives 2 poses for 3 robots (--robots 3)" },
        { { "--robots", "1", "--starts", "1,1,0/2,2,0" }, "--starts gives 2 poses for 1 robot (--robots 1)" },
        { { "--start", "1,1,0", "--starts", "1,1,0" }, "--start and --starts: give one or the other" },
        { { "--starts", SEVENTEEN_POSES }, "--starts gives more than 16 poses (at most 16 robots)" },
        { { "--starts", "1,1,0/2,2,0", "--tcp", "65535" }, "--tcp 65535 with 2 robots needs ports up to 65536" },
        { { "--tcp", "65535", "--robots", "2" }, "beyond 65535" },
        { { "--frobnicate" }, "unknown option '--frobnicate'" },
        { { "--tcp" }, "--tcp wants an argument" },
        { { "stray" }, "unexpected argument 'stray'" },
        { { "--map", "/nonexistent/lab.yaml" }, "map /nonexistent/lab.yaml: No such file or directory" },
        { { "--battery-capacity", "0" }, "--battery-capacity wants a number in 0.001..65.535, got '0'" },
        { { "--battery-capacity", "70" }, "--battery-capacity wants a number in 0.001..65.535, got '70'" },
        { { "--battery-soc", "1.5" }, "value 1 is '1.5' in '1.5'" },
        { { "--battery-soc", "0.5/low" }, "value 2 is 'low' in '0.5/low'" },
        { { "--battery-soc", "0.5/" }, "value 2 is '' in '0.5/'" },
        { { "--battery-soc", "0.5/0.6", "--robots", "3" }, "--battery-soc gives 2 values for 3 robots" },
        { { "--battery-base-load", "-1" }, "--battery-base-load wants a number in 0..1000" },
        { { "--battery-charge", "0" }, "--battery-charge wants a number > 0" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sim_t s;
        /* should one be wrongly accepted, it still ends */
        const char *args[8] = { "--duration", "0.01" };
        int n = 2;
        for (int k = 0; k < 5 && cases[i].args[k]; k++)
            args[n++] = cases[i].args[k];
        sim_start(&s, args);
        char err[1024];
        size_t len = read_until_newline(s.err_fd, err, sizeof err, now_s() + DEADLINE_S);
        int status = sim_stop(&s);
        CHECK(status == 2, "%s %s: exit status %d", cases[i].args[0], cases[i].args[1] ? cases[i].args[1] : "",
              status);
        CHECK(len > 0 && strstr(err, cases[i].message), "%s: message '%s', expected '%s'", cases[i].args[0],
              strtok(err, "\n"), cases[i].message);
        CHECK(s.first_line[0] == '\0', "started anyway: %s", s.first_line);
    }
}

/* Each robot stands where its pose says: the truth over the control channel. */
static void check_poses(const sim_t *s, int n, const double (*poses)[3])
{
    int ctl = connect_to(s->control_port);
    for (int i = 0; i < n; i++) {
        truth_t t = { 0 };
        CHECK(truth(ctl, i + 1, &t), "truth %d", i + 1);
        CHECK(fabs(t.x - poses[i][0]) < 1e-3 && fabs(t.y - poses[i][1]) < 1e-3 && fabs(t.theta - poses[i][2]) < 1e-3,
              "robot %d at (%.4f, %.4f, %.4f), expected (%g, %g, %g)", i + 1, t.x, t.y, t.theta, poses[i][0],
              poses[i][1], poses[i][2]);
    }
    char none[64];
    snprintf(none, sizeof none, "error no robot '%d' (robots are 1..%d)", n + 1, n);
    const char *a = command(ctl, "truth %d", n + 1);
    CHECK(!strcmp(a, none), "truth %d: %s", n + 1, a);
    close(ctl);
}

/* Nothing on stderr yet: a start pose's warning comes before the first stdout line, so it would be in the pipe. */
static bool no_warning(const sim_t *s)
{
    struct pollfd p = { s->err_fd, POLLIN, 0 };
    return poll(&p, 1, 0) == 0;
}

static void theStartsOptionPlacesEachRobotAndCountsThem(void)
{
    char link[PATH_MAX + 16];
    snprintf(link, sizeof link, "%s/starts-robot", tmp_dir);
    /* two-rooms: one robot in each room, one in the door between them (maps/make_two_rooms.py) */
    static const double three[3][3] = { { 1.0, 1.0, 0.0 }, { 5.0, 1.0, 3.14 }, { 4.3, 2.2, 1.5708 } };
    sim_t s;
    CHECK(sim_start(&s, SIM_ARGS("--map", "maps/two-rooms.yaml", "--control", "0", "--link", link, "--starts",
                                 "1.0,1.0,0/5.0,1.0,3.14/4.3,2.2,1.5708")),
          "start: %s", s.first_line);
    CHECK(strstr(s.first_line, "\"id\": 3,") && !strstr(s.first_line, "\"id\": 4,"),
          "not three robots: %s", s.first_line);
    CHECK(no_warning(&s), "a warning for free, distinct start poses");
    check_poses(&s, 3, three);
    CHECK(sim_stop(&s) == 0, "exit status");

    /* --starts with as many poses as --robots */
    static const double two[2][3] = { { 1.0, 3.0, -1.0 }, { 7.5, 3.5, 2.0 } };
    CHECK(sim_start(&s, SIM_ARGS("--map", "maps/two-rooms.yaml", "--control", "0", "--link", link, "--robots", "2",
                                 "--starts", "1,3,-1/7.5,3.5,2")),
          "start: %s", s.first_line);
    check_poses(&s, 2, two);
    CHECK(sim_stop(&s) == 0, "exit status");

    /* --start as before: robot 1 there, the others 0.8 m apart in y */
    static const double spaced[2][3] = { { 1.0, 1.0, 0.5 }, { 1.0, 1.8, 0.5 } };
    CHECK(sim_start(&s, SIM_ARGS("--map", "maps/two-rooms.yaml", "--control", "0", "--link", link, "--robots", "2",
                                 "--start", "1,1,0.5")),
          "start: %s", s.first_line);
    CHECK(no_warning(&s), "a warning for free, distinct start poses");
    check_poses(&s, 2, spaced);
    CHECK(sim_stop(&s) == 0, "exit status");
}

static void aStartPoseInAWallOrOnAnotherRobotIsAWarningNamingTheRobot(void)
{
    char link[PATH_MAX + 16];
    snprintf(link, sizeof link, "%s/starts-robot", tmp_dir);
    sim_t s;
    /* robot 1 in the wall between the rooms, robot 3 0.32 m from robot 2 */
    CHECK(sim_start(&s, SIM_ARGS("--duration", "0.01", "--map", "maps/two-rooms.yaml", "--link", link, "--starts",
                                 "4.3,1,0/1,1,0/1.3,1.1,0")),
          "start: %s", s.first_line);
    char wall[512], overlap[512];
    read_until_newline(s.err_fd, wall, sizeof wall, now_s() + DEADLINE_S);
    read_until_newline(s.err_fd, overlap, sizeof overlap, now_s() + DEADLINE_S);
    CHECK(strstr(wall, "sabot-sim: warning: robot 1 starts inside an obstacle: its footprint (radius 0.25 m) at "
                       "(4.3, 1) overlaps the map's obstacles or edge"),
          "%s", wall);
    CHECK(strstr(overlap, "sabot-sim: warning: robot 3 at (1.3, 1.1) overlaps robot 2 at (1, 1): 0.316 m apart, their "
                          "footprints (radius 0.25 m) need 0.5 m"),
          "%s", overlap);
    CHECK(sim_stop(&s) == 0, "exit status");
}

static void anObstacleAheadEchoesAtItsRangeAndIsGoneWhenRemoved(void)
{
    sim_t s;
    start_lab_robot(&s, NULL);
    int ctl = connect_to(s.control_port), bus = connect_to(s.tcp_port);
    uint16_t hold = 0;
    CHECK(tcp_write(bus, MB_SONAR_ADDRESS, MB_SONAR_FILE_CONFIG, MB_SONAR_CONFIG_SWEEP_ENABLE, &hold, 1) == 0,
          "sweep off");
    /* nothing within the 4 m range of the centre sensor's cone from (6, 6.5) looking east */
    long none = await_centre_range(bus, 0, 0);
    CHECK(none == 0, "echo %ld mm before any obstacle", none);
    const char *a = command(ctl, "obstacle add crate 7.5 6.5 0.3");
    CHECK(!strcmp(a, "ok obstacle crate added"), "%s", a);
    /* sensor 0.20 m ahead of the centre (x 6.20), crate face at 7.20: 1.000 m */
    long range = await_centre_range(bus, 960, 1040);
    CHECK(labs(range - 1000) <= 40, "crate echo at %ld mm, expected 1000", range);
    long x = tcp_read(bus, MB_SONAR_ADDRESS, MB_SONAR_FILE_LATEST, 6 + 3);
    CHECK(labs(x - 1200) <= 40, "crate at x %ld mm from the centre, expected 1200", x);
    a = command(ctl, "obstacle move crate 7.0 6.5");
    CHECK(!strcmp(a, "ok obstacle crate moved"), "%s", a);
    range = await_centre_range(bus, 460, 540);
    CHECK(labs(range - 500) <= 40, "moved crate echo at %ld mm, expected 500", range);
    a = command(ctl, "obstacle remove crate");
    CHECK(!strcmp(a, "ok obstacle crate removed"), "%s", a);
    none = await_centre_range(bus, 0, 0);
    CHECK(none == 0, "echo %ld mm after the crate was removed", none);
    /* a person standing there echoes too (disc of 0.25 m: face at 7.20 m) */
    a = command(ctl, "person add carol 7.45 6.5 0 0");
    CHECK(!strcmp(a, "ok person carol added"), "%s", a);
    range = await_centre_range(bus, 960, 1040);
    CHECK(labs(range - 1000) <= 40, "person echo at %ld mm, expected 1000", range);
    CHECK(!strcmp(command(ctl, "person remove carol"), "ok person carol removed"), "remove");
    close(ctl);
    close(bus);
    CHECK(sim_stop(&s) == 0, "exit status");
}

/* `board 1 NAME off` silences that board and no other; `on` brings it back. */
static void switch_board_off_and_on(int ctl, int bus, const char *name, uint8_t address, uint8_t other)
{
    char expected[64];
    CHECK(!silent(bus, address), "%s silent before being switched off", name);
    const char *a = command(ctl, "board 1 %s off", name);
    snprintf(expected, sizeof expected, "ok robot 1 %s off", name);
    CHECK(!strcmp(a, expected), "%s, expected %s", a, expected);
    CHECK(silent(bus, address), "%s still answers", name);
    CHECK(!silent(bus, other), "board %u went silent with the %s", other, name);
    a = command(ctl, "board 1 %s on", name);
    snprintf(expected, sizeof expected, "ok robot 1 %s on", name);
    CHECK(!strcmp(a, expected), "%s, expected %s", a, expected);
    CHECK(!silent(bus, address), "%s silent after being switched on", name);
}

static void aBoardSwitchedOffIsSilentAndItsDeadmanStillStopsTheRobot(void)
{
    sim_t s;
    start_lab_robot(&s, NULL);
    int ctl = connect_to(s.control_port), bus = connect_to(s.tcp_port);
    switch_board_off_and_on(ctl, bus, "sonar", MB_SONAR_ADDRESS, MB_INS_ADDRESS);
    const char *a;

    /* Deadman 200 ms, then 0.2 m/s forward: in 8.8 counts per Ts. */
    uint16_t timeout = 200;
    CHECK(tcp_write(bus, MB_SACT_ADDRESS, MB_SACT_FILE_CONFIG, MB_SACT_CONFIG_COMMAND_TIMEOUT, &timeout, 1) == 0,
          "deadman");
    double counts_per_m = COUNTS_PER_M;
    uint16_t speed = (uint16_t)lround(0.2 * counts_per_m * 50e-6 * 256.0), both[2] = { speed, speed };
    CHECK(tcp_write(bus, MB_SACT_ADDRESS, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_LEFT, both, 2) == 0,
          "drive");
    truth_t t = { 0 };
    double deadline = now_s() + DEADLINE_S;
    while (now_s() < deadline && truth(ctl, 1, &t) && t.v < 0.15) {
        /* keep the deadman fed until the robot is under way */
        tcp_write(bus, MB_SACT_ADDRESS, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_LEFT, both, 2);
    }
    CHECK(t.v >= 0.15, "robot did not start: v %.3f", t.v);
    a = command(ctl, "board 1 sact off");
    CHECK(!strcmp(a, "ok robot 1 sact off"), "%s", a);
    CHECK(silent(bus, MB_SACT_ADDRESS), "SACT still answers");
    truth_t cut = t;
    deadline = now_s() + DEADLINE_S;
    while (now_s() < deadline && truth(ctl, 1, &t) && fabs(t.v) > 0.005)
        continue;
    CHECK(fabs(t.v) <= 0.005, "still moving at %.3f m/s with the link cut", t.v);
    /* 200 ms at 0.2 m/s, then a 0.5 m/s^2 ramp down: about 0.08 m */
    CHECK(t.x - cut.x < 0.2, "rolled %.3f m after the cut", t.x - cut.x);
    a = command(ctl, "board 1 sact on");
    CHECK(!strcmp(a, "ok robot 1 sact on"), "%s", a);
    CHECK(!silent(bus, MB_SACT_ADDRESS), "SACT silent after being switched on");
    close(ctl);
    close(bus);
    CHECK(sim_stop(&s) == 0, "exit status");
}

static void aJammedWheelLatchesAFollowingErrorAndTheBoardRefusesToDrive(void)
{
    sim_t s;
    start_lab_robot(&s, NULL);
    int ctl = connect_to(s.control_port), bus = connect_to(s.tcp_port);
    uint16_t speed = (uint16_t)lround(0.2 * COUNTS_PER_M * 50e-6 * 256.0), both[2] = { speed, speed };
    truth_t t = { 0 };
    double deadline = now_s() + DEADLINE_S;
    while (now_s() < deadline && truth(ctl, 1, &t) && t.v < 0.15)
        tcp_write(bus, MB_SACT_ADDRESS, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_LEFT, both, 2);
    CHECK(t.v >= 0.15, "robot did not start: v %.3f", t.v);
    const char *a = command(ctl, "wheel 1 left jam");
    CHECK(!strcmp(a, "ok robot 1 left wheel jammed"), "%s", a);
    /* The commanded position runs away from the stalled motor's: the firmware's following-error check latches. */
    long status = 0;
    deadline = now_s() + DEADLINE_S;
    while (now_s() < deadline && !((status = tcp_read(bus, MB_SACT_ADDRESS, MB_SACT_FILE_MOTOR_LEFT,
                                                       MB_SACT_MOTOR_STATUS)) & MB_SACT_MOTOR_STATUS_FAULT))
        continue;
    CHECK(status > 0 && (status & MB_SACT_MOTOR_STATUS_FAULT) && (status & MB_SACT_MOTOR_STATUS_FOLLOWING_ERROR),
          "left status 0x%lx, expected a latched following error", status);
    CHECK(tcp_write(bus, MB_SACT_ADDRESS, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_LEFT, both, 2) ==
              MB_SERVER_DEVICE_FAILURE, "a drive command was accepted with a latched fault");
    uint16_t stop[2] = { 0, 0 };
    CHECK(tcp_write(bus, MB_SACT_ADDRESS, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_LEFT, stop, 2) == 0,
          "a stop was refused");
    a = command(ctl, "wheel 1 left free");
    CHECK(!strcmp(a, "ok robot 1 left wheel free"), "%s", a);
    uint16_t ack = 0;
    CHECK(tcp_write(bus, MB_SACT_ADDRESS, MB_SACT_FILE_MOTOR_LEFT, MB_SACT_MOTOR_STATUS, &ack, 1) == 0, "acknowledge");
    CHECK(tcp_write(bus, MB_SACT_ADDRESS, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_LEFT, both, 2) == 0,
          "drive refused after the fault was acknowledged");
    close(ctl);
    close(bus);
    CHECK(sim_stop(&s) == 0, "exit status");
}

static void drivingIntoAnObstacleCountsContacts(void)
{
    sim_t s;
    start_lab_robot(&s, NULL);
    int ctl = connect_to(s.control_port), bus = connect_to(s.tcp_port);
    CHECK(!strncmp(command(ctl, "obstacle add post 6.7 6.5 0.2"), "ok", 2), "add");
    double counts_per_m = COUNTS_PER_M;
    uint16_t speed = (uint16_t)lround(0.2 * counts_per_m * 50e-6 * 256.0), both[2] = { speed, speed };
    CHECK(tcp_write(bus, MB_SACT_ADDRESS, MB_SACT_FILE_DRIVE, MB_SACT_DRIVE_VELOCITY_SETPOINT_LEFT, both, 2) == 0,
          "drive");
    truth_t t = { 0 };
    double deadline = now_s() + DEADLINE_S;
    while (now_s() < deadline && truth(ctl, 1, &t) && t.contacts == 0)
        continue;
    CHECK(t.contacts > 0, "no contact; robot at x %.3f", t.x);
    CHECK(t.x <= 6.7 - 0.45 + 1e-3, "drove into the post: x %.3f", t.x);
    close(ctl);
    close(bus);
    CHECK(sim_stop(&s) == 0, "exit status");
}

/* Rows of the truth CSV for robot 1 either side of time t. */
static bool csv_bracket(const char *path, double t, truth_t *before, truth_t *after)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return false;
    char line[512];
    bool have_before = false, have_after = false;
    if (!fgets(line, sizeof line, f)) {
        fclose(f);
        return false;
    }
    while (fgets(line, sizeof line, f) && !have_after) {
        truth_t r;
        int robot;
        if (sscanf(line, "%lf,%d,%lf,%lf,%lf,%lf,%lf,%*f,%*f,%*f,%*f,%llu", &r.t, &robot, &r.x, &r.y, &r.theta, &r.v,
                   &r.omega, &r.contacts) != 8 || robot != 1)
            continue;
        if (r.t <= t + 1e-9) {
            *before = r;
            have_before = true;
        }
        if (r.t >= t - 1e-9) {
            *after = r;
            have_after = true;
        }
    }
    fclose(f);
    return have_before && have_after;
}

static bool between(double v, double a, double b) { return v >= fmin(a, b) - 1e-5 && v <= fmax(a, b) + 1e-5; }

static void aPersonWalkingIntoTheRobotIsAContactAndTruthAgreesWithTheCsv(void)
{
    char csv[PATH_MAX + 16];
    snprintf(csv, sizeof csv, "%s/ctl-truth.csv", tmp_dir);
    sim_t s;
    start_lab_robot(&s, csv);
    int ctl = connect_to(s.control_port), bus = connect_to(s.tcp_port);
    truth_t t = { 0 };
    CHECK(truth(ctl, 1, &t) && t.contacts == 0, "contacts at start: %llu", t.contacts);
    /* discs touch at 0.50 m between centres: the person reaches the robot after 0.2 s */
    const char *a = command(ctl, "person add alice 5.4 6.5 0.5 0");
    CHECK(!strcmp(a, "ok person alice added"), "%s", a);
    /* people walk: by the time of the contact she is past her start */
    double deadline = now_s() + DEADLINE_S;
    while (now_s() < deadline && truth(ctl, 1, &t) && t.contacts == 0)
        continue;
    CHECK(t.contacts > 0, "the person walked through the robot without contact");
    a = command(ctl, "list");
    double px = 0;
    CHECK(sscanf(a, "ok count=1; person alice x=%lf", &px) == 1 && px > 5.5, "%s", a);
    CHECK(!strcmp(command(ctl, "person remove alice"), "ok person alice removed"), "remove");
    truth_t last = { 0 };
    CHECK(truth(ctl, 1, &last), "truth");
    close(ctl);
    close(bus);
    CHECK(sim_stop(&s) == 0, "exit status");
    truth_t lo = { 0 }, hi = { 0 };
    CHECK(csv_bracket(csv, last.t, &lo, &hi), "no CSV rows around t = %.3f", last.t);
    CHECK(between(last.x, lo.x, hi.x) && between(last.y, lo.y, hi.y) && between(last.theta, lo.theta, hi.theta),
          "truth pose %.5f %.5f %.5f outside CSV rows %.3f..%.3f", last.x, last.y, last.theta, lo.t, hi.t);
    CHECK(between(last.v, lo.v, hi.v) && between(last.omega, lo.omega, hi.omega), "truth speeds %.5f %.5f", last.v,
          last.omega);
    CHECK(last.contacts >= lo.contacts && last.contacts <= hi.contacts && hi.contacts > 0,
          "truth contacts %llu, CSV %llu..%llu", last.contacts, lo.contacts, hi.contacts);
}

static void everyBadCommandAnswersAnErrorAndChangesNothing(void)
{
    sim_t s;
    start_lab_robot(&s, NULL);
    int ctl = connect_to(s.control_port);
    CHECK(!strcmp(command(ctl, "obstacle add box 1 1 0.3"), "ok obstacle box added"), "add");
    CHECK(!strcmp(command(ctl, "person add bob 2 2 0 0"), "ok person bob added"), "add");
    static const struct {
        const char *command, *answer;
    } bad[] = {
        { "", "error empty command" },
        { "fly 1", "error unknown command 'fly' (obstacle, person, board, wheel, truth, battery, list)" },
        { "obstacle", "error obstacle wants add, move or remove" },
        { "obstacle add box 5 5 0.3", "error obstacle 'box' exists" },
        { "obstacle add bob 5 5 0.3", "error person 'bob' exists" },
        { "obstacle add b@d 5 5 0.3", "error bad ID 'b@d': 1 to 32 of A-Z a-z 0-9 _ -" },
        { "obstacle add abcdefghijklmnopqrstuvwxyz0123456 5 5 0.3",
          "error bad ID 'abcdefghijklmnopqrstuvwxyz0123456': 1 to 32 of A-Z a-z 0-9 _ -" },
        { "obstacle add c 5 5 0", "error RADIUS must be > 0, was 0" },
        { "obstacle add c 5 5 -1", "error RADIUS must be > 0, was -1" },
        { "obstacle add c five 5 1", "error X is not a number: 'five'" },
        { "obstacle add c 5 nan 1", "error Y is not a number: 'nan'" },
        { "obstacle add c 5 5", "error obstacle add wants ID X Y RADIUS" },
        { "obstacle add c 5 5 1 1", "error obstacle add wants ID X Y RADIUS" },
        { "obstacle move ghost 1 1", "error no obstacle 'ghost'" },
        { "obstacle move bob 1 1", "error 'bob' is a person, not an obstacle" },
        { "obstacle move box 1", "error obstacle move wants ID X Y" },
        { "obstacle remove ghost", "error no obstacle 'ghost'" },
        { "person add p 1 1 0", "error person add wants ID X Y VX VY" },
        { "person add p 1 1 0 fast", "error VY is not a number: 'fast'" },
        { "person move box 1 1 0 0", "error 'box' is an obstacle, not a person" },
        { "person remove box", "error 'box' is an obstacle, not a person" },
        { "person jump bob", "error person wants add, move or remove" },
        { "board 2 sact off", "error no robot '2' (robots are 1..1)" },
        { "board 0 sact off", "error no robot '0' (robots are 1..1)" },
        { "board 1 motor off", "error no board 'motor' (sact, ins, sonar, landmark or power)" },
        { "board 1 sact dim", "error board state must be off or on, was 'dim'" },
        { "board 1 sact", "error board wants ROBOT sact|ins|sonar|landmark|power off|on" },
        { "wheel 1 left", "error wheel wants ROBOT left|right jam|free" },
        { "wheel 1 middle jam", "error no wheel 'middle' (left or right)" },
        { "wheel 1 left stuck", "error wheel state must be jam or free, was 'stuck'" },
        { "wheel 3 left jam", "error no robot '3' (robots are 1..1)" },
        { "truth", "error truth wants ROBOT" },
        { "truth one", "error no robot 'one' (robots are 1..1)" },
        { "list all", "error list takes no arguments" },
        { "battery", "error battery wants ROBOT, or ROBOT soc F (0..1)" },
        { "battery 1 soc", "error battery wants ROBOT, or ROBOT soc F (0..1)" },
        { "battery 1 charge 0.5", "error battery wants ROBOT, or ROBOT soc F (0..1)" },
        { "battery 2", "error no robot '2' (robots are 1..1)" },
        { "battery 1 soc full", "error F is not a number: 'full'" },
        { "battery 1 soc 1.5", "error F must be in 0..1, was 1.5" },
        { "battery 1 soc -0.1", "error F must be in 0..1, was -0.1" },
        { "a b c d e f g h i", "error too many words (at most 8)" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const char *a = command(ctl, "%s", bad[i].command);
        CHECK(!strcmp(a, bad[i].answer), "'%s' answered '%s', expected '%s'", bad[i].command, a, bad[i].answer);
    }
    char longline[600];
    memset(longline, 'x', sizeof longline - 1);
    longline[sizeof longline - 1] = '\0';
    const char *a = command(ctl, "%s", longline);
    CHECK(!strcmp(a, "error line too long (at most 255 characters)"), "%s", a);
    a = command(ctl, "list");
    CHECK(!strcmp(a, "ok count=2; obstacle box x=1.0000 y=1.0000 radius=0.3000; "
                     "person bob x=2.0000 y=2.0000 vx=0.0000 vy=0.0000"),
          "scene changed by refused commands: %s", a);
    CHECK(!strncmp(command(ctl, "truth 1"), "ok t=", 5), "truth after errors");
    double soc = 0;
    CHECK(sscanf(command(ctl, "battery 1"), "ok t=%*f soc=%lf", &soc) == 1 && soc > 0.999,
          "battery changed by refused commands: soc %.5f", soc);
    CHECK(sim_alive(&s), "the simulator died");

    /* Clients at once and one after another see the one scene. */
    int other = connect_to(s.control_port);
    CHECK(!strcmp(command(other, "obstacle remove box"), "ok obstacle box removed"), "second client");
    CHECK(!strncmp(command(ctl, "list"), "ok count=1; person bob", 22), "first client does not see the removal");
    close(other);
    close(ctl);
    int third = connect_to(s.control_port);
    CHECK(!strcmp(command(third, "list"), "ok count=1; person bob x=2.0000 y=2.0000 vx=0.0000 vy=0.0000"),
          "third client: %s", command(third, "list"));
    close(third);
    CHECK(sim_stop(&s) == 0, "exit status");
}

static void theControlPortIsAnnouncedOnlyWhenAsked(void)
{
    sim_t s;
    char link[PATH_MAX + 16];
    snprintf(link, sizeof link, "%s/ctl-plain", tmp_dir);
    CHECK(sim_start(&s, SIM_ARGS("--link", link)), "start: %s", s.first_line);
    CHECK(!strstr(s.first_line, "\"control\""), "control announced without --control: %s", s.first_line);
    CHECK(sim_stop(&s) == 0, "exit status");
}

/* Reads `count` registers from `record` over TCP into v; false on any failure. */
static bool tcp_read_n(int fd, uint8_t address, uint16_t file, uint16_t record, uint16_t count, long *v)
{
    frame_t req = read_request(address, file, record, count), ans;
    if (modbus(fd, &req, &ans, 1000) != 5u + 2u * count + 2u || answer_exception(&ans) != 0)
        return false;
    for (int k = 0; k < count; k++)
        v[k] = ans.data[5 + 2 * k] << 8 | ans.data[6 + 2 * k];
    return true;
}

static void theLandmarkBoardSeesTheMarkerOverheadAndCanBeSwitchedOff(void)
{
    sim_t s;
    char link[PATH_MAX + 16];
    snprintf(link, sizeof link, "%s/lm-robot", tmp_dir);
    /* 0.67 m south-east of the lab's marker 5 at (5.6, 3.6), facing north-west */
    CHECK(sim_start(&s, SIM_ARGS("--control", "0", "--tcp", "0", "--start", "6.2,3.3,2.0", "--link", link)),
          "start: %s", s.first_line);
    CHECK(strstr(s.first_line, "\"landmark\": 4,") && strstr(s.first_line, "\"landmarks\": 10"),
          "first line does not announce the landmark board and markers: %s", s.first_line);
    world_t lab = { 0 };
    char err[256];
    CHECK(world_load_landmarks(&lab, "maps/lab.landmarks", err, sizeof err) == 0 && lab.n_landmarks >= 5 &&
              lab.landmarks[4].id == 5,
          "maps/lab.landmarks: %s", err);
    double mx = lab.n_landmarks >= 5 ? lab.landmarks[4].x : NAN, my = lab.n_landmarks >= 5 ? lab.landmarks[4].y : NAN;
    free(lab.landmarks);
    int ctl = connect_to(s.control_port), bus = connect_to(s.tcp_port);
    long v[5] = { 0 }, seq0 = -1;
    double deadline = now_s() + DEADLINE_S;
    /* two fresh measurements, so the first is one taken at the start pose */
    while (now_s() < deadline && tcp_read_n(bus, MB_LANDMARK_ADDRESS, MB_LANDMARK_FILE_LATEST, 0, 5, v)) {
        if (seq0 < 0)
            seq0 = v[0];
        else if (((v[0] - seq0) & 0xFFFF) >= 2)
            break;
    }
    truth_t t = { 0 };
    CHECK(truth(ctl, 1, &t), "truth");
    double range = hypot(mx - t.x, my - t.y), bearing = remainder(atan2(my - t.y, mx - t.x) - t.theta, 2 * M_PI);
    CHECK(((v[0] - seq0) & 0xFFFF) >= 2, "sequence %ld -> %ld", seq0, v[0]);
    CHECK(v[1] == 5, "sees landmark %ld, expected 5", v[1]);
    CHECK(fabs(v[2] * 1e-3 - range) < 0.041, "range %ld mm, truth %.1f mm", v[2], range * 1e3);
    CHECK(fabs(remainder((int16_t)v[3] * 1e-4 - bearing, 2 * M_PI)) < 4 * 0.5 * M_PI / 180 + 1e-4,
          "bearing %.4f rad, truth %.4f", (int16_t)v[3] * 1e-4, bearing);
    CHECK(v[4] <= 110, "age %ld ms at a 100 ms period", v[4]);

    switch_board_off_and_on(ctl, bus, "landmark", MB_LANDMARK_ADDRESS, MB_SONAR_ADDRESS);
    close(ctl);
    close(bus);
    CHECK(sim_stop(&s) == 0, "exit status");
}

/* The battery's truth on the control channel: "ok t=... soc=... voltage=... current=... docked=D charging=C full=F". */
typedef struct {
    double t, soc, voltage, current;
    int docked, charging, full;
} battery_truth_t;

static bool battery_truth(int fd, int robot, battery_truth_t *b)
{
    const char *a = command(fd, "battery %d", robot);
    return sscanf(a, "ok t=%lf soc=%lf voltage=%lf current=%lf docked=%d charging=%d full=%d", &b->t, &b->soc,
                  &b->voltage, &b->current, &b->docked, &b->charging, &b->full) == 7;
}

/* The power board's file 1 over TCP against the battery's truth read just after; the soc changes too
 * little between the two to matter at 0.01 %. */
static void check_power_reading(int ctl, int bus, int robot, const char *what)
{
    long v[5] = { 0 };
    battery_truth_t b = { 0 };
    bool read = tcp_read_n(bus, MB_POWER_ADDRESS, MB_POWER_FILE_LATEST, MB_POWER_LATEST_SEQUENCE, 5, v);
    CHECK(read && battery_truth(ctl, robot, &b), "%s: read power board and truth", what);
    CHECK(fabs(v[1] * 1e-3 - b.voltage) < 0.05, "%s: voltage %ld mV, truth %.4f V", what, v[1], b.voltage);
    CHECK(fabs((int16_t)v[2] * 1e-3 - b.current) < 0.2, "%s: current %d mA, truth %.4f A", what, (int16_t)v[2],
          b.current);
    CHECK(fabs(v[3] * 1e-4 - b.soc) < 2e-4, "%s: soc %ld (0.01 %%), truth %.5f", what, v[3], b.soc);
    long bits = (b.docked ? MB_POWER_LATEST_STATUS_DOCKED : 0) | (b.charging ? MB_POWER_LATEST_STATUS_CHARGING : 0) |
                (b.full ? MB_POWER_LATEST_STATUS_FULL : 0);
    CHECK(v[4] == bits, "%s: status %ld, truth %ld", what, v[4], bits);
}

static void thePowerBoardReportsTheBatteryTheControlChannelSetsAndReads(void)
{
    sim_t s;
    char link[PATH_MAX + 16];
    snprintf(link, sizeof link, "%s/power-robot", tmp_dir);
    /* robot 1 away from the docks, robot 2 on the lab's dock at (1, 1); each its own charge */
    CHECK(sim_start(&s, SIM_ARGS("--control", "0", "--tcp", "0", "--starts", "6,6.5,0/1.05,1,0", "--link", link,
                                 "--battery-soc", "0.4/0.3", "--battery-capacity", "2.5")),
          "start: %s", s.first_line);
    CHECK(strstr(s.first_line, "\"power\": 5}") && strstr(s.first_line, "\"docks\": 2"),
          "first line does not announce the power board and docks: %s", s.first_line);
    const char *second = strstr(s.first_line, "\"id\": 2");
    const char *tcp2 = second ? strstr(second, "\"tcp\": ") : NULL;
    int ctl = connect_to(s.control_port), bus = connect_to(s.tcp_port), bus2 = connect_to(tcp2 ? atoi(tcp2 + 7) : -1);
    long config[2] = { 0 };
    CHECK(tcp_read_n(bus, MB_POWER_ADDRESS, MB_POWER_FILE_CONFIG, 0, 2, config) && config[0] == 2500 &&
              config[1] == MB_POWER_CONFIG_PERIOD_DEFAULT,
          "config: capacity %ld mAh, period %ld ms", config[0], config[1]);
    battery_truth_t one = { 0 }, two = { 0 };
    CHECK(battery_truth(ctl, 1, &one) && battery_truth(ctl, 2, &two), "battery truth");
    CHECK(fabs(one.soc - 0.4) < 1e-3 && !one.docked && !one.charging && one.current > 0.4,
          "robot 1: soc %.5f docked %d current %.3f A", one.soc, one.docked, one.current);
    CHECK(fabs(two.soc - 0.3) < 1e-3 && two.docked && two.charging && two.current < -4.9,
          "robot 2 on its dock: soc %.5f docked %d charging %d current %.3f A", two.soc, two.docked, two.charging,
          two.current);
    /* a fresh measurement each, after a period */
    long seq[1] = { 0 }, seq0 = -1;
    double deadline = now_s() + DEADLINE_S;
    while (now_s() < deadline && tcp_read_n(bus, MB_POWER_ADDRESS, MB_POWER_FILE_LATEST, 0, 1, seq)) {
        if (seq0 < 0)
            seq0 = seq[0];
        else if (((seq[0] - seq0) & 0xFFFF) >= 2)
            break;
    }
    check_power_reading(ctl, bus, 1, "robot 1");
    check_power_reading(ctl, bus2, 2, "robot 2");

    CHECK(!strcmp(command(ctl, "battery 1 soc 0.05"), "ok robot 1 battery soc 0.05000"), "set soc");
    CHECK(battery_truth(ctl, 1, &one) && fabs(one.soc - 0.05) < 1e-3, "soc %.5f after setting 0.05", one.soc);
    switch_board_off_and_on(ctl, bus, "power", MB_POWER_ADDRESS, MB_LANDMARK_ADDRESS);
    close(ctl);
    close(bus);
    close(bus2);
    CHECK(sim_stop(&s) == 0, "exit status");
}

static void aBadDocksListStopsTheSimulator(void)
{
    char pgm[PATH_MAX], yaml[PATH_MAX + 32];
    CHECK(realpath("maps/lab.pgm", pgm) != NULL, "maps/lab.pgm (run from onboard-bridge)");
    snprintf(yaml, sizeof yaml, "%s/bad-docks.yaml", tmp_dir);
    FILE *f = fopen(yaml, "w");
    fprintf(f, "image: %s\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nsabot_docks: [[1.0, 1.0], [2.0]]\n", pgm);
    fclose(f);
    sim_t s;
    sim_start(&s, SIM_ARGS("--duration", "0.01", "--map", yaml));
    char err[1024];
    size_t len = read_until_newline(s.err_fd, err, sizeof err, now_s() + DEADLINE_S);
    int status = sim_stop(&s);
    CHECK(status == 2, "exit status %d", status);
    CHECK(len > 0 && strstr(err, "bad-docks.yaml: sabot_docks wants [[x, y], ...] (numbers, metres), got "
                                 "'[[1.0, 1.0], [2.0]]'"),
          "message '%s'", err);
    CHECK(s.first_line[0] == '\0', "started anyway: %s", s.first_line);
}

static void aBadLandmarksFileStopsTheSimulatorWithItsLine(void)
{
    char pgm[PATH_MAX], yaml[PATH_MAX + 32], marks[PATH_MAX + 32];
    CHECK(realpath("maps/lab.pgm", pgm) != NULL, "maps/lab.pgm (run from onboard-bridge)");
    snprintf(yaml, sizeof yaml, "%s/bad-lm.yaml", tmp_dir);
    snprintf(marks, sizeof marks, "%s/bad-lm.landmarks", tmp_dir);
    FILE *f = fopen(yaml, "w");
    fprintf(f, "image: %s\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nsabot_landmarks: bad-lm.landmarks\n", pgm);
    fclose(f);
    f = fopen(marks, "w");
    fputs("# two markers\n1 1.0 1.0\n2 2.0 two\n", f);
    fclose(f);
    sim_t s;
    sim_start(&s, SIM_ARGS("--duration", "0.01", "--map", yaml));
    char err[1024];
    size_t len = read_until_newline(s.err_fd, err, sizeof err, now_s() + DEADLINE_S);
    int status = sim_stop(&s);
    CHECK(status == 2, "exit status %d", status);
    CHECK(len > 0 && strstr(err, "bad-lm.landmarks:3: y 'two' is not a number (metres)"), "message '%s'", err);
    CHECK(s.first_line[0] == '\0', "started anyway: %s", s.first_line);
}

int main(int argc, char **argv)
{
    (void)argc;
    printf("test_sim_process\n");
    char self[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n <= 0) {
        printf("cannot locate myself\ntest_sim_process: 0 passed, 1 failed\n");
        return 1;
    }
    self[n] = '\0';
    *strrchr(self, '/') = '\0';
    snprintf(sim_path, sizeof sim_path, "%.*s/sabot-sim", PATH_MAX - 16, self);
    snprintf(tmp_dir, sizeof tmp_dir, "%.*s/tmp", PATH_MAX - 16, self);
    if (access(sim_path, X_OK)) {
        printf("%s: %s\ntest_sim_process: 0 passed, 1 failed\n", sim_path, strerror(errno));
        return 1;
    }
    (void)argv;
    mkdir(tmp_dir, 0755);
    signal(SIGPIPE, SIG_IGN);
    RUN(badArgumentsAreRefusedWithStatusTwoAndAMessage);
    RUN(theControlPortIsAnnouncedOnlyWhenAsked);
    RUN(theStartsOptionPlacesEachRobotAndCountsThem);
    RUN(aStartPoseInAWallOrOnAnotherRobotIsAWarningNamingTheRobot);
    RUN(anObstacleAheadEchoesAtItsRangeAndIsGoneWhenRemoved);
    RUN(aBoardSwitchedOffIsSilentAndItsDeadmanStillStopsTheRobot);
    RUN(aJammedWheelLatchesAFollowingErrorAndTheBoardRefusesToDrive);
    RUN(drivingIntoAnObstacleCountsContacts);
    RUN(aPersonWalkingIntoTheRobotIsAContactAndTruthAgreesWithTheCsv);
    RUN(everyBadCommandAnswersAnErrorAndChangesNothing);
    RUN(theLandmarkBoardSeesTheMarkerOverheadAndCanBeSwitchedOff);
    RUN(aBadLandmarksFileStopsTheSimulatorWithItsLine);
    RUN(thePowerBoardReportsTheBatteryTheControlChannelSetsAndReads);
    RUN(aBadDocksListStopsTheSimulator);
    return REPORT("test_sim_process");
}
