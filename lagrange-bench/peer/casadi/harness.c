/* Calls each function trace.cpp generated (casadi_gen.c) at its robot's
 * state and prints, per function, one `value` line per output (row-major) and one
 * `time` line: the median over batches of the mean ns of one call in a batch
 * (batches of about 2 ms, after one to warm up), the loop of
 * examples/casadi_peer/ on our side. `harness values` prints the values
 * alone; `harness [values] wide` uses the wide state, `harness solo12`
 * runs one robot. The states are casadi_codegen.py's (casadi_states.h).
 * Built by casadi_codegen.py with gcc -O3 -march=native, as this program
 * and, with CASADI_PEER_LIBRARY defined, as libharness.so without main,
 * whose peer_open / peer_run / peer_close let examples/casadi_peer/
 * alternate the C's batches with its own in one process. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "casadi_gen.h"

typedef int (*Eval)(const casadi_real**, casadi_real**, casadi_int*, casadi_real*, int);
typedef int (*Work)(casadi_int*, casadi_int*, casadi_int*, casadi_int*);

typedef struct {
  const char* name;
  int rows, cols;
} Output;

typedef struct {
  const char* robot;
  const char* quantity;
  Eval eval;
  Work work;
  const double *q, *v, *a;
  int n_in, n_out;
  Output out[3];
} Entry;

#include "casadi_states.h"
#include "casadi_registry.h"

/* The wide state's q of a robot (casadi_states.h), or NULL. */
static const double* wide_q(const char* robot) {
  for (size_t i = 0; i < sizeof WIDE / sizeof WIDE[0]; ++i)
    if (strcmp(WIDE[i].robot, robot) == 0) return WIDE[i].q;
  return NULL;
}

/* Whether a robot of the registry has this name. */
static int known(const char* name) {
  for (size_t e = 0; e < sizeof ENTRIES / sizeof ENTRIES[0]; ++e)
    if (strcmp(ENTRIES[e].robot, name) == 0) return 1;
  return 0;
}

/* Whether the command line names this robot. */
static int listed(const char* robot, int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (strcmp(argv[i], robot) == 0) return 1;
  return 0;
}

#define BATCHES 31

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static int compare(const void* x, const void* y) {
  const double a = *(const double*)x, b = *(const double*)y;
  return (a > b) - (a < b);
}

/* Keeps the compiler from dropping a call whose results are never read. */
static void clobber(void) { __asm__ volatile("" ::: "memory"); }

/* One function of the registry at one state, ready to run: what the
 * interleaved timing (`casadi_peer --interleave libharness.so`) holds. */
typedef struct {
  const Entry* f;
  const casadi_real** arg;
  casadi_real** res;
  casadi_int* iw;
  casadi_real* w;
  double* outs[3];
} Bound;

/* The robot's function for `quantity` at the small or the wide state, its
 * work arrays and outputs allocated: a handle, or NULL if there is none. */
void* peer_open(const char* robot, const char* quantity, int wide) {
  for (size_t e = 0; e < sizeof ENTRIES / sizeof ENTRIES[0]; ++e) {
    const Entry* f = &ENTRIES[e];
    if (strcmp(f->robot, robot) != 0 || strcmp(f->quantity, quantity) != 0) continue;
    const double* q = wide ? wide_q(robot) : f->q;
    if (!q) return NULL;
    Bound* b = calloc(1, sizeof *b);
    casadi_int sz_arg, sz_res, sz_iw, sz_w;
    f->work(&sz_arg, &sz_res, &sz_iw, &sz_w);
    b->f = f;
    b->arg = calloc(sz_arg > 3 ? sz_arg : 3, sizeof *b->arg);
    b->res = calloc(sz_res > 3 ? sz_res : 3, sizeof *b->res);
    b->iw = calloc(sz_iw + 1, sizeof *b->iw);
    b->w = calloc(sz_w + 1, sizeof *b->w);
    b->arg[0] = q;
    b->arg[1] = f->v;
    if (f->n_in > 2) b->arg[2] = f->a;
    for (int o = 0; o < f->n_out; ++o)
      b->res[o] = b->outs[o] = calloc(f->out[o].rows * f->out[o].cols, sizeof(double));
    return b;
  }
  return NULL;
}

/* Seconds taken by `calls` calls, the loop of main below. */
double peer_run(void* handle, long calls) {
  Bound* b = handle;
  const double start = now();
  for (long i = 0; i < calls; ++i) {
    b->f->eval(b->arg, b->res, b->iw, b->w, 0);
    clobber();
  }
  return now() - start;
}

void peer_close(void* handle) {
  Bound* b = handle;
  for (int o = 0; o < b->f->n_out; ++o) free(b->outs[o]);
  free(b->arg);
  free(b->res);
  free(b->iw);
  free(b->w);
  free(b);
}

#ifndef CASADI_PEER_LIBRARY
int main(int argc, char** argv) {
  /* Arguments: `values` (print the values, time nothing), `wide` (the
   * wide state's q instead of the small one) or `small` (the default), and
   * robots' names (only those; every robot without one), in any order. */
  int time_them = 1, wide = 0, named = 0;
  for (int i = 1; i < argc; ++i) {
    if (strcmp(argv[i], "values") == 0) {
      time_them = 0;
    } else if (strcmp(argv[i], "wide") == 0) {
      wide = 1;
    } else if (strcmp(argv[i], "small") != 0) {
      if (!known(argv[i])) {
        fprintf(stderr, "harness: unknown argument %s (values, small, wide or a robot)\n", argv[i]);
        return 2;
      }
      named = 1;
    }
  }
  for (size_t e = 0; e < sizeof ENTRIES / sizeof ENTRIES[0]; ++e) {
    const Entry* f = &ENTRIES[e];
    if (named && !listed(f->robot, argc, argv)) continue;
    casadi_int sz_arg, sz_res, sz_iw, sz_w;
    f->work(&sz_arg, &sz_res, &sz_iw, &sz_w);
    const casadi_real** arg = calloc(sz_arg > 3 ? sz_arg : 3, sizeof *arg);
    casadi_real** res = calloc(sz_res > 3 ? sz_res : 3, sizeof *res);
    casadi_int* iw = calloc(sz_iw + 1, sizeof *iw);
    casadi_real* w = calloc(sz_w + 1, sizeof *w);
    arg[0] = wide ? wide_q(f->robot) : f->q;
    if (!arg[0]) {
      fprintf(stderr, "no wide state for %s\n", f->robot);
      return 1;
    }
    arg[1] = f->v;
    if (f->n_in > 2) arg[2] = f->a;
    double* outs[3];
    for (int o = 0; o < f->n_out; ++o) res[o] = outs[o] = calloc(f->out[o].rows * f->out[o].cols, sizeof(double));
    f->eval(arg, res, iw, w, 0);
    for (int o = 0; o < f->n_out; ++o) {
      printf("value %s %s %s ", f->robot, f->quantity, f->out[o].name);
      const int r = f->out[o].rows, c = f->out[o].cols;
      for (int i = 0; i < r; ++i)
        for (int j = 0; j < c; ++j) printf("%s%.17e", i + j ? "," : "", outs[o][j * r + i]);
      printf("\n");
    }
    if (time_them) {
      long calls = 1;
      for (;;) {
        const double start = now();
        for (long i = 0; i < calls; ++i) {
          f->eval(arg, res, iw, w, 0);
          clobber();
        }
        if (now() - start > 2e-3) break;
        calls *= 2;
      }
      double times[BATCHES];
      for (int b = 0; b < BATCHES; ++b) {
        const double start = now();
        for (long i = 0; i < calls; ++i) {
          f->eval(arg, res, iw, w, 0);
          clobber();
        }
        times[b] = (now() - start) * 1e9 / calls;
      }
      qsort(times, BATCHES, sizeof times[0], compare);
      printf("time %s %s %.1f\n", f->robot, f->quantity, times[BATCHES / 2]);
    }
    fflush(stdout);
    for (int o = 0; o < f->n_out; ++o) free(outs[o]);
    free(arg);
    free(res);
    free(iw);
    free(w);
  }
  return 0;
}
#endif
