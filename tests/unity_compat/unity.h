/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Unity-compatible test runner: the subset of Unity's API (v2.6) that the
 * ladrc tests use, with Unity's semantics and output format, so the same
 * test files build against either this runner or the real Unity.
 *
 * Semantics kept from Unity: the first failed assertion ends the current
 * test (setjmp/longjmp), tearDown still runs; setUp/tearDown are declared
 * here and defined by each test file; UNITY_END prints the summary and
 * returns the failure count; float asserts work on UNITY_FLOAT (float);
 * TEST_ASSERT_EQUAL_FLOAT(e, a) passes when |a - e| <= |e| * 0.00001;
 * threshold asserts take (threshold, actual), e.g. LESS_THAN passes when
 * actual < threshold.
 *
 * Small, deliberate differences:
 *  - floats print with printf "%.7g": 7 significant digits and exponents
 *    like Unity ("1.5", "1e-05", "1e+10"), but the 7th digit is rounded
 *    exactly, where Unity's own printer may be one off (0.3333334);
 *  - integers are compared and printed as 64-bit on every target;
 *  - UNITY_OUTPUT_FLUSH() flushes stdout by default (Unity: only with
 *    UNITY_USE_FLUSH_STDOUT);
 *  - no details, test context, colour, command-line filtering or doubles.
 */
#ifndef UNITY_FRAMEWORK_H
#define UNITY_FRAMEWORK_H

#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>

/* All output goes through this one character function. */
#ifndef UNITY_OUTPUT_CHAR
#include <stdio.h>
#define UNITY_OUTPUT_CHAR(c) (void)putchar(c)
#endif
#ifndef UNITY_OUTPUT_FLUSH
#include <stdio.h>
#define UNITY_OUTPUT_FLUSH() (void)fflush(stdout)
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef float UNITY_FLOAT;
typedef long long UNITY_INT;
typedef unsigned long long UNITY_UINT;
typedef uint32_t UNITY_UINT32;
typedef unsigned long UNITY_LINE_TYPE;
typedef void (*UnityTestFunction)(void);

#define UNITY_FLOAT_PRECISION (0.00001f)

/* Failing and ignoring never return (as in Unity), which also tells
 * compilers and analysers that e.g. a pointer checked non-NULL is. */
#if defined(__GNUC__)
#define UNITY_NORETURN __attribute__((noreturn))
#else
#define UNITY_NORETURN
#endif

/* Defined by each test file, run around every test. */
void setUp(void);
void tearDown(void);

struct UNITY_STORAGE_T {
    const char *TestFile;
    const char *CurrentTestName;
    UNITY_LINE_TYPE CurrentTestLineNumber;
    UNITY_UINT NumberOfTests;
    UNITY_UINT TestFailures;
    UNITY_UINT TestIgnores;
    int CurrentTestFailed;
    int CurrentTestIgnored;
    jmp_buf AbortFrame;
};
extern struct UNITY_STORAGE_T Unity;

typedef enum { UNITY_DISPLAY_STYLE_INT, UNITY_DISPLAY_STYLE_UINT, UNITY_DISPLAY_STYLE_HEX8 } UNITY_DISPLAY_STYLE_T;

typedef enum {
    UNITY_GREATER_THAN = 1,
    UNITY_SMALLER_THAN = 2,
    UNITY_EQUAL_TO = 4,
    UNITY_GREATER_OR_EQUAL = 5,
    UNITY_SMALLER_OR_EQUAL = 6
} UNITY_COMPARISON_T;

typedef enum {
    UNITY_FLOAT_IS_NAN,
    UNITY_FLOAT_IS_NOT_NAN,
    UNITY_FLOAT_IS_DET,
    UNITY_FLOAT_IS_NOT_DET
} UNITY_FLOAT_TRAIT_T;

void UnityBegin(const char *filename);
int UnityEnd(void);
void UnityDefaultTestRun(UnityTestFunction func, const char *name, int line);
UNITY_NORETURN void UnityFail(const char *msg, UNITY_LINE_TYPE line);
UNITY_NORETURN void UnityIgnore(const char *msg, UNITY_LINE_TYPE line);
void UnityMessage(const char *msg, UNITY_LINE_TYPE line);
void UnityAssertEqualNumber(UNITY_INT expected, UNITY_INT actual, const char *msg, UNITY_LINE_TYPE line,
                            UNITY_DISPLAY_STYLE_T style);
void UnityAssertGreaterOrLessOrEqualNumber(UNITY_INT threshold, UNITY_INT actual, UNITY_COMPARISON_T compare,
                                           const char *msg, UNITY_LINE_TYPE line, UNITY_DISPLAY_STYLE_T style);
void UnityAssertEqualIntArray(const void *expected, const void *actual, UNITY_UINT32 num, const char *msg,
                              UNITY_LINE_TYPE line);
void UnityAssertEqualMemory(const void *expected, const void *actual, UNITY_UINT32 len, const char *msg,
                            UNITY_LINE_TYPE line);
void UnityAssertEqualString(const char *expected, const char *actual, const char *msg, UNITY_LINE_TYPE line);
void UnityAssertFloatsWithin(UNITY_FLOAT delta, UNITY_FLOAT expected, UNITY_FLOAT actual, const char *msg,
                             UNITY_LINE_TYPE line);
void UnityAssertGreaterOrLessFloat(UNITY_FLOAT threshold, UNITY_FLOAT actual, UNITY_COMPARISON_T compare,
                                   const char *msg, UNITY_LINE_TYPE line);
void UnityAssertFloatSpecial(UNITY_FLOAT actual, const char *msg, UNITY_LINE_TYPE line, UNITY_FLOAT_TRAIT_T trait);
void UnityAssertEqualFloatArray(const UNITY_FLOAT *expected, const UNITY_FLOAT *actual, UNITY_UINT32 num,
                                const char *msg, UNITY_LINE_TYPE line);

/* ---- running ---------------------------------------------------------- */
#define UNITY_BEGIN() UnityBegin(__FILE__)
#define UNITY_END() UnityEnd()
#define RUN_TEST(func) UnityDefaultTestRun(func, #func, __LINE__)
#define TEST_PROTECT() (setjmp(Unity.AbortFrame) == 0)
#define TEST_ABORT() longjmp(Unity.AbortFrame, 1)

#define TEST_FAIL_MESSAGE(message) UnityFail((message), __LINE__)
#define TEST_FAIL() UnityFail(NULL, __LINE__)
#define TEST_IGNORE_MESSAGE(message) UnityIgnore((message), __LINE__)
#define TEST_IGNORE() UnityIgnore(NULL, __LINE__)
#define TEST_MESSAGE(message) UnityMessage((message), __LINE__)
#define TEST_PASS() TEST_ABORT()
#define TEST_PASS_MESSAGE(message)                                                                                     \
    do {                                                                                                               \
        UnityMessage((message), __LINE__);                                                                             \
        TEST_ABORT();                                                                                                  \
    } while (0)

/* ---- booleans and pointers -------------------------------------------- */
#define UNITY_TEST_ASSERT(condition, line, message)                                                                    \
    do {                                                                                                               \
        if (condition) {                                                                                               \
        } else {                                                                                                       \
            UnityFail((message), (UNITY_LINE_TYPE)(line));                                                             \
        }                                                                                                              \
    } while (0)

#define TEST_ASSERT_MESSAGE(c, message) UNITY_TEST_ASSERT((c), __LINE__, (message))
#define TEST_ASSERT(c) UNITY_TEST_ASSERT((c), __LINE__, " Expression Evaluated To FALSE")
#define TEST_ASSERT_TRUE_MESSAGE(c, message) UNITY_TEST_ASSERT((c), __LINE__, (message))
#define TEST_ASSERT_TRUE(c) UNITY_TEST_ASSERT((c), __LINE__, " Expected TRUE Was FALSE")
#define TEST_ASSERT_FALSE_MESSAGE(c, message) UNITY_TEST_ASSERT(!(c), __LINE__, (message))
#define TEST_ASSERT_FALSE(c) UNITY_TEST_ASSERT(!(c), __LINE__, " Expected FALSE Was TRUE")
#define TEST_ASSERT_NULL_MESSAGE(p, message) UNITY_TEST_ASSERT(((p) == NULL), __LINE__, (message))
#define TEST_ASSERT_NULL(p) UNITY_TEST_ASSERT(((p) == NULL), __LINE__, " Expected NULL")
#define TEST_ASSERT_NOT_NULL_MESSAGE(p, message) UNITY_TEST_ASSERT(((p) != NULL), __LINE__, (message))
#define TEST_ASSERT_NOT_NULL(p) UNITY_TEST_ASSERT(((p) != NULL), __LINE__, " Expected Non-NULL")

/* ---- integers --------------------------------------------------------- */
#define UNITY_EQ(e, a, message, style) UnityAssertEqualNumber((e), (a), (message), (UNITY_LINE_TYPE)__LINE__, (style))
#define UNITY_CMP(t, a, cmp, message)                                                                                  \
    UnityAssertGreaterOrLessOrEqualNumber((UNITY_INT)(t), (UNITY_INT)(a), (cmp), (message), (UNITY_LINE_TYPE)__LINE__, \
                                          UNITY_DISPLAY_STYLE_INT)

#define TEST_ASSERT_EQUAL_INT_MESSAGE(e, a, message)                                                                   \
    UNITY_EQ((UNITY_INT)(e), (UNITY_INT)(a), (message), UNITY_DISPLAY_STYLE_INT)
#define TEST_ASSERT_EQUAL_UINT_MESSAGE(e, a, message)                                                                  \
    UNITY_EQ((UNITY_INT)(e), (UNITY_INT)(a), (message), UNITY_DISPLAY_STYLE_UINT)
#define TEST_ASSERT_EQUAL_UINT8_MESSAGE(e, a, message)                                                                 \
    UNITY_EQ((UNITY_INT)(uint8_t)(e), (UNITY_INT)(uint8_t)(a), (message), UNITY_DISPLAY_STYLE_UINT)
#define TEST_ASSERT_EQUAL_UINT32_MESSAGE(e, a, message)                                                                \
    UNITY_EQ((UNITY_INT)(uint32_t)(e), (UNITY_INT)(uint32_t)(a), (message), UNITY_DISPLAY_STYLE_UINT)
#define TEST_ASSERT_EQUAL_HEX8_MESSAGE(e, a, message)                                                                  \
    UNITY_EQ((UNITY_INT)(uint8_t)(e), (UNITY_INT)(uint8_t)(a), (message), UNITY_DISPLAY_STYLE_HEX8)
#define TEST_ASSERT_EQUAL_MESSAGE(e, a, message) TEST_ASSERT_EQUAL_INT_MESSAGE((e), (a), (message))
#define TEST_ASSERT_NOT_EQUAL_MESSAGE(e, a, message) UNITY_TEST_ASSERT(((e) != (a)), __LINE__, (message))

#define TEST_ASSERT_EQUAL_INT(e, a) TEST_ASSERT_EQUAL_INT_MESSAGE((e), (a), NULL)
#define TEST_ASSERT_EQUAL_UINT(e, a) TEST_ASSERT_EQUAL_UINT_MESSAGE((e), (a), NULL)
#define TEST_ASSERT_EQUAL_UINT8(e, a) TEST_ASSERT_EQUAL_UINT8_MESSAGE((e), (a), NULL)
#define TEST_ASSERT_EQUAL_UINT32(e, a) TEST_ASSERT_EQUAL_UINT32_MESSAGE((e), (a), NULL)
#define TEST_ASSERT_EQUAL_HEX8(e, a) TEST_ASSERT_EQUAL_HEX8_MESSAGE((e), (a), NULL)
#define TEST_ASSERT_EQUAL(e, a) TEST_ASSERT_EQUAL_INT_MESSAGE((e), (a), NULL)
#define TEST_ASSERT_NOT_EQUAL(e, a) UNITY_TEST_ASSERT(((e) != (a)), __LINE__, " Expected Not-Equal")

#define TEST_ASSERT_GREATER_THAN_MESSAGE(t, a, message) UNITY_CMP((t), (a), UNITY_GREATER_THAN, (message))
#define TEST_ASSERT_GREATER_THAN_INT_MESSAGE(t, a, message) UNITY_CMP((t), (a), UNITY_GREATER_THAN, (message))
#define TEST_ASSERT_LESS_THAN_MESSAGE(t, a, message) UNITY_CMP((t), (a), UNITY_SMALLER_THAN, (message))
#define TEST_ASSERT_LESS_THAN_INT_MESSAGE(t, a, message) UNITY_CMP((t), (a), UNITY_SMALLER_THAN, (message))
#define TEST_ASSERT_GREATER_OR_EQUAL_MESSAGE(t, a, message) UNITY_CMP((t), (a), UNITY_GREATER_OR_EQUAL, (message))
#define TEST_ASSERT_LESS_OR_EQUAL_MESSAGE(t, a, message) UNITY_CMP((t), (a), UNITY_SMALLER_OR_EQUAL, (message))
#define TEST_ASSERT_GREATER_THAN(t, a) TEST_ASSERT_GREATER_THAN_MESSAGE((t), (a), NULL)
#define TEST_ASSERT_GREATER_THAN_INT(t, a) TEST_ASSERT_GREATER_THAN_MESSAGE((t), (a), NULL)
#define TEST_ASSERT_LESS_THAN(t, a) TEST_ASSERT_LESS_THAN_MESSAGE((t), (a), NULL)
#define TEST_ASSERT_LESS_THAN_INT(t, a) TEST_ASSERT_LESS_THAN_MESSAGE((t), (a), NULL)
#define TEST_ASSERT_GREATER_OR_EQUAL(t, a) TEST_ASSERT_GREATER_OR_EQUAL_MESSAGE((t), (a), NULL)
#define TEST_ASSERT_LESS_OR_EQUAL(t, a) TEST_ASSERT_LESS_OR_EQUAL_MESSAGE((t), (a), NULL)

/* ---- floats ----------------------------------------------------------- */
#define TEST_ASSERT_FLOAT_WITHIN_MESSAGE(delta, e, a, message)                                                         \
    UnityAssertFloatsWithin((UNITY_FLOAT)(delta), (UNITY_FLOAT)(e), (UNITY_FLOAT)(a), (message), __LINE__)
#define TEST_ASSERT_EQUAL_FLOAT_MESSAGE(e, a, message)                                                                 \
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE((UNITY_FLOAT)(e)*UNITY_FLOAT_PRECISION, (e), (a), (message))
#define UNITY_FCMP(t, a, cmp, message)                                                                                 \
    UnityAssertGreaterOrLessFloat((UNITY_FLOAT)(t), (UNITY_FLOAT)(a), (cmp), (message), __LINE__)
#define TEST_ASSERT_LESS_THAN_FLOAT_MESSAGE(t, a, message) UNITY_FCMP((t), (a), UNITY_SMALLER_THAN, (message))
#define TEST_ASSERT_GREATER_THAN_FLOAT_MESSAGE(t, a, message) UNITY_FCMP((t), (a), UNITY_GREATER_THAN, (message))
#define TEST_ASSERT_LESS_OR_EQUAL_FLOAT_MESSAGE(t, a, message) UNITY_FCMP((t), (a), UNITY_SMALLER_OR_EQUAL, (message))
#define TEST_ASSERT_GREATER_OR_EQUAL_FLOAT_MESSAGE(t, a, message)                                                      \
    UNITY_FCMP((t), (a), UNITY_GREATER_OR_EQUAL, (message))
#define UNITY_FTRAIT(a, trait, message) UnityAssertFloatSpecial((UNITY_FLOAT)(a), (message), __LINE__, (trait))
#define TEST_ASSERT_FLOAT_IS_NAN_MESSAGE(a, message) UNITY_FTRAIT((a), UNITY_FLOAT_IS_NAN, (message))
#define TEST_ASSERT_FLOAT_IS_NOT_NAN_MESSAGE(a, message) UNITY_FTRAIT((a), UNITY_FLOAT_IS_NOT_NAN, (message))
#define TEST_ASSERT_FLOAT_IS_DETERMINATE_MESSAGE(a, message) UNITY_FTRAIT((a), UNITY_FLOAT_IS_DET, (message))
#define TEST_ASSERT_FLOAT_IS_NOT_DETERMINATE_MESSAGE(a, message) UNITY_FTRAIT((a), UNITY_FLOAT_IS_NOT_DET, (message))

#define TEST_ASSERT_FLOAT_WITHIN(delta, e, a) TEST_ASSERT_FLOAT_WITHIN_MESSAGE((delta), (e), (a), NULL)
#define TEST_ASSERT_EQUAL_FLOAT(e, a) TEST_ASSERT_EQUAL_FLOAT_MESSAGE((e), (a), NULL)
#define TEST_ASSERT_LESS_THAN_FLOAT(t, a) TEST_ASSERT_LESS_THAN_FLOAT_MESSAGE((t), (a), NULL)
#define TEST_ASSERT_GREATER_THAN_FLOAT(t, a) TEST_ASSERT_GREATER_THAN_FLOAT_MESSAGE((t), (a), NULL)
#define TEST_ASSERT_LESS_OR_EQUAL_FLOAT(t, a) TEST_ASSERT_LESS_OR_EQUAL_FLOAT_MESSAGE((t), (a), NULL)
#define TEST_ASSERT_GREATER_OR_EQUAL_FLOAT(t, a) TEST_ASSERT_GREATER_OR_EQUAL_FLOAT_MESSAGE((t), (a), NULL)
#define TEST_ASSERT_FLOAT_IS_NAN(a) TEST_ASSERT_FLOAT_IS_NAN_MESSAGE((a), NULL)
#define TEST_ASSERT_FLOAT_IS_NOT_NAN(a) TEST_ASSERT_FLOAT_IS_NOT_NAN_MESSAGE((a), NULL)
#define TEST_ASSERT_FLOAT_IS_DETERMINATE(a) TEST_ASSERT_FLOAT_IS_DETERMINATE_MESSAGE((a), NULL)
#define TEST_ASSERT_FLOAT_IS_NOT_DETERMINATE(a) TEST_ASSERT_FLOAT_IS_NOT_DETERMINATE_MESSAGE((a), NULL)

/* ---- memory, strings, arrays ------------------------------------------ */
#define TEST_ASSERT_EQUAL_MEMORY_MESSAGE(e, a, len, message)                                                           \
    UnityAssertEqualMemory((const void *)(e), (const void *)(a), (UNITY_UINT32)(len), (message), __LINE__)
#define TEST_ASSERT_EQUAL_STRING_MESSAGE(e, a, message)                                                                \
    UnityAssertEqualString((const char *)(e), (const char *)(a), (message), __LINE__)
#define TEST_ASSERT_EQUAL_INT_ARRAY_MESSAGE(e, a, n, message)                                                          \
    UnityAssertEqualIntArray((const void *)(e), (const void *)(a), (UNITY_UINT32)(n), (message), __LINE__)
#define TEST_ASSERT_EQUAL_FLOAT_ARRAY_MESSAGE(e, a, n, message)                                                        \
    UnityAssertEqualFloatArray((const UNITY_FLOAT *)(e), (const UNITY_FLOAT *)(a), (UNITY_UINT32)(n), (message),       \
                               __LINE__)

#define TEST_ASSERT_EQUAL_MEMORY(e, a, len) TEST_ASSERT_EQUAL_MEMORY_MESSAGE((e), (a), (len), NULL)
#define TEST_ASSERT_EQUAL_STRING(e, a) TEST_ASSERT_EQUAL_STRING_MESSAGE((e), (a), NULL)
#define TEST_ASSERT_EQUAL_INT_ARRAY(e, a, n) TEST_ASSERT_EQUAL_INT_ARRAY_MESSAGE((e), (a), (n), NULL)
#define TEST_ASSERT_EQUAL_FLOAT_ARRAY(e, a, n) TEST_ASSERT_EQUAL_FLOAT_ARRAY_MESSAGE((e), (a), (n), NULL)

#ifdef __cplusplus
}
#endif

#endif /* UNITY_FRAMEWORK_H */
