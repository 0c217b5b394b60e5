/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Unity-compatible test runner (see unity.h for scope and differences).
 * Output format follows Unity:
 *   FILE:LINE:TEST:PASS
 *   FILE:LINE:TEST:FAIL: message
 *   FILE:LINE:TEST:IGNORE: message
 * and UNITY_END's "N Tests F Failures I Ignored" summary.
 */
#include "unity.h"

#include <stdio.h>
#include <string.h>

struct UNITY_STORAGE_T Unity;

/* ---- output ----------------------------------------------------------- */

static void print(const char *s)
{
    while (*s != '\0') {
        UNITY_OUTPUT_CHAR(*s);
        s++;
    }
}

static void print_unsigned(UNITY_UINT n)
{
    char buf[24];
    int i = 0;
    do {
        buf[i++] = (char)('0' + (int)(n % 10u));
        n /= 10u;
    } while (n != 0u);
    while (i > 0) {
        UNITY_OUTPUT_CHAR(buf[--i]);
    }
}

static void print_signed(UNITY_INT n)
{
    if (n < 0) {
        UNITY_OUTPUT_CHAR('-');
        print_unsigned(0u - (UNITY_UINT)n); /* also right for the minimum */
    } else {
        print_unsigned((UNITY_UINT)n);
    }
}

static void print_hex(UNITY_UINT n, int nibbles)
{
    print("0x");
    while (nibbles-- > 0) {
        UNITY_OUTPUT_CHAR("0123456789ABCDEF"[(n >> (4 * nibbles)) & 0xFu]);
    }
}

static void print_number(UNITY_INT n, UNITY_DISPLAY_STYLE_T style)
{
    switch (style) {
    case UNITY_DISPLAY_STYLE_UINT:
        print_unsigned((UNITY_UINT)n);
        break;
    case UNITY_DISPLAY_STYLE_HEX8:
        print_hex((UNITY_UINT)n, 2);
        break;
    default:
        print_signed(n);
        break;
    }
}

static void print_float(UNITY_FLOAT f)
{
    char buf[32];
    if (isnan(f)) {
        print("nan"); /* Unity prints NaN without a sign */
        return;
    }
    if (isinf(f)) {
        print(f < 0.0f ? "-inf" : "inf");
        return;
    }
    (void)snprintf(buf, sizeof buf, "%.7g", (double)f);
    print(buf);
}

static void result_begin(UNITY_LINE_TYPE line)
{
    print(Unity.TestFile != NULL ? Unity.TestFile : "");
    UNITY_OUTPUT_CHAR(':');
    print_unsigned(line);
    UNITY_OUTPUT_CHAR(':');
    print(Unity.CurrentTestName != NULL ? Unity.CurrentTestName : "");
    UNITY_OUTPUT_CHAR(':');
}

static void fail_begin(UNITY_LINE_TYPE line)
{
    result_begin(line);
    print("FAIL:");
}

static void add_message(const char *msg)
{
    if (msg != NULL) {
        print(". ");
        print(msg);
    }
}

/* ---- control flow ----------------------------------------------------- */

/* Ends the current test; the setjmp in UnityDefaultTestRun resumes. */
static UNITY_NORETURN void fail_and_bail(void)
{
    Unity.CurrentTestFailed = 1;
    UNITY_OUTPUT_FLUSH();
    TEST_ABORT();
}

/* As in Unity, an assertion after the test already failed or was ignored
 * (e.g. in tearDown) only ends that function. */
static void return_if_done(void)
{
    if (Unity.CurrentTestFailed || Unity.CurrentTestIgnored) {
        TEST_ABORT();
    }
}

void UnityBegin(const char *filename)
{
    Unity.TestFile = filename;
    Unity.CurrentTestName = NULL;
    Unity.CurrentTestLineNumber = 0;
    Unity.NumberOfTests = 0;
    Unity.TestFailures = 0;
    Unity.TestIgnores = 0;
    Unity.CurrentTestFailed = 0;
    Unity.CurrentTestIgnored = 0;
}

void UnityDefaultTestRun(UnityTestFunction func, const char *name, int line)
{
    Unity.CurrentTestName = name;
    Unity.CurrentTestLineNumber = (UNITY_LINE_TYPE)line;
    Unity.NumberOfTests++;
    if (TEST_PROTECT()) {
        setUp();
        func();
    }
    if (TEST_PROTECT()) {
        tearDown();
    }
    if (Unity.CurrentTestIgnored) {
        Unity.TestIgnores++;
    } else if (Unity.CurrentTestFailed) {
        Unity.TestFailures++;
    } else {
        result_begin(Unity.CurrentTestLineNumber);
        print("PASS");
    }
    Unity.CurrentTestFailed = 0;
    Unity.CurrentTestIgnored = 0;
    UNITY_OUTPUT_CHAR('\n');
    UNITY_OUTPUT_FLUSH();
}

int UnityEnd(void)
{
    print("\n-----------------------\n");
    print_unsigned(Unity.NumberOfTests);
    print(" Tests ");
    print_unsigned(Unity.TestFailures);
    print(" Failures ");
    print_unsigned(Unity.TestIgnores);
    print(" Ignored \n");
    print(Unity.TestFailures == 0u ? "OK\n" : "FAIL\n");
    UNITY_OUTPUT_FLUSH();
    return (int)Unity.TestFailures;
}

void UnityFail(const char *msg, UNITY_LINE_TYPE line)
{
    return_if_done();
    result_begin(line);
    print("FAIL");
    if (msg != NULL) {
        UNITY_OUTPUT_CHAR(':');
        if (msg[0] != ' ') {
            UNITY_OUTPUT_CHAR(' ');
        }
        print(msg);
    }
    fail_and_bail();
}

void UnityIgnore(const char *msg, UNITY_LINE_TYPE line)
{
    return_if_done();
    result_begin(line);
    print("IGNORE");
    if (msg != NULL) {
        print(": ");
        print(msg);
    }
    Unity.CurrentTestIgnored = 1;
    UNITY_OUTPUT_FLUSH();
    TEST_ABORT();
}

void UnityMessage(const char *msg, UNITY_LINE_TYPE line)
{
    result_begin(line);
    print("INFO");
    if (msg != NULL) {
        print(": ");
        print(msg);
    }
    UNITY_OUTPUT_CHAR('\n');
}

/* ---- integer assertions ----------------------------------------------- */

void UnityAssertEqualNumber(UNITY_INT expected, UNITY_INT actual, const char *msg, UNITY_LINE_TYPE line,
                            UNITY_DISPLAY_STYLE_T style)
{
    return_if_done();
    if (expected != actual) {
        fail_begin(line);
        print(" Expected ");
        print_number(expected, style);
        print(" Was ");
        print_number(actual, style);
        add_message(msg);
        fail_and_bail();
    }
}

void UnityAssertGreaterOrLessOrEqualNumber(UNITY_INT threshold, UNITY_INT actual, UNITY_COMPARISON_T compare,
                                           const char *msg, UNITY_LINE_TYPE line, UNITY_DISPLAY_STYLE_T style)
{
    int ok;
    if (style == UNITY_DISPLAY_STYLE_INT) {
        ok = ((compare & UNITY_GREATER_THAN) && actual > threshold) ||
             ((compare & UNITY_SMALLER_THAN) && actual < threshold);
    } else {
        ok = ((compare & UNITY_GREATER_THAN) && (UNITY_UINT)actual > (UNITY_UINT)threshold) ||
             ((compare & UNITY_SMALLER_THAN) && (UNITY_UINT)actual < (UNITY_UINT)threshold);
    }
    ok = ok || ((compare & UNITY_EQUAL_TO) && actual == threshold);

    return_if_done();
    if (!ok) {
        fail_begin(line);
        print(" Expected ");
        print_number(actual, style);
        print((compare & UNITY_GREATER_THAN) ? " to be greater than " : " to be less than ");
        if (compare & UNITY_EQUAL_TO) {
            print("or equal to ");
        }
        print_number(threshold, style);
        add_message(msg);
        fail_and_bail();
    }
}

/* Unity's checks before comparing two arrays: fails on an empty length or a
 * NULL side; returns 0 when both are the same pointer (nothing to compare). */
static int arrays_to_compare(const void *expected, const void *actual, UNITY_UINT32 num, const char *msg,
                             UNITY_LINE_TYPE line)
{
    if (num == 0u) {
        fail_begin(line);
        print(" You Asked Me To Compare Nothing, Which Was Pointless.");
        add_message(msg);
        fail_and_bail();
    }
    if (expected == actual) {
        return 0;
    }
    if (expected == NULL || actual == NULL) {
        fail_begin(line);
        print(expected == NULL ? " Expected pointer to be NULL" : " Actual pointer was NULL");
        add_message(msg);
        fail_and_bail();
    }
    return 1;
}

void UnityAssertEqualIntArray(const void *expected, const void *actual, UNITY_UINT32 num, const char *msg,
                              UNITY_LINE_TYPE line)
{
    const int *e = expected;
    const int *a = actual;
    UNITY_UINT32 i;

    return_if_done();
    if (!arrays_to_compare(e, a, num, msg, line)) {
        return;
    }
    for (i = 0; i < num; i++) {
        if (e[i] != a[i]) {
            fail_begin(line);
            print(" Element ");
            print_unsigned(i);
            print(" Expected ");
            print_signed(e[i]);
            print(" Was ");
            print_signed(a[i]);
            add_message(msg);
            fail_and_bail();
        }
    }
}

void UnityAssertEqualMemory(const void *expected, const void *actual, UNITY_UINT32 len, const char *msg,
                            UNITY_LINE_TYPE line)
{
    const unsigned char *e = expected;
    const unsigned char *a = actual;
    UNITY_UINT32 i;

    return_if_done();
    if (!arrays_to_compare(e, a, len, msg, line)) {
        return;
    }
    for (i = 0; i < len; i++) {
        if (e[i] != a[i]) {
            fail_begin(line);
            print(" Memory Mismatch. Byte ");
            print_unsigned(i);
            print(" Expected ");
            print_hex(e[i], 2);
            print(" Was ");
            print_hex(a[i], 2);
            add_message(msg);
            fail_and_bail();
        }
    }
}

static void print_quoted(const char *s)
{
    if (s == NULL) {
        print("NULL");
    } else {
        UNITY_OUTPUT_CHAR('\'');
        print(s);
        UNITY_OUTPUT_CHAR('\'');
    }
}

void UnityAssertEqualString(const char *expected, const char *actual, const char *msg, UNITY_LINE_TYPE line)
{
    int same = (expected == NULL || actual == NULL) ? (expected == actual) : (strcmp(expected, actual) == 0);
    return_if_done();
    if (!same) {
        fail_begin(line);
        print(" Expected ");
        print_quoted(expected);
        print(" Was ");
        print_quoted(actual);
        add_message(msg);
        fail_and_bail();
    }
}

/* ---- float assertions ------------------------------------------------- */

/* Unity's rule: equal infinities and NaN == NaN count as within; otherwise
 * |actual - expected| <= |delta|, and any NaN or infinite difference fails. */
static int floats_within(UNITY_FLOAT delta, UNITY_FLOAT expected, UNITY_FLOAT actual)
{
    UNITY_FLOAT diff;
    if (isinf(expected) && isinf(actual) && ((expected < 0.0f) == (actual < 0.0f))) {
        return 1;
    }
    if (isnan(expected) && isnan(actual)) {
        return 1;
    }
    diff = fabsf(actual - expected);
    delta = fabsf(delta);
    return !(isnan(diff) || isinf(diff) || diff > delta);
}

void UnityAssertFloatsWithin(UNITY_FLOAT delta, UNITY_FLOAT expected, UNITY_FLOAT actual, const char *msg,
                             UNITY_LINE_TYPE line)
{
    return_if_done();
    if (!floats_within(delta, expected, actual)) {
        fail_begin(line);
        print(" Expected ");
        print_float(expected);
        print(" Was ");
        print_float(actual);
        add_message(msg);
        fail_and_bail();
    }
}

void UnityAssertGreaterOrLessFloat(UNITY_FLOAT threshold, UNITY_FLOAT actual, UNITY_COMPARISON_T compare,
                                   const char *msg, UNITY_LINE_TYPE line)
{
    /* Written as "not success" so a NaN never passes. */
    int failed = ((compare & UNITY_SMALLER_THAN) && !(actual < threshold)) ||
                 ((compare & UNITY_GREATER_THAN) && !(actual > threshold));
    if ((compare & UNITY_EQUAL_TO) && floats_within(threshold * UNITY_FLOAT_PRECISION, threshold, actual)) {
        failed = 0;
    }

    return_if_done();
    if (failed) {
        fail_begin(line);
        print(" Expected ");
        print_float(actual);
        print((compare & UNITY_GREATER_THAN) ? " to be greater than " : " to be less than ");
        if (compare & UNITY_EQUAL_TO) {
            print("or equal to ");
        }
        print_float(threshold);
        add_message(msg);
        fail_and_bail();
    }
}

void UnityAssertFloatSpecial(UNITY_FLOAT actual, const char *msg, UNITY_LINE_TYPE line, UNITY_FLOAT_TRAIT_T trait)
{
    int want = (trait == UNITY_FLOAT_IS_NAN || trait == UNITY_FLOAT_IS_DET);
    int is_nan_trait = (trait == UNITY_FLOAT_IS_NAN || trait == UNITY_FLOAT_IS_NOT_NAN);
    int has = is_nan_trait ? (isnan(actual) != 0) : (isfinite(actual) != 0);

    return_if_done();
    if (has != want) {
        fail_begin(line);
        print(" Expected ");
        if (!want) {
            print("Not ");
        }
        print(is_nan_trait ? "NaN" : "Determinate");
        print(" Was ");
        print_float(actual);
        add_message(msg);
        fail_and_bail();
    }
}

void UnityAssertEqualFloatArray(const UNITY_FLOAT *expected, const UNITY_FLOAT *actual, UNITY_UINT32 num,
                                const char *msg, UNITY_LINE_TYPE line)
{
    UNITY_UINT32 i;

    return_if_done();
    if (!arrays_to_compare(expected, actual, num, msg, line)) {
        return;
    }
    for (i = 0; i < num; i++) {
        if (!floats_within(expected[i] * UNITY_FLOAT_PRECISION, expected[i], actual[i])) {
            fail_begin(line);
            print(" Element ");
            print_unsigned(i);
            print(" Expected ");
            print_float(expected[i]);
            print(" Was ");
            print_float(actual[i]);
            add_message(msg);
            fail_and_bail();
        }
    }
}
