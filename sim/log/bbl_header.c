/* SPDX-License-Identifier: BSD-3-Clause */
/* The blackbox log's header: its `H name:value` lines into the decoder's
 * frame definitions and constants, checked (bbl_decoder.h). */
#include "bbl_decoder.h"

#include <stdlib.h>
#include <string.h>

/* deg/s per logged gyro unit: Baseflight's and old Cleanflight's counts are
 * some 0.06 deg/s, Betaflight logs deg/s (1); outside these bounds no gyro's */
#define GYRO_SCALE_MIN 1e-9
#define GYRO_SCALE_MAX 1e6

/* A comma-separated list of integers into v (missing entries stay 0). */
static void parse_ints(const char *text, int *v, int max)
{
    for (int i = 0; i < max && *text != '\0'; ++i) {
        v[i] = (int)strtol(text, NULL, 10);
        text = strchr(text, ',');
        if (text == NULL) {
            break;
        }
        ++text;
    }
}

static int field_index(const frame_def_t *def, const char *name)
{
    for (int i = 0; i < def->n; ++i) {
        if (strcmp(def->names + def->name_at[i], name) == 0) {
            return i;
        }
    }
    return -1;
}

static int parse_names(frame_def_t *def, const char *value)
{
    snprintf(def->names, sizeof def->names, "%s", value);
    def->n = 0;
    for (char *p = def->names;;) {
        if (def->n == MAX_FIELDS) {
            return -1;
        }
        def->name_at[def->n++] = (int)(p - def->names);
        p = strchr(p, ',');
        if (p == NULL) {
            return 0;
        }
        *p++ = '\0';
    }
}

static long clamp_long(long v, long lo, long hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

/* One `H name:value` line (without its end). 0, or -1 with a message. */
static int header_line(decoder_t *d, char *line, const char **msg)
{
    char *colon = strchr(line, ':');
    if (colon == NULL) {
        return 0; /* not a name:value pair: ignored, as blackbox_decode does */
    }
    *colon = '\0';
    const char *name = line, *value = colon + 1;
    if (strncmp(name, "Field ", 6) == 0 && name[6] != '\0' && name[7] == ' ') {
        const int t = bbl_type_of((unsigned char)name[6]);
        const char *what = name + 8;
        if (t < 0 || t == T_E) {
            return 0;
        }
        frame_def_t *def = &d->def[t];
        if (strcmp(what, "name") == 0) {
            if (parse_names(def, value) != 0) {
                *msg = "more than 128 fields in a frame";
                return -1;
            }
            if (t == T_I) { /* P frames have the I frame's fields */
                memcpy(d->def[T_P].names, def->names, sizeof def->names);
                memcpy(d->def[T_P].name_at, def->name_at, sizeof def->name_at);
                d->def[T_P].n = def->n;
            }
        } else if (strcmp(what, "signed") == 0) {
            parse_ints(value, def->is_signed, MAX_FIELDS);
            if (t == T_I) {
                memcpy(d->def[T_P].is_signed, def->is_signed, sizeof def->is_signed);
            }
        } else if (strcmp(what, "predictor") == 0) {
            parse_ints(value, def->predictor, MAX_FIELDS);
        } else if (strcmp(what, "encoding") == 0) {
            parse_ints(value, def->encoding, MAX_FIELDS);
        }
    } else if (strcmp(name, "Data version") == 0) {
        d->data_version = (int)strtol(value, NULL, 10);
    } else if (strcmp(name, "I interval") == 0) {
        d->i_interval = clamp_long(strtol(value, NULL, 10), 1, INTERVAL_MAX);
    } else if (strcmp(name, "P interval") == 0 && strchr(value, '/') != NULL) {
        /* `num/denom`; a plain number (newer firmware's) leaves 1/1, as blackbox_decode does */
        d->p_num = clamp_long(strtol(value, NULL, 10), 1, INTERVAL_MAX);
        d->p_denom = clamp_long(strtol(strchr(value, '/') + 1, NULL, 10), 1, INTERVAL_MAX);
    } else if (strcmp(name, "Firmware type") == 0) {
        d->baseflight = strcmp(value, "Cleanflight") != 0;
    } else if (strcmp(name, "minthrottle") == 0) {
        d->minthrottle = strtol(value, NULL, 10);
        d->motor_low = d->minthrottle; /* until motorOutput says otherwise */
    } else if (strcmp(name, "motorOutput") == 0) {
        d->motor_low = strtol(value, NULL, 10);
    } else if (strcmp(name, "vbatref") == 0) {
        d->vbatref = strtol(value, NULL, 10);
    } else if (strcmp(name, "gyro_scale") == 0 || strcmp(name, "gyro.scale") == 0) {
        const uint32_t bits = (uint32_t)strtoul(value, NULL, 16); /* the float's bits, in hex */
        float f;
        memcpy(&f, &bits, sizeof f);
        d->gyro_scale = f;
        d->has_gyro_scale = 1;
    }
    return 0;
}

static int known_encoding(int e)
{
    return e == BBL_ENC_SIGNED_VB || e == BBL_ENC_UNSIGNED_VB || e == BBL_ENC_NEG_14BIT || e == BBL_ENC_NULL ||
           bbl_is_group(e);
}

/* The frame definitions hold together: 0, or -1 with a message. */
static int check_defs(decoder_t *d, char *msg, size_t len)
{
    const frame_def_t *in = &d->def[T_I];
    if (in->n < 2 || strcmp(in->names + in->name_at[0], "loopIteration") != 0 ||
        strcmp(in->names + in->name_at[1], "time") != 0) {
        snprintf(msg, len, "no 'H Field I name' line starting loopIteration,time: not a main frame layout");
        return -1;
    }
    for (int t = 0; t < T_E; ++t) {
        for (int i = 0; i < d->def[t].n; ++i) {
            const int e = d->def[t].encoding[i], p = d->def[t].predictor[i];
            if (!known_encoding(e)) {
                snprintf(msg, len, "field %d of the %c frame: encoding %d is none of the format's", i + 1, TYPES[t], e);
                return -1;
            }
            if (p < 0 || p >= PRED_COUNT) {
                snprintf(msg, len, "field %d of the %c frame: predictor %d is none of the format's", i + 1, TYPES[t],
                         p);
                return -1;
            }
            if ((t == T_I || t == T_P) && p == PRED_MOTOR_0 && d->motor0 < 0) {
                snprintf(msg, len, "field %d of the %c frame: predicted from motor[0], which no field is", i + 1,
                         TYPES[t]);
                return -1;
            }
        }
    }
    if (!(d->gyro_deg_s_per_unit >= GYRO_SCALE_MIN && d->gyro_deg_s_per_unit <= GYRO_SCALE_MAX)) {
        snprintf(msg, len, "gyro_scale gives %g deg/s per unit: no gyro's", d->gyro_deg_s_per_unit);
        return -1;
    }
    /* home coordinates come in pairs: the second of each takes the home's second */
    frame_def_t *g = &d->def[T_G];
    for (int i = 1; i < g->n; ++i) {
        if (g->predictor[i - 1] == PRED_HOME_COORD && g->predictor[i] == PRED_HOME_COORD) {
            g->predictor[i] = PRED_HOME_COORD_1;
        }
    }
    return 0;
}

static void find_fields(decoder_t *d)
{
    char name[16];
    d->motor0 = field_index(&d->def[T_I], "motor[0]");
    for (int i = 0; i < 3; ++i) {
        snprintf(name, sizeof name, "gyroADC[%d]", i);
        d->gyro[i] = field_index(&d->def[T_I], name);
    }
    for (int i = 0; i < 2; ++i) {
        snprintf(name, sizeof name, "GPS_home[%d]", i);
        d->home[i] = field_index(&d->def[T_H], name);
    }
    /* the gyro as logged unless its scale says it is not deg/s */
    if (d->has_gyro_scale && d->baseflight) {
        d->gyro_deg_s_per_unit = d->gyro_scale * 1e6 * (180.0 / 3.14159265358979323846);
    } else {
        d->gyro_deg_s_per_unit = d->has_gyro_scale ? d->gyro_scale : 1.0;
    }
    d->convert_gyro = d->gyro_deg_s_per_unit != 1.0;
}

/* Reads the header lines from the log's start: 0, or -1 with err set. */
int bbl_read_header(decoder_t *d, sim_log_error_t *err)
{
    char line[HEADER_LINE_MAX + 1], msg[200];
    const char *bad = NULL;
    while (bbl_stream_peek(&d->in) == 'H') {
        bbl_stream_frame_start(&d->in);
        const long long at = bbl_stream_offset(&d->in);
        size_t n = 0;
        int c = 0;
        (void)bbl_read_byte(&d->in); /* 'H' */
        if (bbl_stream_peek(&d->in) != ' ') {
            break; /* an H frame's marker, or garbage: the data begin */
        }
        (void)bbl_read_byte(&d->in);
        while ((c = bbl_stream_peek(&d->in)) >= 0 && c != '\n' && c != '\0' && n < HEADER_LINE_MAX) {
            line[n++] = (char)bbl_read_byte(&d->in);
        }
        if (c != '\n') { /* cut, binary or too long: the header is over */
            bbl_stream_seek_back(&d->in, at);
            break;
        }
        (void)bbl_read_byte(&d->in);
        line[n] = '\0';
        if (header_line(d, line, &bad) != 0) {
            return bbl_fail_at(err, d, at, bad);
        }
    }
    find_fields(d);
    if (check_defs(d, msg, sizeof msg) != 0) {
        return bbl_fail_at(err, d, bbl_stream_offset(&d->in), msg);
    }
    return 0;
}
