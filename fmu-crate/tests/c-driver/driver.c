/* A plain-C FMI 2.0 or FMI 3.0 importer of the ecf_contact binary: the same program runs the
 * x86_64 Linux .so natively, the Windows .dll under Wine and the aarch64 Linux .so under
 * qemu-user (tests-py/test_platforms.py), and their outputs are compared line by line; the
 * FMI 2.0 and FMI 3.0 builds of it are compared with each other too.
 *
 * Built with -DECF_FMI3 it drives the FMI 3.0 API (fmi3* functions, the resources folder as a
 * path, not a URI) and prints, at the end of each scenario, the field arrays (n_field points
 * each) beside the outputs. It loads the shared library by path, resolves the functions of its
 * API by name, and runs, with
 * the FMU's own exported functions only (no fmpy, no Rust):
 *   run RES_URI                 scenarios: several presets, 0.1 and 1 ms steps, the threads and
 *                               scheme parameters, a relative config_file resolved against the
 *                               resources URI, a bad input whose message must reach the logger,
 *                               get/set/free state and serialize/deserialize round trips
 *   save RES_URI FILE           runs 20 steps, writes the serialized FMU state to FILE, then
 *                               prints 20 more steps
 *   load RES_URI FILE           instantiates and initializes like `save`, deserializes FILE, sets
 *                               the state and prints the 20 steps that follow (they must equal
 *                               those `save` printed, on either platform)
 * Every number is printed with %.17g (round-trip exact). Exit code 0 when every call returned
 * what the scenario expects, 1 otherwise (the failing call is printed on stderr).
 *
 * Build: gcc -O1 -o driver driver.c -ldl      (Linux; add -DECF_FMI3 for FMI 3.0)
 *        x86_64-w64-mingw32-gcc -O1 -o driver.exe driver.c   (Windows)
 *        aarch64-linux-gnu-gcc -O1 -o driver-arm64 driver.c -ldl   (ARM64 Linux, run by qemu-aarch64)
 * The FMI 2.0 and 3.0 types and signatures below are those of the standard's headers
 * (fmi2TypesPlatform.h, fmi2FunctionTypes.h, fmi3PlatformTypes.h, fmi3FunctionTypes.h), the
 * few this driver calls, kept here so that it needs no header path.
 */
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _WIN32
#include <fcntl.h>
#include <io.h>
#include <windows.h>
#define LIB_T HMODULE
#define LIB_OPEN(p) LoadLibraryA(p)
#define LIB_SYM(h, n) ((void *)GetProcAddress((h), (n)))
#else
#include <dlfcn.h>
#define LIB_T void *
#define LIB_OPEN(p) dlopen((p), RTLD_NOW | RTLD_LOCAL)
#define LIB_SYM(h, n) dlsym((h), (n))
#endif

typedef void *fmi2Component;
typedef void *fmi2ComponentEnvironment;
typedef void *fmi2FMUstate;
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef const char *fmi2String;
typedef char fmi2Byte;
typedef enum { fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal, fmi2Pending } fmi2Status;
typedef enum { fmi2ModelExchange, fmi2CoSimulation } fmi2Type;
typedef void (*fmi2CallbackLogger)(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...);
typedef void *(*fmi2CallbackAllocateMemory)(size_t, size_t);
typedef void (*fmi2CallbackFreeMemory)(void *);
typedef void (*fmi2StepFinished)(fmi2ComponentEnvironment, fmi2Status);
typedef struct {
    fmi2CallbackLogger logger;
    fmi2CallbackAllocateMemory allocateMemory;
    fmi2CallbackFreeMemory freeMemory;
    fmi2StepFinished stepFinished;
    fmi2ComponentEnvironment componentEnvironment;
} fmi2CallbackFunctions;

typedef fmi2Component (*Instantiate_t)(fmi2String, fmi2Type, fmi2String, fmi2String, const fmi2CallbackFunctions *, fmi2Boolean, fmi2Boolean);
typedef void (*FreeInstance_t)(fmi2Component);
typedef fmi2Status (*SetupExperiment_t)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean, fmi2Real);
typedef fmi2Status (*Comp_t)(fmi2Component);
typedef fmi2Status (*SetReal_t)(fmi2Component, const fmi2ValueReference *, size_t, const fmi2Real *);
typedef fmi2Status (*GetReal_t)(fmi2Component, const fmi2ValueReference *, size_t, fmi2Real *);
typedef fmi2Status (*SetInteger_t)(fmi2Component, const fmi2ValueReference *, size_t, const fmi2Integer *);
typedef fmi2Status (*SetString_t)(fmi2Component, const fmi2ValueReference *, size_t, const fmi2String *);
typedef fmi2Status (*DoStep_t)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean);
typedef fmi2Status (*GetState_t)(fmi2Component, fmi2FMUstate *);
typedef fmi2Status (*SetState_t)(fmi2Component, fmi2FMUstate);
typedef fmi2Status (*FreeState_t)(fmi2Component, fmi2FMUstate *);
typedef fmi2Status (*StateSize_t)(fmi2Component, fmi2FMUstate, size_t *);
typedef fmi2Status (*Serialize_t)(fmi2Component, fmi2FMUstate, fmi2Byte *, size_t);
typedef fmi2Status (*Deserialize_t)(fmi2Component, const fmi2Byte *, size_t, fmi2FMUstate *);
typedef const char *(*Version_t)(void);

/* FMI 3.0: the functions whose signatures differ from FMI 2.0's */
typedef void *fmi3InstanceEnvironment;
typedef void (*fmi3LogMessageCallback)(fmi3InstanceEnvironment, int, const char *, const char *);
typedef void *(*Instantiate3_t)(const char *, const char *, const char *, bool, bool, bool, bool, const unsigned int *, size_t,
                                fmi3InstanceEnvironment, fmi3LogMessageCallback, void *);
typedef fmi2Status (*EnterInit3_t)(fmi2Component, bool, double, double, bool, double);
typedef fmi2Status (*SetFloat64_t)(fmi2Component, const fmi2ValueReference *, size_t, const double *, size_t);
typedef fmi2Status (*GetFloat64_t)(fmi2Component, const fmi2ValueReference *, size_t, double *, size_t);
typedef fmi2Status (*SetInt32_t)(fmi2Component, const fmi2ValueReference *, size_t, const int32_t *, size_t);
typedef fmi2Status (*GetInt32_t)(fmi2Component, const fmi2ValueReference *, size_t, int32_t *, size_t);
typedef fmi2Status (*SetString3_t)(fmi2Component, const fmi2ValueReference *, size_t, const char *const *, size_t);
typedef fmi2Status (*DoStep3_t)(fmi2Component, double, double, bool, bool *, bool *, bool *, double *);

static struct {
    Instantiate_t instantiate;
    Instantiate3_t instantiate3;
    EnterInit3_t enter_init3;
    SetFloat64_t set_float64;
    GetFloat64_t get_float64;
    SetInt32_t set_int32;
    GetInt32_t get_int32;
    SetString3_t set_string3;
    DoStep3_t do_step3;
    FreeInstance_t free_instance;
    SetupExperiment_t setup;
    Comp_t enter_init, exit_init, terminate;
    SetReal_t set_real;
    GetReal_t get_real;
    SetInteger_t set_integer;
    SetString_t set_string;
    DoStep_t do_step;
    GetState_t get_state;
    SetState_t set_state;
    FreeState_t free_state;
    StateSize_t state_size;
    Serialize_t serialize;
    Deserialize_t deserialize;
    Version_t version;
} F;

/* value references of modelDescription.xml */
enum { VR_CX = 1, VR_V = 4, VR_FN = 5, VR_TBULK = 6, VR_THREADS = 43, VR_SCHEME = 44, VR_PRESET = 61, VR_CONFIG = 62 };
static const fmi2ValueReference OUT_VR[] = {10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22};
static const char *OUT_NAME[] = {"Fx", "Fy", "Mz", "f", "T_max", "T_mean", "P_fric", "frac_elastic", "frac_plastic", "frac_sliding", "a", "b", "p0"};
#define N_OUT (sizeof OUT_VR / sizeof OUT_VR[0])
/* the field arrays of the FMI 3.0 FMU (n_field points each) and n_field's start value */
enum { VR_FIELD_X = 201, VR_FIELD_REGIME = 206, N_FIELD = 80 };
#ifdef ECF_FMI3
static const char *FIELD_NAME[] = {"field_x", "field_p", "field_tau_x", "field_tau_c2", "field_T"};
#endif
static const char *FMU_GUID = "";
static int failures = 0;

/* The last message the FMU logged with status Error, for the bad-input check. */
static char last_error[2048];
static int n_logged_errors = 0;

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status st, fmi2String cat, fmi2String msg, ...) {
    char buf[2048];
    va_list ap;
    (void)env;
    va_start(ap, msg);
    vsnprintf(buf, sizeof buf, msg ? msg : "(null)", ap);
    va_end(ap);
    if (st >= fmi2Error) {
        snprintf(last_error, sizeof last_error, "%s", buf);
        n_logged_errors++;
    }
    /* the messages go to stderr: they may name paths, which differ between the platforms */
    fprintf(stderr, "[log %s %d %s] %s\n", name ? name : "?", (int)st, cat ? cat : "?", buf);
}

#ifdef ECF_FMI3
static void logger3(fmi3InstanceEnvironment env, int st, const char *cat, const char *msg) {
    logger(env, "fmi3", (fmi2Status)st, cat, "%s", msg ? msg : "(null)");
}
#endif

#ifndef ECF_FMI3
static void *alloc_mem(size_t n, size_t size) { return calloc(n, size); }

static const fmi2CallbackFunctions CALLBACKS = {logger, alloc_mem, free, NULL, NULL};
#endif

#define CHECK(call, want)                                                                      \
    do {                                                                                       \
        fmi2Status st_ = (call);                                                               \
        if (st_ != (want)) {                                                                   \
            fprintf(stderr, "FAIL line %d: %s returned %d, expected %d\n", __LINE__, #call,     \
                    (int)st_, (int)(want));                                                    \
            failures++;                                                                        \
        }                                                                                      \
    } while (0)

static void *sym(LIB_T lib, const char *name) {
    void *p = LIB_SYM(lib, name);
    if (!p) {
        fprintf(stderr, "the library does not export %s\n", name);
        exit(2);
    }
    return p;
}

static void load(const char *path) {
    LIB_T lib = LIB_OPEN(path);
    if (!lib) {
#ifdef _WIN32
        fprintf(stderr, "cannot load %s (error %lu)\n", path, (unsigned long)GetLastError());
#else
        fprintf(stderr, "cannot load %s: %s\n", path, dlerror());
#endif
        exit(2);
    }
#ifdef ECF_FMI3
    F.instantiate3 = (Instantiate3_t)sym(lib, "fmi3InstantiateCoSimulation");
    F.free_instance = (FreeInstance_t)sym(lib, "fmi3FreeInstance");
    F.enter_init3 = (EnterInit3_t)sym(lib, "fmi3EnterInitializationMode");
    F.exit_init = (Comp_t)sym(lib, "fmi3ExitInitializationMode");
    F.terminate = (Comp_t)sym(lib, "fmi3Terminate");
    F.set_float64 = (SetFloat64_t)sym(lib, "fmi3SetFloat64");
    F.get_float64 = (GetFloat64_t)sym(lib, "fmi3GetFloat64");
    F.set_int32 = (SetInt32_t)sym(lib, "fmi3SetInt32");
    F.get_int32 = (GetInt32_t)sym(lib, "fmi3GetInt32");
    F.set_string3 = (SetString3_t)sym(lib, "fmi3SetString");
    F.do_step3 = (DoStep3_t)sym(lib, "fmi3DoStep");
    F.get_state = (GetState_t)sym(lib, "fmi3GetFMUState");
    F.set_state = (SetState_t)sym(lib, "fmi3SetFMUState");
    F.free_state = (FreeState_t)sym(lib, "fmi3FreeFMUState");
    F.state_size = (StateSize_t)sym(lib, "fmi3SerializedFMUStateSize");
    F.serialize = (Serialize_t)sym(lib, "fmi3SerializeFMUState");
    F.deserialize = (Deserialize_t)sym(lib, "fmi3DeserializeFMUState");
    F.version = (Version_t)sym(lib, "fmi3GetVersion");
#else
    F.instantiate = (Instantiate_t)sym(lib, "fmi2Instantiate");
    F.free_instance = (FreeInstance_t)sym(lib, "fmi2FreeInstance");
    F.setup = (SetupExperiment_t)sym(lib, "fmi2SetupExperiment");
    F.enter_init = (Comp_t)sym(lib, "fmi2EnterInitializationMode");
    F.exit_init = (Comp_t)sym(lib, "fmi2ExitInitializationMode");
    F.terminate = (Comp_t)sym(lib, "fmi2Terminate");
    F.set_real = (SetReal_t)sym(lib, "fmi2SetReal");
    F.get_real = (GetReal_t)sym(lib, "fmi2GetReal");
    F.set_integer = (SetInteger_t)sym(lib, "fmi2SetInteger");
    F.set_string = (SetString_t)sym(lib, "fmi2SetString");
    F.do_step = (DoStep_t)sym(lib, "fmi2DoStep");
    F.get_state = (GetState_t)sym(lib, "fmi2GetFMUstate");
    F.set_state = (SetState_t)sym(lib, "fmi2SetFMUstate");
    F.free_state = (FreeState_t)sym(lib, "fmi2FreeFMUstate");
    F.state_size = (StateSize_t)sym(lib, "fmi2SerializedFMUstateSize");
    F.serialize = (Serialize_t)sym(lib, "fmi2SerializeFMUstate");
    F.deserialize = (Deserialize_t)sym(lib, "fmi2DeSerializeFMUstate");
    F.version = (Version_t)sym(lib, "fmi2GetVersion");
#endif
}

/* The calls whose signatures differ between the APIs, with FMI 2.0's arguments. */
static fmi2Component instantiate(const char *label, const char *res) {
#ifdef ECF_FMI3
    return F.instantiate3(label, FMU_GUID, res, false, false, false, false, NULL, 0, NULL, logger3, NULL);
#else
    return F.instantiate(label, fmi2CoSimulation, FMU_GUID, res, &CALLBACKS, 0, 0);
#endif
}
static fmi2Status set_real(fmi2Component c, const fmi2ValueReference *vr, size_t n, const fmi2Real *x) {
#ifdef ECF_FMI3
    return F.set_float64(c, vr, n, x, n);
#else
    return F.set_real(c, vr, n, x);
#endif
}
static fmi2Status get_real(fmi2Component c, const fmi2ValueReference *vr, size_t n, fmi2Real *x) {
#ifdef ECF_FMI3
    return F.get_float64(c, vr, n, x, n);
#else
    return F.get_real(c, vr, n, x);
#endif
}
static fmi2Status set_integer(fmi2Component c, const fmi2ValueReference *vr, size_t n, const fmi2Integer *x) {
#ifdef ECF_FMI3
    return F.set_int32(c, vr, n, (const int32_t *)x, n);
#else
    return F.set_integer(c, vr, n, x);
#endif
}
static fmi2Status set_string(fmi2Component c, const fmi2ValueReference *vr, size_t n, const fmi2String *x) {
#ifdef ECF_FMI3
    return F.set_string3(c, vr, n, x, n);
#else
    return F.set_string(c, vr, n, x);
#endif
}
/* fmi2SetupExperiment + fmi2EnterInitializationMode, or fmi3EnterInitializationMode */
static fmi2Status enter_init(fmi2Component c) {
#ifdef ECF_FMI3
    return F.enter_init3(c, false, 0.0, 0.0, false, 0.0);
#else
    fmi2Status st = F.setup(c, 0, 0.0, 0.0, 0, 0.0);
    return st == fmi2OK ? F.enter_init(c) : st;
#endif
}
static fmi2Status do_step(fmi2Component c, double t, double h) {
#ifdef ECF_FMI3
    bool event = true, terminate = true, early = true;
    double last = -1.0;
    fmi2Status st = F.do_step3(c, t, h, true, &event, &terminate, &early, &last);
    if (st == fmi2OK && (event || terminate || early || last != t + h)) {
        fprintf(stderr, "FAIL: fmi3DoStep out-arguments %d %d %d %.17g\n", event, terminate, early, last);
        failures++;
    }
    return st;
#else
    return F.do_step(c, t, h, 1);
#endif
}

/* FMI 3.0: prints the field arrays (N_FIELD points each, the start value of n_field) */
static void print_field(const char *label, fmi2Component comp) {
#ifdef ECF_FMI3
    static double x[N_FIELD];
    static int32_t r[N_FIELD];
    for (unsigned int k = 0; k < 5; k++) {
        fmi2ValueReference vr = VR_FIELD_X + k;
        CHECK(F.get_float64(comp, &vr, 1, x, N_FIELD), fmi2OK);
        printf("%s %s", label, FIELD_NAME[k]);
        for (int i = 0; i < N_FIELD; i++) printf(" %.17g", x[i]);
        printf("\n");
    }
    fmi2ValueReference vr = VR_FIELD_REGIME;
    CHECK(F.get_int32(comp, &vr, 1, r, N_FIELD), fmi2OK);
    printf("%s field_regime", label);
    for (int i = 0; i < N_FIELD; i++) printf(" %d", (int)r[i]);
    printf("\n");
#else
    (void)label;
    (void)comp;
#endif
}

typedef struct {
    const char *label;
    const char *preset;      /* NULL: leave unset */
    const char *config_file; /* NULL: leave unset */
    int threads, scheme;     /* 0: leave at the start value */
    double v, fn, cx_from, cx_to, dt;
    int steps, print_every;
} Case;

static fmi2Component start(const Case *c, const char *res) {
    fmi2Component comp = instantiate(c->label, res);
    if (!comp) {
        fprintf(stderr, "FAIL: instantiation returned NULL for %s\n", c->label);
        exit(1);
    }
    fmi2ValueReference vr;
    if (c->preset) {
        vr = VR_PRESET;
        CHECK(set_string(comp, &vr, 1, &c->preset), fmi2OK);
    }
    if (c->config_file) {
        vr = VR_CONFIG;
        CHECK(set_string(comp, &vr, 1, &c->config_file), fmi2OK);
    }
    if (c->threads) {
        vr = VR_THREADS;
        CHECK(set_integer(comp, &vr, 1, &c->threads), fmi2OK);
    }
    if (c->scheme) {
        vr = VR_SCHEME;
        CHECK(set_integer(comp, &vr, 1, &c->scheme), fmi2OK);
    }
    fmi2ValueReference in_vr[] = {VR_CX, VR_V, VR_FN, VR_TBULK};
    fmi2Real in[] = {c->cx_from, c->v, c->fn, 20.0};
    CHECK(set_real(comp, in_vr, 4, in), fmi2OK);
    CHECK(enter_init(comp), fmi2OK);
    CHECK(F.exit_init(comp), fmi2OK);
    return comp;
}

static void outputs(fmi2Component comp, fmi2Real *y) { CHECK(get_real(comp, OUT_VR, N_OUT, y), fmi2OK); }

static void print_outputs(const char *label, int step, double t, fmi2Component comp) {
    fmi2Real y[N_OUT];
    outputs(comp, y);
    printf("%s step %d t %.17g", label, step, t);
    for (size_t i = 0; i < N_OUT; i++) printf(" %s %.17g", OUT_NAME[i], y[i]);
    printf("\n");
}

/* Steps k = from .. from + n - 1 (communication points k dt) with the case's creepage after the
   jump; prints every print_every-th step and the last. */
static void advance(const Case *c, fmi2Component comp, double *t, int from, int n, const char *label, int print) {
    fmi2ValueReference vr = VR_CX;
    for (int k = from; k < from + n; k++) {
        CHECK(set_real(comp, &vr, 1, &c->cx_to), fmi2OK);
        CHECK(do_step(comp, k * c->dt, c->dt), fmi2OK);
        *t = (k + 1) * c->dt;
        if (print && ((k + 1) % c->print_every == 0 || k + 1 == from + n)) print_outputs(label, k + 1, *t, comp);
    }
}

static int same(const fmi2Real *a, const fmi2Real *b) { return memcmp(a, b, N_OUT * sizeof(fmi2Real)) == 0; }

static void scenario(const Case *c, const char *res) {
    fmi2Component comp = start(c, res);
    double t = 0.0;
    print_outputs(c->label, 0, t, comp);
    advance(c, comp, &t, 0, c->steps, c->label, 1);
    print_field(c->label, comp);
    CHECK(F.terminate(comp), fmi2OK);
    F.free_instance(comp);
}

/* get/set/free state and serialize/deserialize: the continuation from a restored state equals the first one, bit for bit */
static void state_round_trips(const char *res) {
    Case c = {"state", "table4.1", NULL, 0, 0, 20.0, 110e3, 0.002, 0.05, 1e-4, 10, 10};
    fmi2Component comp = start(&c, res);
    double t = 0.0;
    advance(&c, comp, &t, 0, 10, c.label, 0);
    fmi2FMUstate s = NULL;
    CHECK(F.get_state(comp, &s), fmi2OK);
    double t0 = t;
    fmi2Real first[N_OUT], again[N_OUT], deser[N_OUT];
    advance(&c, comp, &t, 10, 10, c.label, 0);
    outputs(comp, first);
    CHECK(F.set_state(comp, s), fmi2OK);
    t = t0;
    advance(&c, comp, &t, 10, 10, c.label, 0);
    outputs(comp, again);
    size_t n = 0;
    CHECK(F.state_size(comp, s, &n), fmi2OK);
    fmi2Byte *bytes = malloc(n ? n : 1);
    CHECK(F.serialize(comp, s, bytes, n), fmi2OK);
    fmi2FMUstate s2 = NULL;
    CHECK(F.deserialize(comp, bytes, n, &s2), fmi2OK);
    CHECK(F.set_state(comp, s2), fmi2OK);
    t = t0;
    advance(&c, comp, &t, 10, 10, c.label, 0);
    outputs(comp, deser);
    printf("state set-state-continuation %s serialize-continuation %s bytes %zu\n", same(first, again) ? "identical" : "DIFFERS",
           same(first, deser) ? "identical" : "DIFFERS", n);
    if (!same(first, again) || !same(first, deser)) failures++;
    print_outputs("state", 20, t, comp);
    CHECK(F.free_state(comp, &s), fmi2OK);
    CHECK(F.free_state(comp, &s2), fmi2OK);
    if (s != NULL || s2 != NULL) {
        fprintf(stderr, "FAIL: fmi2FreeFMUstate left the handle non-NULL\n");
        failures++;
    }
    free(bytes);
    CHECK(F.terminate(comp), fmi2OK);
    F.free_instance(comp);
}

/* A bad input: the call returns fmi2Error and its message reaches the logger callback. */
static void bad_inputs(const char *res) {
    Case c = {"bad", "dry", NULL, 0, 0, 5.0, 110e3, 0.0, 0.01, 1e-3, 1, 1};
    fmi2Component comp = instantiate(c.label, res);
    if (!comp) {
        fprintf(stderr, "FAIL: instantiation returned NULL\n");
        exit(1);
    }
    fmi2ValueReference vr = VR_PRESET;
    const char *bad = "no_such_preset";
    int before = n_logged_errors;
    CHECK(set_string(comp, &vr, 1, &bad), fmi2Error);
    printf("bad-input preset status-error logged %s mentions-value %s\n", n_logged_errors > before ? "yes" : "NO",
           strstr(last_error, "no_such_preset") ? "yes" : "NO");
    if (n_logged_errors == before || !strstr(last_error, "no_such_preset")) failures++;
    F.free_instance(comp);

    comp = start(&c, res);
    fmi2Real nan_v = strtod("nan", NULL);
    vr = VR_V;
    before = n_logged_errors;
    CHECK(set_real(comp, &vr, 1, &nan_v), fmi2Error);
    printf("bad-input v=NaN status-error logged %s names-v %s\n", n_logged_errors > before ? "yes" : "NO",
           strstr(last_error, "v = ") ? "yes" : "NO");
    if (n_logged_errors == before || !strstr(last_error, "v = ")) failures++;
    F.free_instance(comp);
}

static const Case SAVE_CASE = {"saveload", "wet", NULL, 0, 0, 20.0, 110e3, 0.002, 0.05, 1e-4, 20, 5};

static void save_load(const char *res, const char *file, int save) {
    const Case *c = &SAVE_CASE;
    fmi2Component comp = start(c, res);
    double t = 0.0;
    if (save) {
        advance(c, comp, &t, 0, 20, c->label, 0);
        fmi2FMUstate s = NULL;
        CHECK(F.get_state(comp, &s), fmi2OK);
        size_t n = 0;
        CHECK(F.state_size(comp, s, &n), fmi2OK);
        fmi2Byte *bytes = malloc(n ? n : 1);
        CHECK(F.serialize(comp, s, bytes, n), fmi2OK);
        FILE *fp = fopen(file, "wb");
        if (!fp || fwrite(bytes, 1, n, fp) != n || fclose(fp) != 0) {
            fprintf(stderr, "FAIL: cannot write %s\n", file);
            exit(1);
        }
        free(bytes);
        CHECK(F.free_state(comp, &s), fmi2OK);
    } else {
        FILE *fp = fopen(file, "rb");
        if (!fp) {
            fprintf(stderr, "FAIL: cannot read %s\n", file);
            exit(1);
        }
        fseek(fp, 0, SEEK_END);
        long n = ftell(fp);
        fseek(fp, 0, SEEK_SET);
        fmi2Byte *bytes = malloc(n > 0 ? (size_t)n : 1);
        if (n <= 0 || fread(bytes, 1, (size_t)n, fp) != (size_t)n) {
            fprintf(stderr, "FAIL: cannot read %s\n", file);
            exit(1);
        }
        fclose(fp);
        fmi2FMUstate s = NULL;
        CHECK(F.deserialize(comp, bytes, (size_t)n, &s), fmi2OK);
        CHECK(F.set_state(comp, s), fmi2OK);
        CHECK(F.free_state(comp, &s), fmi2OK);
        free(bytes);
        t = 20 * c->dt;
    }
    advance(c, comp, &t, 20, 20, c->label, 1);
    CHECK(F.terminate(comp), fmi2OK);
    F.free_instance(comp);
}

int main(int argc, char **argv) {
    if (argc < 4) {
        fprintf(stderr, "usage: %s LIBRARY FMU_GUID_OR_TOKEN run|save|load RESOURCE_URI_OR_PATH [STATE_FILE]\n", argv[0]);
        return 2;
    }
#ifdef _WIN32
    /* "\n", not "\r\n": the output is compared byte for byte with the Linux run's */
    _setmode(_fileno(stdout), _O_BINARY);
#endif
    load(argv[1]);
    FMU_GUID = argv[2];
    const char *mode = argv[3];
    const char *res = argc > 4 ? argv[4] : NULL;
    printf("GetVersion %s\n", F.version());
    if (strcmp(mode, "run") == 0) {
        static const Case cases[] = {
            /* label, preset, config_file, threads, scheme, v [m/s], F_N [N], c_x before, c_x after, step [s], steps, print every */
            {"table4.1_20mps_0.1ms", "table4.1", NULL, 0, 0, 20.0, 110e3, 0.002, 0.05, 1e-4, 40, 10},
            {"dry_5mps_1ms", "dry", NULL, 0, 0, 5.0, 110e3, 0.01, 0.15, 1e-3, 20, 5},
            {"wet_30mps_1ms_threads2", "wet", NULL, 2, 0, 30.0, 110e3, 0.01, 0.15, 1e-3, 20, 5},
            {"dry_20mps_0.1ms_continuous", "dry", NULL, 0, 1, 20.0, 110e3, 0.002, 0.05, 1e-4, 40, 10},
            {"fastsim_10mps_1ms", "fastsim", NULL, 0, 0, 10.0, 110e3, 0.0, 0.003, 1e-3, 10, 5},
            {"polach_10mps_1ms", "polach", NULL, 0, 0, 10.0, 110e3, 0.0, 0.01, 1e-3, 5, 5},
            {"config_file_relative_1ms", NULL, "presets/dry_sanded.json", 0, 0, 10.0, 110e3, 0.0, 0.02, 1e-3, 10, 5},
        };
        for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) scenario(&cases[i], res);
        state_round_trips(res);
        bad_inputs(res);
    } else if ((strcmp(mode, "save") == 0 || strcmp(mode, "load") == 0) && argc > 5) {
        save_load(res, argv[5], strcmp(mode, "save") == 0);
    } else {
        fprintf(stderr, "unknown mode or missing state file: %s\n", mode);
        return 2;
    }
    printf("failures %d\n", failures);
    return failures == 0 ? 0 : 1;
}
