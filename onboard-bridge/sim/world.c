#include "world.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void trim(char *s)
{
    char *p = s;
    while (isspace((unsigned char)*p))
        p++;
    memmove(s, p, strlen(p) + 1);
    size_t n = strlen(s);
    while (n > 0 && isspace((unsigned char)s[n - 1]))
        s[--n] = '\0';
    if (n >= 2 && (s[0] == '"' || s[0] == '\'') && s[n - 1] == s[0]) {
        memmove(s, s + 1, n - 2);
        s[n - 2] = '\0';
    }
}

/* Reads the next PGM header token, skipping whitespace and # comments. */
static int pgm_token(FILE *f, char *buf, size_t len)
{
    int c;
    size_t n = 0;
    for (;;) {
        c = fgetc(f);
        if (c == '#') {
            while (c != '\n' && c != EOF)
                c = fgetc(f);
        } else if (!isspace(c)) {
            break;
        }
    }
    while (c != EOF && !isspace(c) && n + 1 < len) {
        buf[n++] = (char)c;
        c = fgetc(f);
    }
    buf[n] = '\0';
    return n > 0 ? 0 : -1;
}

static int load_pgm(const char *path, int *width, int *height, uint8_t **pixels, char *err, int err_len)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, (size_t)err_len, "map image %s: %s", path, strerror(errno));
        return -1;
    }
    char tok[32];
    int w = 0, h = 0, maxval = 0, rc = -1;
    bool binary;
    if (pgm_token(f, tok, sizeof tok) || (strcmp(tok, "P5") && strcmp(tok, "P2"))) {
        snprintf(err, (size_t)err_len, "%s: not a PGM (P5/P2)", path);
        goto out;
    }
    binary = tok[1] == '5';
    if (pgm_token(f, tok, sizeof tok) || (w = atoi(tok)) <= 0 || pgm_token(f, tok, sizeof tok) ||
        (h = atoi(tok)) <= 0 || pgm_token(f, tok, sizeof tok) || (maxval = atoi(tok)) <= 0 ||
        maxval > 255 || (long)w * h > 64L * 1024 * 1024) {
        snprintf(err, (size_t)err_len, "%s: bad PGM header (8-bit maps only)", path);
        goto out;
    }
    *pixels = malloc((size_t)w * (size_t)h);
    if (!*pixels) {
        snprintf(err, (size_t)err_len, "out of memory");
        goto out;
    }
    for (long i = 0; i < (long)w * h; i++) {
        int v;
        if (binary) {
            v = fgetc(f);
        } else {
            v = pgm_token(f, tok, sizeof tok) ? EOF : atoi(tok);
        }
        if (v == EOF) {
            snprintf(err, (size_t)err_len, "%s: truncated PGM", path);
            free(*pixels);
            *pixels = NULL;
            goto out;
        }
        (*pixels)[i] = (uint8_t)(v * 255 / maxval);
    }
    *width = w;
    *height = h;
    rc = 0;
out:
    fclose(f);
    return rc;
}

/* Exact Euclidean distance transform by brute force over a bounded window would be
 * O(n r^2); two raster passes that propagate the nearest obstacle (Danielsson 1980,
 * 8SSEDT) are O(n) and within a fraction of a cell, which is enough here. */
static void build_clearance(world_t *w)
{
    int n = w->width * w->height;
    int *nx = malloc(sizeof(int) * (size_t)n), *ny = malloc(sizeof(int) * (size_t)n);
    const int far = 1 << 20;
    for (int i = 0; i < n; i++) {
        nx[i] = w->occupied[i] ? 0 : far;
        ny[i] = w->occupied[i] ? 0 : far;
    }
#define D2(i) ((long)nx[i] * nx[i] + (long)ny[i] * ny[i])
#define RELAX(i, j, dx, dy)                                                      \
    do {                                                                         \
        long cx = nx[j] + (dx), cy = ny[j] + (dy);                               \
        if (nx[j] < far && cx * cx + cy * cy < D2(i)) {                          \
            nx[i] = (int)cx;                                                     \
            ny[i] = (int)cy;                                                     \
        }                                                                        \
    } while (0)
    int W = w->width, H = w->height;
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            int i = y * W + x;
            if (x > 0) RELAX(i, i - 1, 1, 0);
            if (y > 0) RELAX(i, i - W, 0, 1);
            if (x > 0 && y > 0) RELAX(i, i - W - 1, 1, 1);
            if (x < W - 1 && y > 0) RELAX(i, i - W + 1, -1, 1);
        }
        for (int x = W - 2; x >= 0; x--) RELAX(y * W + x, y * W + x + 1, -1, 0);
    }
    for (int y = H - 1; y >= 0; y--) {
        for (int x = W - 1; x >= 0; x--) {
            int i = y * W + x;
            if (x < W - 1) RELAX(i, i + 1, -1, 0);
            if (y < H - 1) RELAX(i, i + W, 0, -1);
            if (x < W - 1 && y < H - 1) RELAX(i, i + W + 1, -1, -1);
            if (x > 0 && y < H - 1) RELAX(i, i + W - 1, 1, -1);
        }
        for (int x = 1; x < W; x++) RELAX(y * W + x, y * W + x - 1, 1, 0);
    }
#undef RELAX
    for (int i = 0; i < n; i++) {
        /* Outside the map is an obstacle too: the border is at most this far. */
        int x = i % W, y = i / W;
        double border = fmin(fmin(x + 0.5, W - x - 0.5), fmin(y + 0.5, H - y - 0.5));
        double d = nx[i] < far ? sqrt((double)D2(i)) - 0.5 : DBL_MAX;
        if (d < 0)
            d = 0;
        w->clearance[i] = (float)(fmin(d, border) * w->resolution);
    }
#undef D2
    free(nx);
    free(ny);
}

/* A file named in the YAML: relative to the YAML's folder unless absolute, as map_server resolves `image`. */
static void beside_yaml(char *out, size_t len, const char *yaml_path, const char *name)
{
    if (name[0] == '/') {
        snprintf(out, len, "%s", name);
    } else {
        const char *slash = strrchr(yaml_path, '/');
        int dir_len = slash ? (int)(slash - yaml_path + 1) : 0;
        snprintf(out, len, "%.*s%s", dir_len, yaml_path, name);
    }
}

/* The whole of `text` as a finite decimal number (no hex, inf or nan, which strtod would take). */
static bool parse_number(const char *text, double *out)
{
    if (strspn(text, "0123456789+-.eE") != strlen(text))
        return false;
    char *end;
    errno = 0;
    double v = strtod(text, &end);
    if (end == text || *end || errno || !isfinite(v))
        return false;
    *out = v;
    return true;
}

int world_load_landmarks(world_t *w, const char *path, char *err, int err_len)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, (size_t)err_len, "landmarks file %s: %s", path, strerror(errno));
        return -1;
    }
    world_landmark_t *marks = malloc(sizeof *marks * WORLD_MAX_LANDMARKS);
    int first_line[WORLD_MAX_LANDMARKS];
    int n = 0, line_no = 0, rc = -1;
    char line[512];
    if (!marks) {
        snprintf(err, (size_t)err_len, "out of memory");
        goto out;
    }
    while (fgets(line, sizeof line, f)) {
        line_no++;
        if (!strchr(line, '\n') && !feof(f)) {
            snprintf(err, (size_t)err_len, "%s:%d: line longer than %d characters", path, line_no,
                     (int)sizeof line - 2);
            goto out;
        }
        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        char *word[3];
        int words = 0;
        for (char *tok = strtok(line, " \t\r\n"); tok; tok = strtok(NULL, " \t\r\n"), words++)
            if (words < 3)
                word[words] = tok;
        if (words == 0)
            continue;
        if (words != 3) {
            snprintf(err, (size_t)err_len, "%s:%d: expected 'id x y', got %d field%s", path, line_no, words,
                     words == 1 ? "" : "s");
            goto out;
        }
        char *end;
        errno = 0;
        long id = strtol(word[0], &end, 10);
        if (end == word[0] || *end || errno || id < 1 || id > 65535) {
            snprintf(err, (size_t)err_len, "%s:%d: id '%.32s' is not an integer in 1..65535", path, line_no, word[0]);
            goto out;
        }
        double x, y;
        bool x_ok = parse_number(word[1], &x), y_ok = x_ok && parse_number(word[2], &y);
        if (!y_ok) {
            snprintf(err, (size_t)err_len, "%s:%d: %s '%.32s' is not a number (metres)", path, line_no,
                     x_ok ? "y" : "x", x_ok ? word[2] : word[1]);
            goto out;
        }
        for (int k = 0; k < n; k++) {
            if (marks[k].id == id) {
                snprintf(err, (size_t)err_len, "%s:%d: landmark id %ld given twice (first on line %d)", path, line_no,
                         id, first_line[k]);
                goto out;
            }
        }
        if (n == WORLD_MAX_LANDMARKS) {
            snprintf(err, (size_t)err_len, "%s:%d: more than %d landmarks", path, line_no, WORLD_MAX_LANDMARKS);
            goto out;
        }
        first_line[n] = line_no;
        marks[n++] = (world_landmark_t){ (uint16_t)id, x, y };
    }
    if (ferror(f)) {
        snprintf(err, (size_t)err_len, "landmarks file %s: read error", path);
        goto out;
    }
    free(w->landmarks);
    w->landmarks = marks;
    w->n_landmarks = n;
    marks = NULL;
    rc = 0;
out:
    free(marks);
    fclose(f);
    return rc;
}

static const char *skip_blanks(const char *p)
{
    while (*p == ' ' || *p == '\t')
        p++;
    return p;
}

int world_parse_docks(world_t *w, const char *value, char *err, int err_len)
{
    world_dock_t docks[WORLD_MAX_DOCKS];
    int n = 0;
    const char *p = skip_blanks(value);
    if (*p != '[')
        goto bad;
    p = skip_blanks(p + 1);
    if (*p == ']') {
        p++;
    } else {
        for (;;) {
            if (*p != '[')
                goto bad;
            double xy[2];
            for (int k = 0; k < 2; k++) {
                char *end;
                xy[k] = strtod(p + 1, &end);
                if (end == p + 1 || !isfinite(xy[k]))
                    goto bad;
                p = skip_blanks(end);
                if (*p != (k == 0 ? ',' : ']'))
                    goto bad;
            }
            if (n == WORLD_MAX_DOCKS) {
                snprintf(err, (size_t)err_len, "sabot_docks: more than %d docks", WORLD_MAX_DOCKS);
                return -1;
            }
            docks[n++] = (world_dock_t){ xy[0], xy[1] };
            p = skip_blanks(p + 1);
            if (*p == ']') {
                p++;
                break;
            }
            if (*p != ',')
                goto bad;
            p = skip_blanks(p + 1);
        }
    }
    if (*skip_blanks(p))
        goto bad;
    memcpy(w->docks, docks, sizeof docks[0] * (size_t)n);
    w->n_docks = n;
    return 0;
bad:
    snprintf(err, (size_t)err_len, "sabot_docks wants [[x, y], ...] (numbers, metres), got '%.60s'", value);
    return -1;
}

int world_dock_at(const world_t *w, double x, double y)
{
    for (int k = 0; k < w->n_docks; k++)
        if (hypot(w->docks[k].x - x, w->docks[k].y - y) <= WORLD_DOCK_REACH)
            return k;
    return -1;
}

int world_load(world_t *w, const char *yaml_path, char *err, int err_len)
{
    memset(w, 0, sizeof *w);
    FILE *f = fopen(yaml_path, "r");
    if (!f) {
        snprintf(err, (size_t)err_len, "map %s: %s", yaml_path, strerror(errno));
        return -1;
    }
    char line[1024], image[900] = "", landmarks[900] = "";
    double resolution = 0, ox = 0, oy = 0, occ_thresh = 0.65;
    int negate = 0;
    while (fgets(line, sizeof line, f)) {
        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        char *colon = strchr(line, ':');
        if (!colon)
            continue;
        *colon = '\0';
        char *key = line, *val = colon + 1;
        trim(key);
        trim(val);
        if (!strcmp(key, "image")) {
            snprintf(image, sizeof image, "%s", val);
        } else if (!strcmp(key, "resolution")) {
            resolution = atof(val);
        } else if (!strcmp(key, "origin")) {
            if (sscanf(val, " [ %lf , %lf", &ox, &oy) != 2) {
                snprintf(err, (size_t)err_len, "%s: origin must be [x, y, yaw]", yaml_path);
                fclose(f);
                return -1;
            }
        } else if (!strcmp(key, "negate")) {
            negate = atoi(val) != 0 || !strcmp(val, "true");
        } else if (!strcmp(key, "occupied_thresh")) {
            occ_thresh = atof(val);
        } else if (!strcmp(key, "sabot_landmarks")) {
            if (!val[0]) {
                snprintf(err, (size_t)err_len, "%s: sabot_landmarks wants a file name", yaml_path);
                fclose(f);
                return -1;
            }
            snprintf(landmarks, sizeof landmarks, "%s", val);
        } else if (!strcmp(key, "sabot_docks")) {
            char why[200];
            if (world_parse_docks(w, val, why, sizeof why)) {
                snprintf(err, (size_t)err_len, "%s: %s", yaml_path, why);
                fclose(f);
                return -1;
            }
        }
    }
    fclose(f);
    if (!image[0] || resolution <= 0) {
        snprintf(err, (size_t)err_len, "%s: needs image and resolution > 0", yaml_path);
        return -1;
    }
    char pgm_path[2048];
    beside_yaml(pgm_path, sizeof pgm_path, yaml_path, image);
    if (landmarks[0]) {
        char landmarks_path[2048];
        beside_yaml(landmarks_path, sizeof landmarks_path, yaml_path, landmarks);
        if (world_load_landmarks(w, landmarks_path, err, err_len))
            return -1;
    }
    uint8_t *pixels = NULL;
    if (load_pgm(pgm_path, &w->width, &w->height, &pixels, err, err_len)) {
        world_free(w);
        return -1;
    }
    w->resolution = resolution;
    w->origin_x = ox;
    w->origin_y = oy;
    size_t n = (size_t)w->width * (size_t)w->height;
    w->occupied = malloc(n);
    w->clearance = malloc(n * sizeof(float));
    for (int row = 0; row < w->height; row++) {
        for (int col = 0; col < w->width; col++) {
            double v = pixels[(size_t)row * (size_t)w->width + (size_t)col];
            double p = negate ? v / 255.0 : (255.0 - v) / 255.0;
            w->occupied[(size_t)(w->height - 1 - row) * (size_t)w->width + (size_t)col] = p > occ_thresh;
        }
    }
    free(pixels);
    build_clearance(w);
    return 0;
}

void world_free(world_t *w)
{
    free(w->occupied);
    free(w->clearance);
    free(w->landmarks);
    memset(w, 0, sizeof *w);
}

static bool cell_of(const world_t *w, double x, double y, int *cx, int *cy)
{
    *cx = (int)floor((x - w->origin_x) / w->resolution);
    *cy = (int)floor((y - w->origin_y) / w->resolution);
    return *cx >= 0 && *cy >= 0 && *cx < w->width && *cy < w->height;
}

bool world_occupied(const world_t *w, double x, double y)
{
    int cx, cy;
    if (!cell_of(w, x, y, &cx, &cy))
        return true;
    return w->occupied[cy * w->width + cx] != 0;
}

double world_clearance(const world_t *w, double x, double y)
{
    int cx, cy;
    if (!cell_of(w, x, y, &cx, &cy))
        return 0.0;
    return w->clearance[cy * w->width + cx];
}

double world_raycast(const world_t *w, double x, double y, double angle, double max_range)
{
    double dx = cos(angle), dy = sin(angle);
    int cx, cy;
    if (!cell_of(w, x, y, &cx, &cy) || w->occupied[cy * w->width + cx])
        return 0.0;
    double gx = (x - w->origin_x) / w->resolution, gy = (y - w->origin_y) / w->resolution;
    int step_x = dx > 0 ? 1 : -1, step_y = dy > 0 ? 1 : -1;
    double t_delta_x = dx != 0 ? fabs(1.0 / dx) : DBL_MAX;
    double t_delta_y = dy != 0 ? fabs(1.0 / dy) : DBL_MAX;
    double t_max_x = dx != 0 ? ((dx > 0 ? cx + 1 - gx : gx - cx) * t_delta_x) : DBL_MAX;
    double t_max_y = dy != 0 ? ((dy > 0 ? cy + 1 - gy : gy - cy) * t_delta_y) : DBL_MAX;
    double limit = max_range / w->resolution;
    for (;;) {
        double t;
        if (t_max_x < t_max_y) {
            t = t_max_x;
            t_max_x += t_delta_x;
            cx += step_x;
        } else {
            t = t_max_y;
            t_max_y += t_delta_y;
            cy += step_y;
        }
        if (t > limit)
            return max_range;
        if (cx < 0 || cy < 0 || cx >= w->width || cy >= w->height || w->occupied[cy * w->width + cx])
            return t * w->resolution;
    }
}
