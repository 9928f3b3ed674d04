/*
 * Minimal test harness: each test is a function; it passes when none of its CHECKs
 * fail. A suite ends with "<suite>: N passed, N failed" for tests/run_all.sh.
 */
#ifndef TESTS_CHECK_H
#define TESTS_CHECK_H

#include <stdio.h>

static int check_failures_in_test;
static int tests_passed, tests_failed;

#define CHECK(cond, ...)                                                            \
    do {                                                                            \
        if (!(cond)) {                                                              \
            check_failures_in_test++;                                               \
            printf("    FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);              \
            printf(__VA_ARGS__);                                                    \
            printf("\n");                                                           \
        }                                                                           \
    } while (0)

#define RUN(test)                                                                   \
    do {                                                                            \
        check_failures_in_test = 0;                                                 \
        test();                                                                     \
        if (check_failures_in_test == 0) {                                          \
            tests_passed++;                                                         \
            printf("  ok   %s\n", #test);                                           \
        } else {                                                                    \
            tests_failed++;                                                         \
            printf("  FAIL %s\n", #test);                                           \
        }                                                                           \
        fflush(stdout);                                                             \
    } while (0)

#define REPORT(suite)                                                               \
    (printf("%s: %d passed, %d failed\n", suite, tests_passed, tests_failed),       \
     tests_failed ? 1 : 0)

#endif
