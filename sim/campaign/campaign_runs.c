/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * A campaign's runs (campaign.h): run r's values and settings, its
 * scenario, the plan of a shard, and the K/N text of a shard.
 */
#include <stdio.h>
#include <string.h>

#include "campaign.h"

typedef struct {
    char *buf;
    size_t n, cap;
    int overflow;
} text_t;

static void put(text_t *t, const char *s, size_t len)
{
    if (t->n + len + 1 > t->cap) {
        t->overflow = 1;
        return;
    }
    memcpy(t->buf + t->n, s, len);
    t->n += len;
    t->buf[t->n] = '\0';
}

static void puts_(text_t *t, const char *s)
{
    put(t, s, strlen(s));
}

int sim_campaign_expand(const sim_campaign_t *c, long r, sim_campaign_run_t *out, char *msg, size_t msg_len)
{
    out->run = r;
    out->n_settings = 0;
    if (r < 1 || r > c->n_runs) {
        snprintf(msg, msg_len, "run %ld: the campaign's runs are 1 to %ld", r, c->n_runs);
        return -1;
    }
    long point = (r - 1) / c->samples;
    for (int k = c->n_grid - 1; k >= 0; --k) {
        const sim_campaign_key_t *key = &c->keys[k];
        out->values[k] = key->values[point % key->n_values];
        point /= key->n_values;
    }
    for (int k = c->n_grid; k < c->n_keys; ++k) {
        out->values[k] = sim_campaign_draw(c, &c->keys[k], r);
    }
    for (int k = 0; k < c->n_keys; ++k) {
        sim_campaign_format_value(out->text[k], out->values[k]);
    }
    out->run_seed = sim_campaign_stream(c->seed, r, 0, 1);
    text_t t = {.buf = out->buf, .n = 0, .cap = sizeof out->buf, .overflow = 0};
    /* each setting is NUL-terminated in buf; pointers taken once it is full */
    size_t starts[SIM_CAMPAIGN_MAX_SETS + SIM_CAMPAIGN_MAX_VARIED + 1];
    if (!c->sets_seed) {
        char seed[40];
        snprintf(seed, sizeof seed, "run.seed=%llu", (unsigned long long)out->run_seed);
        starts[out->n_settings] = t.n;
        out->setting_line[out->n_settings++] = 0;
        puts_(&t, seed);
        put(&t, "", 0);
        t.n += 1;
    }
    for (int i = 0; i < c->n_sets; ++i) {
        const sim_campaign_set_t *s = &c->sets[i];
        starts[out->n_settings] = t.n;
        out->setting_line[out->n_settings++] = s->line;
        puts_(&t, s->key);
        puts_(&t, "=");
        for (const char *v = s->value; *v != '\0'; ++v) {
            const char *close = *v == '{' ? strchr(v, '}') : NULL;
            if (close == NULL) {
                put(&t, v, 1);
                continue;
            }
            const size_t len = (size_t)(close - v - 1);
            for (int k = 0; k < c->n_keys; ++k) {
                if (c->keys[k].is_variable && strlen(c->keys[k].name) == len &&
                    strncmp(c->keys[k].name, v + 1, len) == 0) {
                    puts_(&t, out->text[k]);
                }
            }
            v = close;
        }
        put(&t, "", 0);
        t.n += 1;
    }
    for (int k = 0; k < c->n_keys; ++k) {
        if (!c->keys[k].is_variable) {
            starts[out->n_settings] = t.n;
            out->setting_line[out->n_settings++] = c->keys[k].line;
            puts_(&t, c->keys[k].name);
            puts_(&t, "=");
            puts_(&t, out->text[k]);
            put(&t, "", 0);
            t.n += 1;
        }
    }
    if (t.overflow || t.n > t.cap) {
        snprintf(msg, msg_len, "run %ld: its settings are longer than %d characters", r, SIM_CAMPAIGN_RUN_TEXT);
        out->n_settings = 0;
        return -1;
    }
    for (int i = 0; i < out->n_settings; ++i) {
        out->settings[i] = out->buf + starts[i];
    }
    return 0;
}

int sim_campaign_load_run(const sim_campaign_t *c, const sim_campaign_run_t *run, const char *out_dir,
                          sim_scenario_t *sc, sim_parse_error_t *err)
{
    if (sim_scenario_parse_buffer_with(sc, c->base_text, c->base_len, c->base_path, run->settings, run->n_settings,
                                       err) != 0) {
        return -1;
    }
    sim_campaign_run_name(sc->name, sizeof sc->name, run->run);
    if (snprintf(sc->output_dir, sizeof sc->output_dir, "%s/runs/%s", out_dir, sc->name) >=
        (int)sizeof sc->output_dir) {
        memset(err, 0, sizeof *err);
        snprintf(err->path, sizeof err->path, "%s", out_dir);
        snprintf(err->message, sizeof err->message, "output directory path too long");
        return -1;
    }
    return 0;
}

int sim_campaign_write_plan(FILE *f, const sim_campaign_t *c, long shard_k, long shard_n)
{
    fputs("run", f);
    for (int k = 0; k < c->n_keys; ++k) {
        fprintf(f, ",%s", c->keys[k].name);
    }
    fputc('\n', f);
    static sim_campaign_run_t run; /* large: kept off the stack */
    char msg[128];
    for (long r = shard_k; r <= c->n_runs; r += shard_n) {
        if (sim_campaign_expand(c, r, &run, msg, sizeof msg) != 0) {
            return -1;
        }
        fprintf(f, "%ld", r);
        for (int k = 0; k < c->n_keys; ++k) {
            fprintf(f, ",%s", run.text[k]);
        }
        fputc('\n', f);
    }
    return ferror(f) ? -1 : 0;
}

int sim_campaign_parse_shard(const char *text, long *k, long *n, char *msg, size_t msg_len)
{
    const char *slash = strchr(text, '/');
    long v[2] = {0, 0};
    const char *parts[2] = {text, slash != NULL ? slash + 1 : NULL};
    const char *ends[2] = {slash, slash != NULL ? slash + 1 + strlen(slash + 1) : NULL};
    for (int i = 0; i < 2; ++i) {
        if (parts[i] == NULL || parts[i] == ends[i]) {
            snprintf(msg, msg_len, "expected K/N (shard K of N, 1 <= K <= N), got '%s'", text);
            return -1;
        }
        for (const char *s = parts[i]; s < ends[i]; ++s) {
            if (*s < '0' || *s > '9') {
                snprintf(msg, msg_len, "expected K/N with whole numbers K and N, got '%s'", text);
                return -1;
            }
            if (v[i] > SIM_CAMPAIGN_MAX_RUNS) {
                snprintf(msg, msg_len, "'%s': at most %ld shards", text, SIM_CAMPAIGN_MAX_RUNS);
                return -1;
            }
            v[i] = v[i] * 10 + (*s - '0');
        }
    }
    if (v[1] < 1 || v[1] > SIM_CAMPAIGN_MAX_RUNS) {
        snprintf(msg, msg_len, "'%s': N must be from 1 to %ld", text, SIM_CAMPAIGN_MAX_RUNS);
        return -1;
    }
    if (v[0] < 1 || v[0] > v[1]) {
        snprintf(msg, msg_len, "'%s': K must be from 1 to N = %ld", text, v[1]);
        return -1;
    }
    *k = v[0];
    *n = v[1];
    return 0;
}
