/* A tiny FMI 2.0 Model Exchange importer without Python: loads the binary
 * given as argv[1] (GUID argv[2]), initializes, integrates with classical
 * Runge-Kutta (fixed step argv[4]) to argv[3] s without events and prints
 * "t value" of the variable with value reference argv[5]. */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdarg.h>
#include "fmi2Functions.h"

static void logger(fmi2ComponentEnvironment e, fmi2String n, fmi2Status s, fmi2String c,
                   fmi2String m, ...)
{
    va_list ap;
    (void)e; (void)s; (void)c;
    va_start(ap, m);
    fprintf(stderr, "%s: ", n);
    vfprintf(stderr, m, ap);
    fprintf(stderr, "\n");
    va_end(ap);
}

#define GET(name) fmi2##name##TYPE* name = (fmi2##name##TYPE*)dlsym(lib, "fmi2" #name); \
    if (!name) { fprintf(stderr, "missing fmi2" #name "\n"); return 2; }

int main(int argc, char** argv)
{
    void* lib;
    fmi2CallbackFunctions cb = {logger, calloc, free, NULL, NULL};
    fmi2Component c;
    fmi2EventInfo info;
    double t = 0, x[64], k[4][64], xs[64], stop, h, v;
    size_t nx, i, s;
    fmi2ValueReference vr;
    fmi2Boolean enter, term;
    if (argc < 7) return 2;
    lib = dlopen(argv[1], RTLD_NOW);
    if (!lib) { fprintf(stderr, "%s\n", dlerror()); return 2; }
    GET(Instantiate) GET(SetupExperiment) GET(EnterInitializationMode)
    GET(ExitInitializationMode) GET(NewDiscreteStates) GET(EnterContinuousTimeMode)
    GET(GetContinuousStates) GET(SetContinuousStates) GET(GetDerivatives) GET(SetTime)
    GET(GetReal) GET(CompletedIntegratorStep) GET(FreeInstance)
    stop = atof(argv[3]); h = atof(argv[4]); vr = (fmi2ValueReference)atoi(argv[5]);
    nx = (size_t)atoi(argv[6]);
    c = Instantiate("driver", fmi2ModelExchange, argv[2], "", &cb, fmi2False, fmi2False);
    if (!c) return 3;
    if (SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0) || EnterInitializationMode(c)
        || ExitInitializationMode(c) || NewDiscreteStates(c, &info)
        || EnterContinuousTimeMode(c) || GetContinuousStates(c, x, nx)) return 3;
    while (t < stop - 1e-12) {
        for (s = 0; s < 4; s++) {
            double a = s == 0 ? 0 : (s == 3 ? 1.0 : 0.5);
            for (i = 0; i < nx; i++) xs[i] = x[i] + (s ? a * h * k[s - 1][i] : 0.0);
            SetTime(c, t + a * h);
            SetContinuousStates(c, xs, nx);
            if (GetDerivatives(c, k[s], nx)) return 3;
        }
        for (i = 0; i < nx; i++) x[i] += h / 6 * (k[0][i] + 2 * k[1][i] + 2 * k[2][i] + k[3][i]);
        t += h;
        SetTime(c, t);
        SetContinuousStates(c, x, nx);
        CompletedIntegratorStep(c, fmi2True, &enter, &term);
    }
    if (GetReal(c, &vr, 1, &v)) return 3;
    printf("%.17g %.17g\n", t, v);
    FreeInstance(c);
    return 0;
}
