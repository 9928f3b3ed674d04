#include "json_mini.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *p;
    int failed;
} parser_t;

static void skip_ws(parser_t *ps)
{
    while (isspace((unsigned char)*ps->p))
        ps->p++;
}

static json_t *new_value(json_type_t t)
{
    json_t *j = calloc(1, sizeof *j);
    j->type = t;
    return j;
}

static char *parse_string_raw(parser_t *ps)
{
    if (*ps->p != '"') {
        ps->failed = 1;
        return NULL;
    }
    ps->p++;
    size_t cap = 16, n = 0;
    char *s = malloc(cap);
    while (*ps->p && *ps->p != '"') {
        char c = *ps->p++;
        if (c == '\\') {
            c = *ps->p++;
            switch (c) {
            case 'n': c = '\n'; break;
            case 't': c = '\t'; break;
            case 'u': ps->p += 4; c = '?'; break;   /* the map is ASCII */
            default: break;
            }
        }
        if (n + 2 > cap)
            s = realloc(s, cap *= 2);
        s[n++] = c;
    }
    if (*ps->p != '"')
        ps->failed = 1;
    else
        ps->p++;
    s[n] = '\0';
    return s;
}

static json_t *parse_value(parser_t *ps);

static json_t *parse_container(parser_t *ps, int object)
{
    json_t *j = new_value(object ? JSON_OBJECT : JSON_ARRAY);
    ps->p++;
    skip_ws(ps);
    if (*ps->p == (object ? '}' : ']')) {
        ps->p++;
        return j;
    }
    for (;;) {
        skip_ws(ps);
        char *key = NULL;
        if (object) {
            key = parse_string_raw(ps);
            skip_ws(ps);
            if (*ps->p != ':')
                ps->failed = 1;
            else
                ps->p++;
        }
        json_t *v = parse_value(ps);
        if (ps->failed) {
            free(key);
            json_free(v);
            return j;
        }
        j->items = realloc(j->items, sizeof *j->items * (size_t)(j->count + 1));
        j->keys = realloc(j->keys, sizeof *j->keys * (size_t)(j->count + 1));
        j->items[j->count] = v;
        j->keys[j->count] = key;
        j->count++;
        skip_ws(ps);
        if (*ps->p == ',') {
            ps->p++;
            continue;
        }
        if (*ps->p == (object ? '}' : ']')) {
            ps->p++;
            return j;
        }
        ps->failed = 1;
        return j;
    }
}

static json_t *parse_value(parser_t *ps)
{
    skip_ws(ps);
    char c = *ps->p;
    if (c == '{' || c == '[')
        return parse_container(ps, c == '{');
    if (c == '"') {
        json_t *j = new_value(JSON_STRING);
        j->string = parse_string_raw(ps);
        return j;
    }
    if (!strncmp(ps->p, "true", 4) || !strncmp(ps->p, "false", 5)) {
        json_t *j = new_value(JSON_BOOL);
        j->number = c == 't';
        ps->p += c == 't' ? 4 : 5;
        return j;
    }
    if (!strncmp(ps->p, "null", 4)) {
        ps->p += 4;
        return new_value(JSON_NULL);
    }
    char *end;
    double d = strtod(ps->p, &end);
    if (end == ps->p) {
        ps->failed = 1;
        return NULL;
    }
    ps->p = end;
    json_t *j = new_value(JSON_NUMBER);
    j->number = d;
    return j;
}

json_t *json_load(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "json: cannot open %s\n", path);
        return NULL;
    }
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *text = malloc((size_t)len + 1);
    size_t got = fread(text, 1, (size_t)len, f);
    fclose(f);
    text[got] = '\0';
    parser_t ps = { text, 0 };
    json_t *j = parse_value(&ps);
    free(text);
    if (ps.failed) {
        fprintf(stderr, "json: syntax error in %s\n", path);
        json_free(j);
        return NULL;
    }
    return j;
}

const json_t *json_get(const json_t *o, const char *key)
{
    if (!o || o->type != JSON_OBJECT)
        return NULL;
    for (int i = 0; i < o->count; i++)
        if (!strcmp(o->keys[i], key))
            return o->items[i];
    return NULL;
}

const char *json_str(const json_t *o, const char *key)
{
    const json_t *v = json_get(o, key);
    return v && v->type == JSON_STRING ? v->string : "";
}

double json_num(const json_t *o, const char *key, double fallback)
{
    const json_t *v = json_get(o, key);
    return v && (v->type == JSON_NUMBER || v->type == JSON_BOOL) ? v->number : fallback;
}

void json_free(json_t *j)
{
    if (!j)
        return;
    for (int i = 0; i < j->count; i++) {
        json_free(j->items[i]);
        if (j->keys)
            free(j->keys[i]);
    }
    free(j->items);
    free(j->keys);
    free(j->string);
    free(j);
}
