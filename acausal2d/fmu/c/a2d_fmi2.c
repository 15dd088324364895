/* FMI 2.0 interface of an acausal2d FMU (Model Exchange and Co-Simulation)
 * around the core in a2d_core.c; the Co-Simulation integrator is a2d_cs.c. */
#include <stdlib.h>
#include <string.h>
#include <stdio.h>

#include "fmi2Functions.h"
#include "a2d_core.h"
#include "a2d_cs.h"

enum { INSTANTIATED, INITIALIZATION, EVENT, CONTINUOUS, STEPPING, TERMINATED };

typedef struct {
    a2d_core core;
    a2d_cs cs;
    fmi2CallbackFunctions cb;
    char name[128];
    fmi2Type kind;
    int mode;
    int logging;
    int initialized;          /* consistent values for the current parameters */
} a2d_instance;

static int ensure_initialized(a2d_instance* m)
{
    if (m->initialized) return 0;
    if (a2d_initialize(&m->core)) return -1;
    m->initialized = 1;
    return 0;
}

static fmi2Status fail(a2d_instance* m, const char* what)
{
    if (m->cb.logger)
        m->cb.logger(m->cb.componentEnvironment, m->name, fmi2Error, "error", "%s: %s", what,
                     m->core.message[0] ? m->core.message : "failed");
    return fmi2Error;
}

const char* fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char* fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean on, size_t n, const fmi2String cats[])
{
    (void)n; (void)cats;
    ((a2d_instance*)c)->logging = on;
    return fmi2OK;
}

fmi2Component fmi2Instantiate(fmi2String name, fmi2Type kind, fmi2String guid,
                              fmi2String location, const fmi2CallbackFunctions* cb,
                              fmi2Boolean visible, fmi2Boolean logging)
{
    a2d_instance* m;
    (void)location; (void)visible;
    if (!guid || strcmp(guid, A2D_GUID) != 0) {
        if (cb && cb->logger)
            cb->logger(cb->componentEnvironment, name, fmi2Error, "error",
                       "GUID %s does not match this binary (%s)", guid ? guid : "", A2D_GUID);
        return NULL;
    }
    m = (a2d_instance*)calloc(1, sizeof(a2d_instance));
    if (!m) return NULL;
    if (cb) m->cb = *cb;
    strncpy(m->name, name ? name : "acausal2d", sizeof(m->name) - 1);
    m->kind = kind;
    m->logging = logging;
    memcpy(m->core.p, a2d_p0, sizeof(double) * A2D_NP);
    a2d_update_offsets(&m->core);
    m->core.dirty = 1;
    m->mode = INSTANTIATED;
    return m;
}

void fmi2FreeInstance(fmi2Component c) { free(c); }

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean tolDefined, fmi2Real tol,
                               fmi2Real start, fmi2Boolean stopDefined, fmi2Real stop)
{
    a2d_instance* m = (a2d_instance*)c;
    (void)stopDefined; (void)stop;
    m->core.t = start;
    a2d_cs_setup(&m->cs, tolDefined ? tol : 0.0);
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    ((a2d_instance*)c)->mode = INITIALIZATION;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    a2d_instance* m = (a2d_instance*)c;
    if (ensure_initialized(m)) return fail(m, "initialization");
    m->mode = m->kind == fmi2CoSimulation ? STEPPING : EVENT;
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c) { ((a2d_instance*)c)->mode = TERMINATED; return fmi2OK; }

fmi2Status fmi2Reset(fmi2Component c)
{
    a2d_instance* m = (a2d_instance*)c;
    memcpy(m->core.p, a2d_p0, sizeof(double) * A2D_NP);
    a2d_update_offsets(&m->core);
    m->core.dirty = 1;
    m->initialized = 0;
    m->mode = INSTANTIATED;
    return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Real v[])
{
    a2d_instance* m = (a2d_instance*)c;
    size_t i;
    if (m->mode == INITIALIZATION && ensure_initialized(m)) return fail(m, "initialization");
    if (m->mode != INSTANTIATED && m->mode != INITIALIZATION && a2d_solve_states(&m->core))
        return fail(m, "fmi2GetReal");
    for (i = 0; i < n; i++) v[i] = a2d_value(&m->core, vr[i]);
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Real v[])
{
    a2d_instance* m = (a2d_instance*)c;
    size_t i;
    for (i = 0; i < n; i++) {
        if (vr[i] >= A2D_NP) {
            snprintf(m->core.message, sizeof(m->core.message), "value reference %u is not a "
                     "parameter or input (only those can be set)", (unsigned)vr[i]);
            return fail(m, "fmi2SetReal");
        }
        if (a2d_is_structural[vr[i]]) {
            snprintf(m->core.message, sizeof(m->core.message), "%s was read when the model was "
                     "compiled (it decides the model's structure): it is a constant of this "
                     "FMU; export the model again with the value wanted",
                     a2d_parameter_name[vr[i]]);
            return fail(m, "fmi2SetReal");
        }
        if (!a2d_is_input[vr[i]] && m->mode != INSTANTIATED && m->mode != INITIALIZATION) {
            snprintf(m->core.message, sizeof(m->core.message), "parameter %u is fixed: set it "
                     "before initialization", (unsigned)vr[i]);
            return fail(m, "fmi2SetReal");
        }
        m->core.p[vr[i]] = v[i];
        if (!a2d_is_input[vr[i]]) m->initialized = 0;
    }
    a2d_update_offsets(&m->core);
    m->core.dirty = 1;
    return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Integer v[])
{ (void)c; (void)vr; (void)v; return n ? fmi2Error : fmi2OK; }
fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Boolean v[])
{ (void)c; (void)vr; (void)v; return n ? fmi2Error : fmi2OK; }
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2String v[])
{ (void)c; (void)vr; (void)v; return n ? fmi2Error : fmi2OK; }
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Integer v[])
{ (void)c; (void)vr; (void)v; return n ? fmi2Error : fmi2OK; }
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Boolean v[])
{ (void)c; (void)vr; (void)v; return n ? fmi2Error : fmi2OK; }
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2String v[])
{ (void)c; (void)vr; (void)v; return n ? fmi2Error : fmi2OK; }

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate* s) { (void)c; (void)s; return fmi2Error; }
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate s) { (void)c; (void)s; return fmi2Error; }
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate* s) { (void)c; (void)s; return fmi2Error; }
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate s, size_t* n)
{ (void)c; (void)s; (void)n; return fmi2Error; }
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate s, fmi2Byte b[], size_t n)
{ (void)c; (void)s; (void)b; (void)n; return fmi2Error; }
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte b[], size_t n, fmi2FMUstate* s)
{ (void)c; (void)b; (void)n; (void)s; return fmi2Error; }
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference u[], size_t nu,
                                        const fmi2ValueReference k[], size_t nk,
                                        const fmi2Real dv[], fmi2Real dz[])
{ (void)c; (void)u; (void)nu; (void)k; (void)nk; (void)dv; (void)dz; return fmi2Error; }

/* ------------------------------------------------------------ Model Exchange */
fmi2Status fmi2EnterEventMode(fmi2Component c) { ((a2d_instance*)c)->mode = EVENT; return fmi2OK; }

fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo* info)
{
    a2d_instance* m = (a2d_instance*)c;
    int changed = 0;
    double next;
    if (a2d_event_iteration(&m->core, &changed)) return fail(m, "event iteration");
    next = a2d_next_time_event(&m->core, m->core.t);
    info->newDiscreteStatesNeeded = fmi2False;
    info->terminateSimulation = fmi2False;
    info->nominalsOfContinuousStatesChanged = fmi2False;
    info->valuesOfContinuousStatesChanged = fmi2False;
    info->nextEventTimeDefined = next >= 0 ? fmi2True : fmi2False;
    info->nextEventTime = next >= 0 ? next : 0.0;
    return fmi2OK;
}

fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c)
{
    ((a2d_instance*)c)->mode = CONTINUOUS;
    return fmi2OK;
}

fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean noSet, fmi2Boolean* enter,
                                       fmi2Boolean* terminate)
{
    a2d_instance* m = (a2d_instance*)c;
    (void)noSet;
    *enter = fmi2False;
    *terminate = fmi2False;
    if (a2d_check_passage(&m->core)) return fail(m, "fmi2CompletedIntegratorStep");
    return fmi2OK;
}

fmi2Status fmi2SetTime(fmi2Component c, fmi2Real t)
{
    a2d_instance* m = (a2d_instance*)c;
    m->core.t = t;
    m->core.dirty = 1;
    return fmi2OK;
}

fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t n)
{
    a2d_instance* m = (a2d_instance*)c;
    if (n != A2D_NX) return fmi2Error;
    memcpy(m->core.x, x, sizeof(double) * n);
    m->core.dirty = 1;
    return fmi2OK;
}

fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real der[], size_t n)
{
    a2d_instance* m = (a2d_instance*)c;
    size_t k;
    if (n != A2D_NX) return fmi2Error;
    if (a2d_solve_states(&m->core)) return fail(m, "fmi2GetDerivatives");
    for (k = 0; k < n; k++) der[k] = m->core.z[a2d_diff[a2d_states[k]]];
    return fmi2OK;
}

fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real g[], size_t n)
{
    a2d_instance* m = (a2d_instance*)c;
    if (n != A2D_NREL) return fmi2Error;
    if (n == 0) return fmi2OK;
    if (m->mode != INSTANTIATED && m->mode != INITIALIZATION && a2d_solve_states(&m->core))
        return fail(m, "fmi2GetEventIndicators");
    a2d_crossings(&m->core, m->core.t, m->core.z, g);
    return fmi2OK;
}

fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t n)
{
    a2d_instance* m = (a2d_instance*)c;
    if (n != A2D_NX) return fmi2Error;
    memcpy(x, m->core.x, sizeof(double) * n);
    return fmi2OK;
}

fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real x[], size_t n)
{
    size_t k;
    (void)c;
    for (k = 0; k < n; k++) x[k] = a2d_nominal_x[k];
    return fmi2OK;
}

/* ------------------------------------------------------------ Co-Simulation */
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                       const fmi2Integer order[], const fmi2Real v[])
{ (void)c; (void)vr; (void)order; (void)v; return n ? fmi2Error : fmi2OK; }
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                        const fmi2Integer order[], fmi2Real v[])
{ (void)c; (void)vr; (void)order; (void)v; return n ? fmi2Error : fmi2OK; }

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean noSetPrior)
{
    a2d_instance* m = (a2d_instance*)c;
    (void)noSetPrior;
    m->core.t = t;
    if (a2d_cs_advance(&m->cs, &m->core, t + h)) return fail(m, "fmi2DoStep");
    return fmi2OK;
}

fmi2Status fmi2CancelStep(fmi2Component c) { (void)c; return fmi2Error; }

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status* v)
{ (void)c; (void)s; (void)v; return fmi2Discard; }
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* v)
{
    a2d_instance* m = (a2d_instance*)c;
    if (s != fmi2LastSuccessfulTime) return fmi2Discard;
    *v = m->core.t;
    return fmi2OK;
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer* v)
{ (void)c; (void)s; (void)v; return fmi2Discard; }
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* v)
{ (void)c; (void)s; (void)v; return fmi2Discard; }
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String* v)
{ (void)c; (void)s; (void)v; return fmi2Discard; }
