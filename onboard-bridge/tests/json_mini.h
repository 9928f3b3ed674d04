/* A small JSON reader for the tests: they read docs/sact-modbus-map.json directly. */
#ifndef TESTS_JSON_MINI_H
#define TESTS_JSON_MINI_H

typedef enum { JSON_NULL, JSON_BOOL, JSON_NUMBER, JSON_STRING, JSON_ARRAY, JSON_OBJECT } json_type_t;

typedef struct json {
    json_type_t type;
    double number;           /* numbers and booleans */
    char *string;
    struct json **items;     /* array elements or object values */
    char **keys;             /* object keys */
    int count;
} json_t;

/* Parses a file; NULL (with a message on stderr) on error. */
json_t *json_load(const char *path);
const json_t *json_get(const json_t *object, const char *key);
const char *json_str(const json_t *object, const char *key);   /* "" when absent */
double json_num(const json_t *object, const char *key, double fallback);
void json_free(json_t *j);

#endif
