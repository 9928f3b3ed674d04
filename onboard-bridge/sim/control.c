#include "control.h"

#include <errno.h>
#include <math.h>
#include <netinet/in.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#define MAX_WORDS 8

static bool answer(char *out, size_t len, bool ok, const char *fmt, ...)
{
    int n = snprintf(out, len, ok ? "ok" : "error ");
    if (ok && fmt[0])
        n += snprintf(out + n, len - (size_t)n, " ");
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(out + n, len - (size_t)n, fmt, ap);
    va_end(ap);
    return ok;
}

/* A finite decimal number, nothing after it. */
static bool number(const char *word, double *value)
{
    char *end;
    errno = 0;
    *value = strtod(word, &end);
    return end != word && *end == '\0' && errno == 0 && isfinite(*value);
}

static bool valid_id(const char *id)
{
    size_t n = strlen(id);
    if (n < 1 || n > SCENE_ID_MAX)
        return false;
    for (size_t i = 0; i < n; i++) {
        char c = id[i];
        if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-'))
            return false;
    }
    return true;
}

/* Parses words[first..] as the named numbers; on failure writes the error. */
static bool numbers(char **words, int first, int count, const char *const *names, double *values, char *out,
                    size_t len)
{
    for (int i = 0; i < count; i++) {
        if (!number(words[first + i], &values[i])) {
            answer(out, len, false, "%s is not a number: '%s'", names[i], words[first + i]);
            return false;
        }
    }
    return true;
}

static const char *kind_name(scene_kind_t k) { return k == SCENE_PERSON ? "person" : "obstacle"; }
static const char *kind_with_article(scene_kind_t k) { return k == SCENE_PERSON ? "a person" : "an obstacle"; }

/* obstacle|person add|move|remove ... */
static bool scene_command(const control_target_t *t, scene_kind_t kind, char **w, int n, char *out, size_t len)
{
    static const char *const obstacle_add[] = { "X", "Y", "RADIUS" };
    static const char *const person_add[] = { "X", "Y", "VX", "VY" };
    static const char *const obstacle_move[] = { "X", "Y" };
    const char *what = kind_name(kind);
    const char *verb = n > 1 ? w[1] : "";
    bool add = !strcmp(verb, "add"), move = !strcmp(verb, "move"), remove = !strcmp(verb, "remove");
    if (!add && !move && !remove)
        return answer(out, len, false, "%s wants add, move or remove", what);
    int want = remove ? 3 : kind == SCENE_PERSON ? 7 : add ? 6 : 5;
    const char *usage = remove                  ? "ID"
                        : kind == SCENE_PERSON ? "ID X Y VX VY"
                        : add                   ? "ID X Y RADIUS"
                                                : "ID X Y";
    if (n != want)
        return answer(out, len, false, "%s %s wants %s", what, verb, usage);
    const char *id = w[2];
    if (!valid_id(id))
        return answer(out, len, false, "bad ID '%.40s%s': 1 to %d of A-Z a-z 0-9 _ -", id,
                      strlen(id) > 40 ? "..." : "", SCENE_ID_MAX);
    scene_item_t *found = scene_find(t->scene, id);
    double v[4] = { 0 };
    const char *const *names = kind == SCENE_PERSON ? person_add : add ? obstacle_add : obstacle_move;
    if (!remove && !numbers(w, 3, want - 3, names, v, out, len))
        return false;
    if (add) {
        if (found)
            return answer(out, len, false, "%s '%s' exists", kind_name(found->kind), id);
        scene_item_t item = { .kind = kind, .x = v[0], .y = v[1] };
        snprintf(item.id, sizeof item.id, "%s", id);
        if (kind == SCENE_PERSON) {
            item.radius = PERSON_RADIUS;
            item.vx = v[2];
            item.vy = v[3];
        } else {
            if (!(v[2] > 0))
                return answer(out, len, false, "RADIUS must be > 0, was %s", w[5]);
            item.radius = v[2];
        }
        if (!scene_add(t->scene, &item))
            return answer(out, len, false, "the scene is full (%d obstacles and people)", SCENE_MAX_ITEMS);
        return answer(out, len, true, "%s %s added", what, id);
    }
    if (!found)
        return answer(out, len, false, "no %s '%s'", what, id);
    if (found->kind != kind)
        return answer(out, len, false, "'%s' is %s, not %s", id, kind_with_article(found->kind),
                      kind_with_article(kind));
    if (remove) {
        scene_remove(t->scene, found);
        return answer(out, len, true, "%s %s removed", what, id);
    }
    found->x = v[0];
    found->y = v[1];
    if (kind == SCENE_PERSON) {
        found->vx = v[2];
        found->vy = v[3];
    }
    return answer(out, len, true, "%s %s moved", what, id);
}

/* A robot number 1..n; on failure writes the error. */
static robot_t *robot_arg(const control_target_t *t, const char *word, char *out, size_t len)
{
    char *end;
    errno = 0;
    long k = strtol(word, &end, 10);
    if (end == word || *end || errno || k < 1 || k > t->n_robots) {
        answer(out, len, false, "no robot '%s' (robots are 1..%d)", word, t->n_robots);
        return NULL;
    }
    return &t->robots[k - 1];
}

static bool board_command(const control_target_t *t, char **w, int n, char *out, size_t len)
{
    static const char *const names[BOARD_COUNT] = { "sact", "ins", "sonar", "landmark", "power" };
    if (n != 4)
        return answer(out, len, false, "board wants ROBOT sact|ins|sonar|landmark|power off|on");
    robot_t *r = robot_arg(t, w[1], out, len);
    if (!r)
        return false;
    int b = 0;
    while (b < BOARD_COUNT && strcmp(w[2], names[b]))
        b++;
    if (b == BOARD_COUNT)
        return answer(out, len, false, "no board '%s' (sact, ins, sonar, landmark or power)", w[2]);
    bool off = !strcmp(w[3], "off");
    if (!off && strcmp(w[3], "on"))
        return answer(out, len, false, "board state must be off or on, was '%s'", w[3]);
    r->link_cut[b] = off;
    return answer(out, len, true, "robot %d %s %s", r->cfg.id, names[b], off ? "off" : "on");
}

static bool wheel_command(const control_target_t *t, char **w, int n, char *out, size_t len)
{
    if (n != 4)
        return answer(out, len, false, "wheel wants ROBOT left|right jam|free");
    robot_t *r = robot_arg(t, w[1], out, len);
    if (!r)
        return false;
    bool left = !strcmp(w[2], "left");
    if (!left && strcmp(w[2], "right"))
        return answer(out, len, false, "no wheel '%.40s' (left or right)", w[2]);
    bool jam = !strcmp(w[3], "jam");
    if (!jam && strcmp(w[3], "free"))
        return answer(out, len, false, "wheel state must be jam or free, was '%.40s'", w[3]);
    r->body.wheel[left ? 0 : 1].jammed = jam;
    return answer(out, len, true, "robot %d %s wheel %s", r->cfg.id, w[2], jam ? "jammed" : "free");
}

static bool truth_command(const control_target_t *t, char **w, int n, char *out, size_t len)
{
    if (n != 2)
        return answer(out, len, false, "truth wants ROBOT");
    robot_t *r = robot_arg(t, w[1], out, len);
    if (!r)
        return false;
    const body_state_t *b = &r->body;
    /* The --truth CSV's formats, so the two compare digit for digit. */
    return answer(out, len, true, "t=%.3f x=%.5f y=%.5f theta=%.5f v=%.5f omega=%.5f contacts=%llu",
                  *t->sim_us * 1e-6, b->x, b->y, b->theta, b->v, b->omega, (unsigned long long)b->collisions);
}

/* battery ROBOT: the battery's truth; battery ROBOT soc F: sets its state of charge (0..1). */
static bool battery_command(const control_target_t *t, char **w, int n, char *out, size_t len)
{
    if (n != 2 && !(n == 4 && !strcmp(w[2], "soc")))
        return answer(out, len, false, "battery wants ROBOT, or ROBOT soc F (0..1)");
    robot_t *r = robot_arg(t, w[1], out, len);
    if (!r)
        return false;
    battery_t *b = &r->battery;
    if (n == 4) {
        double soc;
        if (!number(w[3], &soc))
            return answer(out, len, false, "F is not a number: '%.40s'", w[3]);
        if (soc < 0 || soc > 1)
            return answer(out, len, false, "F must be in 0..1, was %s", w[3]);
        battery_set_soc(b, soc);
        return answer(out, len, true, "robot %d battery soc %.5f", r->cfg.id, b->soc);
    }
    return answer(out, len, true, "t=%.3f soc=%.5f voltage=%.4f current=%.4f docked=%d charging=%d full=%d",
                  *t->sim_us * 1e-6, b->soc, b->voltage, b->current, b->docked, b->charging, b->full);
}

static bool list_command(const control_target_t *t, int n, char *out, size_t len)
{
    if (n != 1)
        return answer(out, len, false, "list takes no arguments");
    answer(out, len, true, "count=%d", t->scene->n);
    for (int i = 0; i < t->scene->n; i++) {
        const scene_item_t *it = &t->scene->item[i];
        size_t used = strlen(out);
        if (it->kind == SCENE_PERSON)
            snprintf(out + used, len - used, "; person %s x=%.4f y=%.4f vx=%.4f vy=%.4f", it->id, it->x, it->y,
                     it->vx, it->vy);
        else
            snprintf(out + used, len - used, "; obstacle %s x=%.4f y=%.4f radius=%.4f", it->id, it->x, it->y,
                     it->radius);
    }
    return true;
}

bool control_execute(const control_target_t *t, const char *line, char *out, size_t out_len)
{
    char copy[CONTROL_LINE_MAX + 1];
    snprintf(copy, sizeof copy, "%s", line);
    char *w[MAX_WORDS + 1], *save = NULL;
    int n = 0;
    for (char *tok = strtok_r(copy, " \t", &save); tok && n <= MAX_WORDS; tok = strtok_r(NULL, " \t", &save))
        w[n++] = tok;
    if (n == 0)
        return answer(out, out_len, false, "empty command");
    if (n > MAX_WORDS)
        return answer(out, out_len, false, "too many words (at most %d)", MAX_WORDS);
    if (!strcmp(w[0], "obstacle"))
        return scene_command(t, SCENE_OBSTACLE, w, n, out, out_len);
    if (!strcmp(w[0], "person"))
        return scene_command(t, SCENE_PERSON, w, n, out, out_len);
    if (!strcmp(w[0], "board"))
        return board_command(t, w, n, out, out_len);
    if (!strcmp(w[0], "wheel"))
        return wheel_command(t, w, n, out, out_len);
    if (!strcmp(w[0], "truth"))
        return truth_command(t, w, n, out, out_len);
    if (!strcmp(w[0], "battery"))
        return battery_command(t, w, n, out, out_len);
    if (!strcmp(w[0], "list"))
        return list_command(t, n, out, out_len);
    return answer(out, out_len, false,
                  "unknown command '%.40s' (obstacle, person, board, wheel, truth, battery, list)", w[0]);
}

int control_open(control_server_t *s, int port)
{
    s->listen_fd = -1;
    for (int k = 0; k < CONTROL_MAX_CLIENTS; k++)
        s->client[k].fd = -1;
    int fd = socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0)
        return -1;
    int one = 1;
    setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    struct sockaddr_in a = { .sin_family = AF_INET, .sin_port = htons((uint16_t)port),
                             .sin_addr.s_addr = htonl(INADDR_LOOPBACK) };
    socklen_t alen = sizeof a;
    if (bind(fd, (struct sockaddr *)&a, sizeof a) || listen(fd, CONTROL_MAX_CLIENTS) ||
        getsockname(fd, (struct sockaddr *)&a, &alen)) {
        int e = errno;
        close(fd);
        errno = e;
        return -1;
    }
    s->listen_fd = fd;
    s->port = ntohs(a.sin_port);
    return 0;
}

void control_pollfds(const control_server_t *s, struct pollfd *pfd)
{
    pfd[0] = (struct pollfd){ s->listen_fd, POLLIN, 0 };
    /* A server never opened has no clients: its zeroed slots are not fd 0 (stdin). */
    for (int k = 0; k < CONTROL_MAX_CLIENTS; k++)
        pfd[1 + k] = (struct pollfd){ s->listen_fd >= 0 ? s->client[k].fd : -1, POLLIN, 0 };
}

static void drop(control_client_t *c)
{
    close(c->fd);
    c->fd = -1;
}

static void reply(control_client_t *c, const char *text)
{
    size_t len = strlen(text);
    /* A client that does not read its answers is dropped rather than let block the simulation. */
    if (send(c->fd, text, len, MSG_NOSIGNAL) != (ssize_t)len || send(c->fd, "\n", 1, MSG_NOSIGNAL) != 1)
        drop(c);
}

static void take_lines(control_client_t *c, const control_target_t *t)
{
    static char out[CONTROL_ANSWER_MAX];
    size_t start = 0;
    for (size_t i = 0; i < c->len && c->fd >= 0; i++) {
        if (c->buf[i] != '\n')
            continue;
        c->buf[i] = '\0';
        if (i > start && c->buf[i - 1] == '\r')
            c->buf[i - 1] = '\0';
        if (c->overlong) {
            c->overlong = false;
            snprintf(out, sizeof out, "error line too long (at most %d characters)", CONTROL_LINE_MAX - 1);
        } else {
            control_execute(t, c->buf + start, out, sizeof out);
        }
        reply(c, out);
        start = i + 1;
    }
    if (c->fd < 0)
        return;
    memmove(c->buf, c->buf + start, c->len - start);
    c->len -= start;
    if (c->len == sizeof c->buf) {
        /* No newline in a full buffer: the rest of this line is refused when it ends. */
        c->overlong = true;
        c->len = 0;
    }
}

void control_serve(control_server_t *s, const struct pollfd *pfd, const control_target_t *t)
{
    if (s->listen_fd < 0)
        return;
    if (pfd[0].revents & POLLIN) {
        int fd;
        while ((fd = accept4(s->listen_fd, NULL, NULL, SOCK_NONBLOCK | SOCK_CLOEXEC)) >= 0) {
            int k = 0;
            while (k < CONTROL_MAX_CLIENTS && s->client[k].fd >= 0)
                k++;
            if (k == CONTROL_MAX_CLIENTS) {
                static const char busy[] = "error too many control connections\n";
                if (send(fd, busy, sizeof busy - 1, MSG_NOSIGNAL) < 0) {
                    /* closing anyway */
                }
                close(fd);
                continue;
            }
            s->client[k] = (control_client_t){ .fd = fd };
        }
    }
    for (int k = 0; k < CONTROL_MAX_CLIENTS; k++) {
        control_client_t *c = &s->client[k];
        if (c->fd < 0 || pfd[1 + k].fd != c->fd || !(pfd[1 + k].revents & (POLLIN | POLLHUP | POLLERR)))
            continue;
        ssize_t n = recv(c->fd, c->buf + c->len, sizeof c->buf - c->len, 0);
        if (n > 0) {
            c->len += (size_t)n;
            take_lines(c, t);
        } else if (n == 0 || (errno != EAGAIN && errno != EINTR)) {
            drop(c);
        }
    }
}

void control_close(control_server_t *s)
{
    for (int k = 0; k < CONTROL_MAX_CLIENTS; k++)
        if (s->client[k].fd >= 0)
            drop(&s->client[k]);
    if (s->listen_fd >= 0)
        close(s->listen_fd);
    s->listen_fd = -1;
}
