/* SPDX-License-Identifier: BSD-3-Clause */
/* LADRC_CONFIG header of the asserts stage (tools/run_tests.sh asserts):
 * programmer errors abort through the C library's assert. */
#ifndef LADRC_TEST_ASSERT_CONFIG_H
#define LADRC_TEST_ASSERT_CONFIG_H
#include <assert.h>
#define LADRC_ASSERT(cond) assert(cond)
#endif
