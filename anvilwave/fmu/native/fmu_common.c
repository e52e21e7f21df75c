/*
 * fmu_common.c -- strings, logging, resource location and the text resource reader shared by
 * the native anvilwave FMUs (fmu_common.h).
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmu_common.h"

char *fmu_copy_string(const char *text)
{
    size_t n = strlen(text) + 1;
    char *copy = (char *)malloc(n);
    if (copy != NULL) memcpy(copy, text, n);
    return copy;
}

static int hex_digit(char c)
{
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

char *fmu_resource_folder(const char *uri)
{
    const char *p = uri;
    char *path;
    size_t n, i, j;
    if (p == NULL) return fmu_copy_string("");
    if (strncmp(p, "file://localhost/", 17) == 0)
        p += 16;
    else if (strncmp(p, "file:///", 8) == 0)
        p += 7;
    else if (strncmp(p, "file:/", 6) == 0)
        p += 5;
    else if (p[0] != '/')
        return fmu_copy_string(""); /* not a local file URI */
    /* "/C:/..." on Windows */
    if (p[0] == '/' && p[1] != '\0' && p[2] == ':') p += 1;
    n = strlen(p);
    path = (char *)malloc(n + 1);
    if (path == NULL) return NULL;
    for (i = 0, j = 0; i < n; i++) {
        if (p[i] == '%' && i + 2 < n && hex_digit(p[i + 1]) >= 0 &&
            hex_digit(p[i + 2]) >= 0) {
            path[j++] = (char)(hex_digit(p[i + 1]) * 16 + hex_digit(p[i + 2]));
            i += 2;
        } else {
            path[j++] = p[i];
        }
    }
    while (j > 1 && path[j - 1] == '/') j--;
    path[j] = '\0';
    return path;
}

int fmu_is_absolute(const char *path)
{
    return path[0] == '/' || path[0] == '\\' ||
           (path[0] != '\0' && path[1] == ':' && (path[2] == '/' || path[2] == '\\'));
}

char *fmu_join(const char *folder, const char *name)
{
    size_t n = strlen(folder) + strlen(name) + 2;
    char *path = (char *)malloc(n);
    if (path != NULL) snprintf(path, n, "%s/%s", folder, name);
    return path;
}

/* ------------------------------------------------------------------ text resource */
typedef struct {
    char *text;
    char *p;
} Tokens;

/* The next token (NUL-terminated in place), NULL at the end; # comments to the line end. */
static char *next_token(Tokens *t)
{
    char *start;
    for (;;) {
        while (*t->p != '\0' && isspace((unsigned char)*t->p)) t->p++;
        if (*t->p != '#') break;
        while (*t->p != '\0' && *t->p != '\n') t->p++;
    }
    if (*t->p == '\0') return NULL;
    start = t->p;
    while (*t->p != '\0' && !isspace((unsigned char)*t->p)) t->p++;
    if (*t->p != '\0') *t->p++ = '\0';
    return start;
}

/* A hexadecimal floating constant as Python's float.hex() writes it ([-]0xH.HHHp[+-]E), read
 * exactly without strtod (whose C runtime may not read the hexadecimal form). */
static int parse_hex_real(const char *p, double *value)
{
    double sign = 1.0, mantissa = 0.0;
    long exponent = 0, exponent_sign = 1;
    int fraction_digits = 0, digits = 0, d;
    if (*p == '-' || *p == '+') sign = *p++ == '-' ? -1.0 : 1.0;
    if (p[0] != '0' || (p[1] != 'x' && p[1] != 'X')) return 0;
    p += 2;
    while ((d = hex_digit(*p)) >= 0) {
        mantissa = mantissa * 16.0 + d; /* exact: at most 53 significant bits */
        p++;
        digits++;
    }
    if (*p == '.') {
        p++;
        while ((d = hex_digit(*p)) >= 0) {
            mantissa = mantissa * 16.0 + d;
            p++;
            digits++;
            fraction_digits++;
        }
    }
    if (digits == 0 || digits > 14 || (*p != 'p' && *p != 'P')) return 0;
    p++;
    if (*p == '-' || *p == '+') exponent_sign = *p++ == '-' ? -1 : 1;
    if (*p < '0' || *p > '9') return 0;
    while (*p >= '0' && *p <= '9') {
        exponent = exponent * 10 + (*p++ - '0');
        if (exponent > 100000) return 0;
    }
    if (*p != '\0') return 0;
    *value = sign * ldexp(mantissa, (int)(exponent_sign * exponent - 4 * fraction_digits));
    return isfinite(*value);
}

static int parse_real(const char *token, double *value)
{
    char *end;
    const char *p = token;
    if (token == NULL) return 0;
    if (*p == '-' || *p == '+') p++;
    if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X')) return parse_hex_real(token, value);
    errno = 0;
    *value = strtod(token, &end);
    return end != token && *end == '\0' && errno == 0 && isfinite(*value);
}

static char *read_all(const char *path, char *reason, size_t reason_size)
{
    FILE *file = fopen(path, "rb");
    char *text;
    long size;
    if (file == NULL) {
        snprintf(reason, reason_size, "cannot open %s", path);
        return NULL;
    }
    if (fseek(file, 0, SEEK_END) != 0 || (size = ftell(file)) < 0 ||
        fseek(file, 0, SEEK_SET) != 0) {
        fclose(file);
        snprintf(reason, reason_size, "cannot read %s", path);
        return NULL;
    }
    text = (char *)malloc((size_t)size + 1);
    if (text == NULL) {
        fclose(file);
        snprintf(reason, reason_size, "out of memory reading %s", path);
        return NULL;
    }
    if (fread(text, 1, (size_t)size, file) != (size_t)size) {
        fclose(file);
        free(text);
        snprintf(reason, reason_size, "cannot read %s", path);
        return NULL;
    }
    fclose(file);
    text[size] = '\0';
    return text;
}

void fmu_resource_free(FmuResource *res)
{
    size_t i;
    for (i = 0; i < res->n_starts; i++) free(res->start_names[i]);
    free(res->start_names);
    free(res->start_values);
    for (i = 0; i < res->n_arrays; i++) {
        free(res->arrays[i].name);
        free(res->arrays[i].values);
    }
    free(res->arrays);
    memset(res, 0, sizeof *res);
}

#define PARSE_FAIL(...)                                                                          \
    do {                                                                                         \
        snprintf(reason, reason_size, __VA_ARGS__);                                              \
        goto fail;                                                                               \
    } while (0)

int fmu_resource_read(const char *path, FmuResource *res, char *reason, size_t reason_size)
{
    Tokens t;
    char *token, *name, *text;
    double value;
    int ended = 0;
    memset(res, 0, sizeof *res);
    text = read_all(path, reason, reason_size);
    if (text == NULL) return 0;
    t.text = t.p = text;
    token = next_token(&t);
    if (token == NULL || strcmp(token, FMU_UNIT_MAGIC) != 0)
        PARSE_FAIL("%s: not an %s resource", path, FMU_UNIT_MAGIC);
    token = next_token(&t);
    if (token == NULL || strtol(token, NULL, 10) != FMU_UNIT_VERSION)
        PARSE_FAIL("%s: format version %s, this binary reads version %d", path,
                   token != NULL ? token : "(missing)", FMU_UNIT_VERSION);
    while ((token = next_token(&t)) != NULL) {
        if (strcmp(token, "end") == 0) {
            ended = 1;
            break;
        } else if (strcmp(token, "kind") == 0 || strcmp(token, "guid") == 0) {
            char *field = token[0] == 'k' ? res->kind : res->guid;
            size_t size = token[0] == 'k' ? sizeof res->kind : sizeof res->guid;
            name = next_token(&t);
            if (name == NULL || strlen(name) >= size) PARSE_FAIL("%s: bad %s", path, token);
            strcpy(field, name);
        } else if (strcmp(token, "start") == 0) {
            char **names;
            double *values;
            name = next_token(&t);
            if (name == NULL || !parse_real(next_token(&t), &value))
                PARSE_FAIL("%s: start %s: a finite Real expected", path,
                           name != NULL ? name : "(missing)");
            names = (char **)realloc(res->start_names, (res->n_starts + 1) * sizeof *names);
            if (names == NULL) PARSE_FAIL("out of memory");
            res->start_names = names;
            values = (double *)realloc(res->start_values, (res->n_starts + 1) * sizeof *values);
            if (values == NULL) PARSE_FAIL("out of memory");
            res->start_values = values;
            if ((names[res->n_starts] = fmu_copy_string(name)) == NULL)
                PARSE_FAIL("out of memory");
            values[res->n_starts++] = value;
        } else if (strcmp(token, "array") == 0) {
            FmuArray *arrays, *a;
            char *count;
            long n;
            size_t i;
            name = next_token(&t);
            count = next_token(&t);
            n = count != NULL ? strtol(count, NULL, 10) : -1;
            if (name == NULL || n < 0 || n > 100000000L)
                PARSE_FAIL("%s: array %s: bad size", path, name != NULL ? name : "(missing)");
            arrays = (FmuArray *)realloc(res->arrays, (res->n_arrays + 1) * sizeof *arrays);
            if (arrays == NULL) PARSE_FAIL("out of memory");
            res->arrays = arrays;
            a = &arrays[res->n_arrays];
            a->size = (size_t)n;
            a->name = fmu_copy_string(name);
            a->values = (double *)malloc((a->size > 0 ? a->size : 1) * sizeof(double));
            res->n_arrays++;
            if (a->name == NULL || a->values == NULL) PARSE_FAIL("out of memory");
            for (i = 0; i < a->size; i++)
                if (!parse_real(next_token(&t), &a->values[i]))
                    PARSE_FAIL("%s: array %s: entry %lu is not a finite Real", path, name,
                               (unsigned long)i);
        } else {
            PARSE_FAIL("%s: unknown entry %s", path, token);
        }
    }
    if (!ended) PARSE_FAIL("%s: truncated (no end)", path);
    if (res->kind[0] == '\0' || res->guid[0] == '\0')
        PARSE_FAIL("%s: kind or guid missing", path);
    free(text);
    return 1;
fail:
    free(text);
    fmu_resource_free(res);
    return 0;
}

const double *fmu_resource_array(const FmuResource *res, const char *name, size_t *size)
{
    size_t i;
    for (i = 0; i < res->n_arrays; i++)
        if (strcmp(res->arrays[i].name, name) == 0) {
            *size = res->arrays[i].size;
            return res->arrays[i].values;
        }
    *size = 0;
    return NULL;
}

int fmu_resource_start(const FmuResource *res, const char *name, double *value)
{
    size_t i;
    for (i = 0; i < res->n_starts; i++)
        if (strcmp(res->start_names[i], name) == 0) {
            *value = res->start_values[i];
            return 1;
        }
    return 0;
}
