/* SPDX-License-Identifier: BSD-3-Clause */
/* Which form a CSV log is read in (log/log_convert.h, sim_log_csv_format_of):
 * ulog2csv's topic names count in the file's name only, never in the names
 * of the folders it lies in; Betaflight's by its header. A log that is not a
 * regular file (a pipe) is refused before a byte of it is read. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include "unity.h"
#include "log/log_convert.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char dir[64];
static char inner[96];
static char file[160];

void setUp(void)
{
    snprintf(dir, sizeof dir, "/tmp/ladrc_form_XXXXXX");
    TEST_ASSERT_NOT_NULL(mkdtemp(dir));
    /* a folder whose name holds a PX4 topic's pattern */
    snprintf(inner, sizeof inner, "%s/flights_vehicle_attitude_2024", dir);
    TEST_ASSERT_EQUAL_INT(0, mkdir(inner, 0700));
}

void tearDown(void)
{
    remove(file);
    rmdir(inner);
    rmdir(dir);
}

static void write_csv(const char *name, const char *header)
{
    snprintf(file, sizeof file, "%s/%s", inner, name);
    FILE *f = fopen(file, "w");
    TEST_ASSERT_NOT_NULL(f);
    fprintf(f, "%s\n0,1\n0.001,1\n", header);
    fclose(f);
}

static void test_a_folder_named_like_a_px4_topic_does_not_make_a_log_px4(void)
{
    write_csv("flight.csv", "time,gyro[0]");
    TEST_ASSERT_EQUAL_INT(SIM_LOG_GENERIC, sim_log_csv_format_of(file));
}

static void test_a_file_named_as_ulog2csv_names_a_topic_is_px4(void)
{
    write_csv("flight_vehicle_attitude_0.csv", "timestamp,q[0]");
    TEST_ASSERT_EQUAL_INT(SIM_LOG_PX4, sim_log_csv_format_of(file));
}

static void test_a_blackbox_decode_header_is_betaflight(void)
{
    write_csv("btfl_001.csv", "loopIteration,time (us),gyroADC[0]");
    TEST_ASSERT_EQUAL_INT(SIM_LOG_BETAFLIGHT, sim_log_csv_format_of(file));
}

static void test_a_pipe_is_refused_before_a_byte_is_read(void)
{
    snprintf(file, sizeof file, "%s/flight.csv", inner);
    TEST_ASSERT_EQUAL_INT(0, mkfifo(file, 0600));
    sim_log_options_t o;
    sim_log_options_default(&o);
    snprintf(o.path, sizeof o.path, "%s", file);
    sim_log_prepared_t prepared;
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT(-1, sim_log_prepare(&o, 0, &prepared, NULL, NULL, &err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, "not a regular file (a pipe or a device)"), err.message);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_a_folder_named_like_a_px4_topic_does_not_make_a_log_px4);
    RUN_TEST(test_a_file_named_as_ulog2csv_names_a_topic_is_px4);
    RUN_TEST(test_a_blackbox_decode_header_is_betaflight);
    RUN_TEST(test_a_pipe_is_refused_before_a_byte_is_read);
    return UNITY_END();
}
