/*
 * unit_core.c -- the instance, state machine, variables and errors of every native unit, for
 * the FMI 2.0 and FMI 3.0 layers (unit_core.h).
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unit_core.h"

#define SET_STATES (ST_INSTANTIATED | ST_INITIALIZATION | ST_STEP_COMPLETE)

static void log_va(const Unit *u, int status, const char *category, const char *format,
                   va_list args)
{
    char message[FMU_MESSAGE_SIZE];
    int n;
    if (u->host.log == NULL) return;
    n = snprintf(message, sizeof message, "%s %s: ", u->m != NULL ? u->m->kind :
                 UNIT_MODELS[0]->kind, u->name != NULL ? u->name : "");
    if (n < 0 || (size_t)n >= sizeof message) n = 0;
    vsnprintf(message + n, sizeof message - (size_t)n, format, args);
    u->host.log(u, status, category, message);
}

void unit_log(const Unit *u, int status, const char *category, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    log_va(u, status, category, format, args);
    va_end(args);
}

#define LOG_CALL(u, ...)                                                                         \
    do {                                                                                         \
        if ((u)->logging_on && (u)->log_calls)                                                   \
            unit_log((u), UNIT_STATUS_OK, "logCalls", __VA_ARGS__);                              \
    } while (0)

/* An error that ends the instance's run: logged, state error. */
static int fail(Unit *u, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    log_va(u, UNIT_STATUS_ERROR, "logStatusError", format, args);
    va_end(args);
    u->state = ST_ERROR;
    return UNIT_STATUS_ERROR;
}

/* A call the instance refuses: logged, the state kept. */
static int refuse(Unit *u, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    log_va(u, UNIT_STATUS_ERROR, "logStatusError", format, args);
    va_end(args);
    return UNIT_STATUS_ERROR;
}

static const char *state_name(UnitState state)
{
    switch (state) {
    case ST_INSTANTIATED: return "instantiated";
    case ST_INITIALIZATION: return "initialization mode";
    case ST_STEP_COMPLETE: return "step complete";
    case ST_TERMINATED: return "terminated";
    default: return "error";
    }
}

static const char *type_name(UnitType type)
{
    return type == UNIT_REAL ? "Real" : type == UNIT_BOOLEAN ? "Boolean" : "String";
}

#define REQUIRE_STATE(u, function, mask)                                                         \
    do {                                                                                         \
        if (((u)->state & (mask)) == 0)                                                          \
            return refuse((u), "%s: not allowed in state %s", (function),                       \
                          state_name((u)->state));                                               \
    } while (0)

#define REQUIRE_ARRAYS(u, function, n, vr, values)                                               \
    do {                                                                                         \
        if ((n) > 0 && ((vr) == NULL || (values) == NULL))                                       \
            return refuse((u), "%s: null value-reference or value array", (function));         \
    } while (0)

/* The slot of the variable vr of this type; -1 with the reason logged. */
static long find_slot(Unit *u, const char *function, unsigned int vr, UnitType type)
{
    size_t i;
    if (vr < u->m->n_variables && u->m->variables[vr].vr == vr && /* the anvils' tables */
        u->m->variables[vr].type == type)
        return (long)vr;
    for (i = 0; i < u->m->n_variables; i++)
        if (u->m->variables[i].vr == vr) {
            if (u->m->variables[i].type == type) return (long)i;
            refuse(u, "%s: unknown value reference %u: it is %s, a %s variable", function, vr,
                   u->m->variables[i].name, type_name(u->m->variables[i].type));
            return -1;
        }
    refuse(u, "%s: unknown value reference %u", function, vr);
    return -1;
}

static void drop_unit(Unit *u)
{
    if (u->run != NULL) u->m->free_state(u->run);
    u->run = NULL;
    u->outputs_valid = 0;
}

/* The start values of the build; 0 when out of memory. */
static int apply_start_values(Unit *u)
{
    size_t i;
    drop_unit(u);
    for (i = 0; i < u->m->n_variables; i++) {
        const UnitVariable *v = &u->m->variables[i];
        double value = v->start;
        if (v->type == UNIT_STRING) {
            char *copy = fmu_copy_string(v->text != NULL ? v->text : "");
            if (copy == NULL) return 0;
            free(u->strings[i]);
            u->strings[i] = copy;
            continue;
        }
        if (v->causality == UNIT_PARAMETER) fmu_resource_start(&u->resource, v->name, &value);
        u->slots[i] = v->causality == UNIT_OUTPUT ? 0.0 : value;
    }
    return 1;
}

/* The unit's state from the current parameters (once per parameter set); 0 with the reason. */
static int build(Unit *u)
{
    if (u->run != NULL) return 1;
    u->reason[0] = '\0';
    u->run = u->m->start(u->model, u->slots, u->strings, u->start_time, u->reason,
                         sizeof u->reason);
    if (u->run == NULL) return 0;
    u->outputs_valid = 0;
    if (!u->m->feedthrough) {
        u->m->outputs(u->run, u->slots, u->time);
        u->outputs_valid = 1;
    }
    return 1;
}

/* The name of the first non-finite output, NULL when all are finite. */
static const char *non_finite_output(const Unit *u)
{
    size_t i;
    for (i = 0; i < u->m->n_variables; i++)
        if (u->m->variables[i].causality == UNIT_OUTPUT && !isfinite(u->slots[i]))
            return u->m->variables[i].name;
    return NULL;
}

void unit_free(Unit *u)
{
    size_t i;
    if (u == NULL) return;
    LOG_CALL(u, "free instance");
    if (u->m != NULL) {
        drop_unit(u);
        if (u->model != NULL) u->m->free_model(u->model);
        if (u->strings != NULL)
            for (i = 0; i < u->m->n_variables; i++) free(u->strings[i]);
    }
    fmu_resource_free(&u->resource);
    free(u->strings);
    free(u->slots);
    free(u->resources);
    free(u->name);
    free(u);
}

/* ------------------------------------------------------------------ life cycle */
static const UnitModel *model_of_kind(const char *kind)
{
    size_t i;
    for (i = 0; i < N_UNIT_MODELS; i++)
        if (strcmp(UNIT_MODELS[i]->kind, kind) == 0) return UNIT_MODELS[i];
    return NULL;
}

static Unit *refuse_instance(Unit *u, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    log_va(u, UNIT_STATUS_ERROR, "logStatusError", format, args);
    va_end(args);
    unit_free(u);
    return NULL;
}

Unit *unit_instantiate(const char *function, const char *name, const char *token_name,
                       const char *token, const char *resources, const UnitHost *host,
                       int logging_on)
{
    Unit *u;
    char *path;
    if (host == NULL) return NULL;
    u = (Unit *)calloc(1, sizeof *u);
    if (u == NULL) return NULL;
    u->host = *host;
    u->logging_on = u->log_calls = logging_on ? 1 : 0;
    u->name = fmu_copy_string(name != NULL ? name : "");
    u->resources = fmu_copy_string(resources != NULL ? resources : "");
    if (u->name == NULL || u->resources == NULL)
        return refuse_instance(u, "%s: out of memory", function);
    if (u->name[0] == '\0') return refuse_instance(u, "%s: the instance name is missing",
                                                   function);
    if (u->resources[0] == '\0')
        return refuse_instance(u, "%s: no resource location: this unit reads its model from "
                               "resources/%s", function, FMU_UNIT_RESOURCE);
    path = fmu_join(u->resources, FMU_UNIT_RESOURCE);
    if (path == NULL || !fmu_resource_read(path, &u->resource, u->reason, sizeof u->reason)) {
        free(path);
        return refuse_instance(u, "%s: %s", function, path == NULL ? "out of memory" :
                               u->reason);
    }
    free(path);
    u->m = model_of_kind(u->resource.kind);
    if (u->m == NULL)
        return refuse_instance(u, "%s: the resource is for a %s unit, this binary is the %s "
                               "unit%s", function, u->resource.kind, UNIT_MODELS[0]->kind,
                               N_UNIT_MODELS > 1 ? " (and its variants)" : "");
    if (token == NULL || strcmp(token, u->resource.guid) != 0)
        return refuse_instance(u, "%s: %s %s does not match the resource's %s "
                               "(modelDescription.xml and resources from different builds)",
                               function, token_name, token != NULL ? token : "(null)",
                               u->resource.guid);
    u->slots = (double *)calloc(u->m->n_variables, sizeof(double));
    u->strings = (char **)calloc(u->m->n_variables, sizeof(char *));
    if (u->slots == NULL || u->strings == NULL || !apply_start_values(u))
        return refuse_instance(u, "%s: out of memory", function);
    u->model = u->m->load(&u->resource, u->resources, u->reason, sizeof u->reason);
    if (u->model == NULL)
        return refuse_instance(u, "%s: resources/%s: %s", function, FMU_UNIT_RESOURCE,
                               u->reason);
    u->state = ST_INSTANTIATED;
    LOG_CALL(u, "%s(%s = %s, resources = %s)", function, token_name, token, u->resources);
    return u;
}

int unit_set_debug_logging(Unit *u, const char *function, int on, size_t n,
                           const char *const categories[])
{
    size_t i;
    if (u == NULL) return UNIT_STATUS_ERROR;
    if (n > 0 && categories == NULL) return refuse(u, "%s: null category array", function);
    for (i = 0; i < n; i++) {
        const char *name = categories[i] != NULL ? categories[i] : "(null)";
        if (strcmp(name, "logCalls") != 0 && strcmp(name, "logStatusError") != 0 &&
            strcmp(name, "logStatusWarning") != 0)
            return refuse(u, "%s: unknown log category \"%s\" (categories: logStatusError, "
                          "logStatusWarning, logCalls)", function, name);
    }
    u->logging_on = on ? 1 : 0;
    if (n == 0) u->log_calls = u->logging_on;
    for (i = 0; i < n; i++)
        if (strcmp(categories[i], "logCalls") == 0) u->log_calls = u->logging_on;
    return UNIT_STATUS_OK;
}

int unit_setup(Unit *u, const char *function, double start_time)
{
    if (u == NULL) return UNIT_STATUS_ERROR;
    LOG_CALL(u, "%s(startTime = %.17g)", function, start_time);
    REQUIRE_STATE(u, function, ST_INSTANTIATED);
    if (!isfinite(start_time))
        return refuse(u, "%s: the start time must be finite, got %g", function, start_time);
    u->start_time = u->time = start_time;
    drop_unit(u);
    return UNIT_STATUS_OK;
}

int unit_enter_initialization(Unit *u, const char *function)
{
    if (u == NULL) return UNIT_STATUS_ERROR;
    LOG_CALL(u, "%s", function);
    REQUIRE_STATE(u, function, ST_INSTANTIATED);
    u->state = ST_INITIALIZATION;
    return UNIT_STATUS_OK;
}

int unit_exit_initialization(Unit *u, const char *function)
{
    const char *bad;
    if (u == NULL) return UNIT_STATUS_ERROR;
    LOG_CALL(u, "%s", function);
    REQUIRE_STATE(u, function, ST_INITIALIZATION);
    if (!build(u)) return fail(u, "%s: %s", function, u->reason);
    if (u->outputs_valid && (bad = non_finite_output(u)) != NULL)
        return fail(u, "%s: output %s is not finite", function, bad);
    u->time = u->start_time;
    u->state = ST_STEP_COMPLETE;
    return UNIT_STATUS_OK;
}

int unit_terminate(Unit *u, const char *function)
{
    if (u == NULL) return UNIT_STATUS_ERROR;
    LOG_CALL(u, "%s", function);
    REQUIRE_STATE(u, function, ST_STEP_COMPLETE | ST_TERMINATED | ST_ERROR);
    u->state = ST_TERMINATED;
    return UNIT_STATUS_OK;
}

int unit_reset(Unit *u, const char *function)
{
    if (u == NULL) return UNIT_STATUS_ERROR;
    LOG_CALL(u, "%s", function);
    if (!apply_start_values(u)) return fail(u, "%s: out of memory", function);
    u->start_time = u->time = 0.0;
    u->state = ST_INSTANTIATED;
    return UNIT_STATUS_OK;
}

/* ------------------------------------------------------------------ variables */
/* The outputs from the current state and inputs (evaluated once per input set). */
static int evaluate_outputs(Unit *u, const char *function, const UnitVariable *v)
{
    const char *bad;
    if (u->state == ST_INSTANTIATED || (u->state == ST_ERROR && u->run == NULL) ||
        (u->run == NULL && u->state != ST_INITIALIZATION))
        return refuse(u, "%s: output %s not available in state %s", function, v->name,
                      state_name(u->state));
    if (u->run == NULL && !build(u)) return refuse(u, "%s: %s", function, u->reason);
    if (u->outputs_valid) return UNIT_STATUS_OK;
    u->m->outputs(u->run, u->slots, u->time);
    u->outputs_valid = 1;
    if ((bad = non_finite_output(u)) != NULL)
        return fail(u, "%s(t = %.9g s): output %s is not finite", function, u->time, bad);
    return UNIT_STATUS_OK;
}

int unit_get_real(Unit *u, const char *function, const unsigned int vr[], size_t n,
                  double values[], int with_time)
{
    size_t i;
    if (u == NULL) return UNIT_STATUS_ERROR;
    REQUIRE_ARRAYS(u, function, n, vr, values);
    for (i = 0; i < n; i++) {
        long slot;
        if (with_time && vr[i] == u->m->time_vr) {
            values[i] = u->time;
            continue;
        }
        if ((slot = find_slot(u, function, vr[i], UNIT_REAL)) < 0) return UNIT_STATUS_ERROR;
        if (u->m->variables[slot].causality == UNIT_OUTPUT &&
            evaluate_outputs(u, function, &u->m->variables[slot]) != UNIT_STATUS_OK)
            return UNIT_STATUS_ERROR;
        values[i] = u->slots[slot];
    }
    if (u->run != NULL && u->m->outputs_read != NULL) u->m->outputs_read(u->run);
    return UNIT_STATUS_OK;
}

/* May variable v be set now? A parameter of a new value drops the unit's state. */
static int settable(Unit *u, const char *function, const UnitVariable *v, int changes)
{
    REQUIRE_STATE(u, function, SET_STATES);
    if (v->causality == UNIT_OUTPUT)
        return refuse(u, "%s: %s is an output: it cannot be set", function, v->name);
    if (v->causality == UNIT_PARAMETER && u->state == ST_STEP_COMPLETE)
        return refuse(u, "%s: parameter %s is fixed after initialization", function, v->name);
    if (v->causality == UNIT_PARAMETER && changes) drop_unit(u);
    return UNIT_STATUS_OK;
}

int unit_set_real(Unit *u, const char *function, const unsigned int vr[], size_t n,
                  const double values[])
{
    size_t i;
    if (u == NULL) return UNIT_STATUS_ERROR;
    REQUIRE_STATE(u, function, SET_STATES);
    REQUIRE_ARRAYS(u, function, n, vr, values);
    for (i = 0; i < n; i++) {
        long slot = find_slot(u, function, vr[i], UNIT_REAL);
        const UnitVariable *v;
        if (slot < 0) return UNIT_STATUS_ERROR;
        v = &u->m->variables[slot];
        if (!isfinite(values[i]) && v->causality != UNIT_OUTPUT)
            return refuse(u, "%s: %s must be finite, got %g", function, v->name, values[i]);
        if (settable(u, function, v, u->slots[slot] != values[i]) != UNIT_STATUS_OK)
            return UNIT_STATUS_ERROR;
        if (v->causality == UNIT_PARAMETER) {
            LOG_CALL(u, "%s: %s = %.17g", function, v->name, values[i]);
        } else {
            if (u->run != NULL && u->m->inputs_set != NULL)
                u->m->inputs_set(u->run, u->slots, u->time);
            if (u->m->feedthrough) u->outputs_valid = 0;
        }
        u->slots[slot] = values[i];
    }
    return UNIT_STATUS_OK;
}

int unit_get_boolean(Unit *u, const char *function, const unsigned int vr[], size_t n,
                     int values[])
{
    size_t i;
    if (u == NULL) return UNIT_STATUS_ERROR;
    REQUIRE_ARRAYS(u, function, n, vr, values);
    for (i = 0; i < n; i++) {
        long slot = find_slot(u, function, vr[i], UNIT_BOOLEAN);
        if (slot < 0) return UNIT_STATUS_ERROR;
        values[i] = u->slots[slot] != 0.0;
    }
    return UNIT_STATUS_OK;
}

int unit_set_boolean(Unit *u, const char *function, const unsigned int vr[], size_t n,
                     const int values[])
{
    size_t i;
    if (u == NULL) return UNIT_STATUS_ERROR;
    REQUIRE_STATE(u, function, SET_STATES);
    REQUIRE_ARRAYS(u, function, n, vr, values);
    for (i = 0; i < n; i++) {
        long slot = find_slot(u, function, vr[i], UNIT_BOOLEAN);
        double number = values[i] ? 1.0 : 0.0;
        if (slot < 0 ||
            settable(u, function, &u->m->variables[slot], u->slots[slot] != number) !=
                UNIT_STATUS_OK)
            return UNIT_STATUS_ERROR;
        LOG_CALL(u, "%s: %s = %d", function, u->m->variables[slot].name, values[i] ? 1 : 0);
        u->slots[slot] = number;
    }
    return UNIT_STATUS_OK;
}

int unit_get_string(Unit *u, const char *function, const unsigned int vr[], size_t n,
                    const char *values[])
{
    size_t i;
    if (u == NULL) return UNIT_STATUS_ERROR;
    REQUIRE_ARRAYS(u, function, n, vr, values);
    for (i = 0; i < n; i++) {
        long slot = find_slot(u, function, vr[i], UNIT_STRING);
        if (slot < 0) return UNIT_STATUS_ERROR;
        values[i] = u->strings[slot];
    }
    return UNIT_STATUS_OK;
}

int unit_set_string(Unit *u, const char *function, const unsigned int vr[], size_t n,
                    const char *const values[])
{
    size_t i;
    if (u == NULL) return UNIT_STATUS_ERROR;
    REQUIRE_STATE(u, function, SET_STATES);
    REQUIRE_ARRAYS(u, function, n, vr, values);
    for (i = 0; i < n; i++) {
        long slot = find_slot(u, function, vr[i], UNIT_STRING);
        char *copy;
        if (slot < 0) return UNIT_STATUS_ERROR;
        if (values[i] == NULL)
            return refuse(u, "%s: %s: null string", function, u->m->variables[slot].name);
        if (settable(u, function, &u->m->variables[slot],
                     strcmp(u->strings[slot], values[i]) != 0) != UNIT_STATUS_OK)
            return UNIT_STATUS_ERROR;
        LOG_CALL(u, "%s: %s = %s", function, u->m->variables[slot].name, values[i]);
        if ((copy = fmu_copy_string(values[i])) == NULL)
            return fail(u, "%s: out of memory", function);
        free(u->strings[slot]);
        u->strings[slot] = copy;
    }
    return UNIT_STATUS_OK;
}

int unit_no_variables(Unit *u, const char *function, const char *type, size_t n)
{
    if (u == NULL) return UNIT_STATUS_ERROR;
    if (n == 0) return UNIT_STATUS_OK;
    return refuse(u, "%s: no %s variable (this FMU has none)", function, type);
}

/* ------------------------------------------------------------------ stepping */
int unit_do_step(Unit *u, const char *function, double t, double h)
{
    const char *bad;
    if (u == NULL) return UNIT_STATUS_ERROR;
    LOG_CALL(u, "%s(t = %.17g, h = %.17g)", function, t, h);
    if (u->state == ST_ERROR)
        return fail(u, "%s at t = %.9g s: the instance failed earlier (see the previous "
                    "error): reset or free it", function, t);
    REQUIRE_STATE(u, function, ST_STEP_COMPLETE);
    if (!isfinite(t))
        return fail(u, "%s: the communication point must be finite, got %g", function, t);
    if (!(isfinite(h) && h > 0.0))
        return fail(u, "%s at t = %.9g s: the communication step must be finite and "
                    "positive, got %g s", function, t, h);
    if (h > FMU_MAX_STEP)
        return fail(u, "%s at t = %.9g s: the communication step %g s is larger than %g s",
                    function, t, h, FMU_MAX_STEP);
    u->reason[0] = '\0';
    if (!u->m->step(u->run, u->slots, u->time, h, u->reason, sizeof u->reason))
        return fail(u, "%s at t = %.9g s: %s", function, t, u->reason);
    u->outputs_valid = 0;
    if (!u->m->feedthrough) {
        u->m->outputs(u->run, u->slots, t + h);
        u->outputs_valid = 1;
        if ((bad = non_finite_output(u)) != NULL)
            return fail(u, "%s(t = %g, h = %g): output %s is not finite after the step",
                        function, t, h, bad);
    }
    u->time = t + h;
    return UNIT_STATUS_OK;
}

int unit_unsupported(Unit *u, const char *function, const char *why)
{
    if (u == NULL) return UNIT_STATUS_ERROR;
    return refuse(u, "%s: not supported by this FMU%s%s", function, why[0] ? " " : "", why);
}
