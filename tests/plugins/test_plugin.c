// SPDX-License-Identifier: MIT
/* A plugin for chainbench's own tests, in C to prove the ABI is plain C. Without a fault it is a
 * ballistic integrator (semi-implicit Euler, no collisions), whose free fall the tests compare
 * with the analytic answer. Built once per fault: TEST_PLUGIN_FAULT selects what goes wrong. */
#include <chainbench/engine_plugin.h>

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#define FAULT_NONE 0
#define FAULT_NO_ENTRY 1      /* exports no entry point */
#define FAULT_ABI 2           /* built for another ABI */
#define FAULT_SIZE 3          /* a cb_engine of the wrong size */
#define FAULT_NULL_FUNCTION 4 /* no step function */
#define FAULT_BAD_COUNTER 5   /* a counter name with a space */
#define FAULT_CREATE 6        /* refuses every world */
#define FAULT_STEP 7          /* fails at step 3 */
#define FAULT_COUNT 8         /* holds one body more than the scene */
#define FAULT_NAN 9           /* positions turn to NaN at step 2 */
#define FAULT_CRASH 10        /* dies of SIGSEGV at step 2 */
#define FAULT_VELOCITY 11     /* refuses every velocity */
#define FAULT_ABORT 12        /* aborts (SIGABRT) at step 10 */
#define FAULT_HANG 13         /* never returns from step 10 */
#define FAULT_EXIT 14         /* calls exit(0) at step 10, as a plugin that quits might */
/* Hostile returns: what a plugin hands back that chainbench must not trust. */
#define FAULT_CREATE_UNTERMINATED 15 /* fills the whole error buffer, no terminator */
#define FAULT_STEP_UNTERMINATED 16   /* the same at step 3 */
#define FAULT_NAME_UNTERMINATED 17   /* a name with no terminator within 4 KiB */
#define FAULT_NAME_ESCAPE 18         /* a name that clears the terminal and prints a line */
#define FAULT_COUNTER_UNTERMINATED 19
#define FAULT_COUNTER_DUPLICATE 20 /* two counters of one name */
#define FAULT_COUNTER_RESERVED 21  /* a counter named budget_hits */
#define FAULT_COUNTER_NAN 22       /* its counter turns NaN at step 2 */
#define FAULT_STEP_RC 23           /* step 3 returns 2 */
#define FAULT_CAPABILITY 24        /* an unknown capability bit */
#define FAULT_ERROR_ESCAPE 25      /* refuses every world with terminal escapes in the message */
#define FAULT_ABI1 26              /* built for ABI 1, which had no declared keys */
/* Declared keys that are not what the contract allows. */
#define FAULT_KEY_NAME 27            /* a key named "Gain" */
#define FAULT_KEY_DEFAULT 28         /* gain's default, 20, outside its range [0, 10] */
#define FAULT_KEY_RANGE 29           /* substeps' range [8, 1] */
#define FAULT_KEY_TYPE 30            /* a key of type 7 */
#define FAULT_COUNTER_AGGREGATE 31   /* a counter aggregated by 9 */
#define FAULT_COUNTER_DESCRIPTION 32 /* a counter whose description holds a newline */
#define FAULT_LIFETIMES_NULL 33      /* CB_CAN_LIFETIMES without remove_body */
#define FAULT_ADD_REFUSED 34         /* add_body refuses every body */
/* Hostile to the process it runs in (bench/support/child_process.h guards against each): */
#define FAULT_CLOSE_FDS 35   /* closes every descriptor above stderr, then hangs at step 3 */
#define FAULT_FORK_HOLD 36   /* leaves a process of its own holding them, then SIGSEGV at step 3 */
#define FAULT_FORGE 37       /* writes 4 KiB into descriptors 3 to 63, then _exit(0) */
#define FAULT_OOM 38         /* allocates without end at step 3 (abort() when malloc fails) */
#define FAULT_LOAD_CRASH 39  /* dies of SIGSEGV in a static constructor, while dlopen runs */
#define FAULT_ENTRY_CRASH 40 /* dies of SIGSEGV in its entry function */
#define FAULT_NAME_GUARD 41  /* a name of 5 bytes ending the page before an unreadable one */

#ifndef TEST_PLUGIN_FAULT
#define TEST_PLUGIN_FAULT FAULT_NONE
#endif

struct cb_world {
  uint32_t count;
  double gravity[2];
  double dt;
  int steps;
  cb_body* bodies;
  char* alive; /* per body: in the world now */
};

static void write_error(char* error, size_t size, const char* text) {
  if (size > 0) snprintf(error, size, "%s", text);
}

/* The hostile faults' part of create. */
static void hostile_create(void) {
  int fd;
  if (TEST_PLUGIN_FAULT == FAULT_CLOSE_FDS) {
    for (fd = 3; fd < 1024; ++fd)
      close(fd);
  }
  if (TEST_PLUGIN_FAULT == FAULT_FORK_HOLD && fork() == 0) {
    /* Holds whatever it inherited but the standard streams (the test reads those to their end),
     * in a session of its own, for longer than the test waits. */
    close(0), close(1), close(2);
    setsid();
    sleep(20);
    _exit(0);
  }
  if (TEST_PLUGIN_FAULT == FAULT_FORGE) {
    char junk[4096];
    memset(junk, 'A', sizeof junk);
    for (fd = 3; fd < 64; ++fd)
      if (write(fd, junk, sizeof junk) < 0) continue;
    _exit(0);
  }
}

static cb_world* create(const cb_world_desc* desc, char* error, size_t error_size) {
  cb_world* w;
  hostile_create();
  if (TEST_PLUGIN_FAULT == FAULT_CREATE) {
    write_error(error, error_size, "this plugin builds no worlds");
    return NULL;
  }
  if (TEST_PLUGIN_FAULT == FAULT_CREATE_UNTERMINATED) {
    memset(error, 'x', error_size);
    return NULL;
  }
  if (TEST_PLUGIN_FAULT == FAULT_ERROR_ESCAPE) {
    write_error(error, error_size, "bad\033[2J\nchainbench: all engines ok");
    return NULL;
  }
  /* label=echo: refuses the world with the settings it was given, in their order. */
  if (desc->setting_count == 3 && strcmp(desc->settings[2].key, "label") == 0 &&
      strcmp(desc->settings[2].value, "echo") == 0) {
    char message[256];
    snprintf(message, sizeof message, "settings: %s=%s %s=%s %s=%s", desc->settings[0].key,
             desc->settings[0].value, desc->settings[1].key, desc->settings[1].value,
             desc->settings[2].key, desc->settings[2].value);
    write_error(error, error_size, message);
    return NULL;
  }
  /* label=describe: refuses the world with what its description says of the scene. */
  if (desc->setting_count == 3 && strcmp(desc->settings[2].value, "describe") == 0) {
    char message[512];
    size_t used = (size_t)snprintf(message, sizeof message, "steps %d, bodies", (int)desc->steps);
    uint32_t i;
    for (i = 0; i < desc->body_count && used < sizeof message; ++i)
      used += (size_t)snprintf(message + used, sizeof message - used, " %s", desc->bodies[i].name);
    for (i = 0; i < desc->driver_count && used < sizeof message; ++i) {
      const cb_driver* d = &desc->drivers[i];
      used += (size_t)snprintf(message + used, sizeof message - used,
                               ", driver body %u axes %u velocity %g %g steps %d to %d",
                               (unsigned)d->body, (unsigned)d->axes, d->velocity[0], d->velocity[1],
                               (int)d->from_step, (int)d->to_step);
    }
    write_error(error, error_size, message);
    return NULL;
  }
  w = (cb_world*)calloc(1, sizeof *w);
  if (!w) return NULL;
  w->count = desc->body_count;
  w->gravity[0] = desc->gravity[0];
  w->gravity[1] = desc->gravity[1];
  w->dt = desc->dt;
  w->bodies = (cb_body*)calloc(desc->body_count ? desc->body_count : 1, sizeof(cb_body));
  if (!w->bodies) {
    free(w);
    return NULL;
  }
  memcpy(w->bodies, desc->bodies, desc->body_count * sizeof(cb_body));
  w->alive = (char*)calloc(desc->body_count ? desc->body_count : 1, 1);
  if (!w->alive) {
    free(w->bodies);
    free(w);
    return NULL;
  }
  for (uint32_t i = 0; i < desc->body_count; ++i)
    w->alive[i] = desc->bodies[i].from_step == 0;
  return w;
}

static int set_velocity(cb_world* w, uint32_t body, double vx, double vy, uint32_t axes) {
  if (TEST_PLUGIN_FAULT == FAULT_VELOCITY || body >= w->count) return 1;
  if (axes & CB_AXIS_X) w->bodies[body].velocity[0] = vx;
  if (axes & CB_AXIS_Y) w->bodies[body].velocity[1] = vy;
  return 0;
}

static int step(cb_world* w, char* error, size_t error_size) {
  uint32_t i;
  ++w->steps;
  if (TEST_PLUGIN_FAULT == FAULT_STEP && w->steps == 3) {
    write_error(error, error_size, "the solver diverged");
    return -1;
  }
  if (TEST_PLUGIN_FAULT == FAULT_STEP_UNTERMINATED && w->steps == 3) {
    memset(error, 'y', error_size);
    return -1;
  }
  if (TEST_PLUGIN_FAULT == FAULT_STEP_RC && w->steps == 3) return 2;
  if (TEST_PLUGIN_FAULT == FAULT_CLOSE_FDS && w->steps == 3)
    for (;;)
      pause();
  if (TEST_PLUGIN_FAULT == FAULT_FORK_HOLD && w->steps == 3) raise(SIGSEGV);
  if (TEST_PLUGIN_FAULT == FAULT_OOM && w->steps == 3) {
    for (;;) {
      char* p = malloc(1u << 24);
      if (!p) abort();
      memset(p, 1, 1u << 24);
    }
  }
  if (TEST_PLUGIN_FAULT == FAULT_CRASH && w->steps == 2) raise(SIGSEGV);
  if (TEST_PLUGIN_FAULT == FAULT_ABORT && w->steps == 10) abort();
  if (TEST_PLUGIN_FAULT == FAULT_EXIT && w->steps == 10) exit(0);
  if (TEST_PLUGIN_FAULT == FAULT_HANG && w->steps == 10) {
    /* A test waits for this file to know the hang has begun (CHAINBENCH_TEST_HANG_MARK). */
    const char* mark = getenv("CHAINBENCH_TEST_HANG_MARK");
    FILE* f = mark ? fopen(mark, "w") : NULL;
    if (f) fclose(f);
    for (;;)
      pause();
  }
  for (i = 0; i < w->count; ++i) {
    cb_body* b = &w->bodies[i];
    if (b->kind == CB_STATIC || !w->alive[i]) continue;
    if (b->kind == CB_DYNAMIC) {
      b->velocity[0] += w->dt * b->gravity_scale * w->gravity[0];
      b->velocity[1] += w->dt * b->gravity_scale * w->gravity[1];
    }
    b->center[0] += w->dt * b->velocity[0];
    b->center[1] += w->dt * b->velocity[1];
    if (TEST_PLUGIN_FAULT == FAULT_NAN && w->steps >= 2) b->center[0] = NAN;
  }
  return 0;
}

static uint32_t read_state(const cb_world* w, double* positions, double* velocities, double* angles,
                           uint32_t capacity) {
  uint32_t i;
  for (i = 0; i < w->count && i < capacity; ++i) {
    if (!w->alive[i]) continue;
    if (positions) {
      positions[2 * i] = w->bodies[i].center[0];
      positions[2 * i + 1] = w->bodies[i].center[1];
    }
    if (velocities) {
      velocities[2 * i] = w->bodies[i].velocity[0];
      velocities[2 * i + 1] = w->bodies[i].velocity[1];
    }
    if (angles) angles[i] = 0.0;
  }
  return TEST_PLUGIN_FAULT == FAULT_COUNT ? w->count + 1 : w->count;
}

/* A body enters as create described it: it has not moved while out of the world. */
static int add_body(cb_world* w, uint32_t body) {
  if (TEST_PLUGIN_FAULT == FAULT_ADD_REFUSED || body >= w->count || w->alive[body]) return 1;
  w->alive[body] = 1;
  return 0;
}

static int remove_body(cb_world* w, uint32_t body) {
  if (body >= w->count || !w->alive[body]) return 1;
  w->alive[body] = 0;
  return 0;
}

static void destroy(cb_world* w) {
  if (!w) return;
  free(w->alive);
  free(w->bodies);
  free(w);
}

/* 4 KiB without a terminator, for the unterminated names: longer than any bound chainbench
 * reads within, so a bounded read stays inside it. */
#define LONG4 'A', 'A', 'A', 'A'
#define LONG64                                                                               \
  LONG4, LONG4, LONG4, LONG4, LONG4, LONG4, LONG4, LONG4, LONG4, LONG4, LONG4, LONG4, LONG4, \
      LONG4, LONG4, LONG4
#define LONG1K                                                                                    \
  LONG64, LONG64, LONG64, LONG64, LONG64, LONG64, LONG64, LONG64, LONG64, LONG64, LONG64, LONG64, \
      LONG64, LONG64, LONG64, LONG64
#if TEST_PLUGIN_FAULT == FAULT_NAME_UNTERMINATED || TEST_PLUGIN_FAULT == FAULT_COUNTER_UNTERMINATED
static const char unterminated[4096] = {LONG1K, LONG1K, LONG1K, LONG1K};
#endif

/* Without a fault: the steps taken, once per aggregate, so that each aggregate has a known
 * answer over n steps: mean (n + 1) / 2, max n, sum n (n + 1) / 2, last n. */
#if TEST_PLUGIN_FAULT == FAULT_BAD_COUNTER
static const cb_counter counters[] = {{"steps so far", "steps taken", CB_AGG_MEAN}};
#elif TEST_PLUGIN_FAULT == FAULT_COUNTER_UNTERMINATED
static const cb_counter counters[] = {{unterminated, "steps taken", CB_AGG_MEAN}};
#elif TEST_PLUGIN_FAULT == FAULT_COUNTER_DUPLICATE
static const cb_counter counters[] = {{"steps_so_far", "steps taken", CB_AGG_MEAN},
                                      {"steps_so_far", "steps taken", CB_AGG_MAX}};
#elif TEST_PLUGIN_FAULT == FAULT_COUNTER_RESERVED
static const cb_counter counters[] = {{"budget_hits", "steps taken", CB_AGG_MEAN}};
#elif TEST_PLUGIN_FAULT == FAULT_COUNTER_AGGREGATE
static const cb_counter counters[] = {{"steps_so_far", "steps taken", 9}};
#elif TEST_PLUGIN_FAULT == FAULT_COUNTER_DESCRIPTION
static const cb_counter counters[] = {{"steps_so_far", "steps\ntaken", CB_AGG_MEAN}};
#else
static const cb_counter counters[] = {{"steps_so_far", "steps taken, mean", CB_AGG_MEAN},
                                      {"steps_max", "steps taken, largest", CB_AGG_MAX},
                                      {"steps_sum", "steps taken, summed", CB_AGG_SUM},
                                      {"steps_last", "steps taken, last", CB_AGG_LAST}};
#endif
#define COUNTER_COUNT (sizeof counters / sizeof counters[0])

/* Keys it declares; the ballistic integrator ignores them, but label=echo shows what arrived. */
static const cb_key keys[] = {
    {TEST_PLUGIN_FAULT == FAULT_KEY_NAME ? "Gain" : "gain", CB_KEY_NUMBER, 0, 10,
     TEST_PLUGIN_FAULT == FAULT_KEY_DEFAULT ? "20" : "1", "a gain, from 0 to 10"},
    {"substeps", TEST_PLUGIN_FAULT == FAULT_KEY_TYPE ? 7 : CB_KEY_INTEGER,
     TEST_PLUGIN_FAULT == FAULT_KEY_RANGE ? 8 : 1, TEST_PLUGIN_FAULT == FAULT_KEY_RANGE ? 1 : 8,
     "1", "sub-steps per step"},
    {"label", CB_KEY_TEXT, 0, 0, "none", "echo: refuse the world, listing the settings"}};

#if TEST_PLUGIN_FAULT == FAULT_NAME_UNTERMINATED
#define PLUGIN_NAME unterminated
#elif TEST_PLUGIN_FAULT == FAULT_NAME_ESCAPE
#define PLUGIN_NAME "\033[2J\033[Hchainbench: all engines ok\n"
#else
#define PLUGIN_NAME "ballistic"
#endif

static void read_counters(const cb_world* w, double* values) {
  size_t k;
  for (k = 0; k < COUNTER_COUNT; ++k)
    values[k] = (double)w->steps;
  if (TEST_PLUGIN_FAULT == FAULT_COUNTER_NAN && w->steps >= 2) values[0] = NAN;
}

static const cb_engine engine = {
    .abi = TEST_PLUGIN_FAULT == FAULT_ABI    ? CHAINBENCH_PLUGIN_ABI + 1
           : TEST_PLUGIN_FAULT == FAULT_ABI1 ? 1
                                             : CHAINBENCH_PLUGIN_ABI,
    .size = TEST_PLUGIN_FAULT == FAULT_SIZE ? sizeof(cb_engine) - 8 : sizeof(cb_engine),
    .name = PLUGIN_NAME,
    .capabilities = CB_CAN_KINEMATIC | CB_CAN_AXIS_DRIVES | CB_CAN_LIFETIMES |
                    (TEST_PLUGIN_FAULT == FAULT_CAPABILITY ? 256u : 0u),
    .counter_count = COUNTER_COUNT,
    .counters = counters,
    .key_count = sizeof keys / sizeof keys[0],
    .keys = keys,
    .create = create,
    .set_velocity = set_velocity,
    .step = TEST_PLUGIN_FAULT == FAULT_NULL_FUNCTION ? NULL : step,
    .read_state = read_state,
    .read_counters = read_counters,
    .destroy = destroy,
    .add_body = add_body,
    .remove_body = TEST_PLUGIN_FAULT == FAULT_LIFETIMES_NULL ? NULL : remove_body};

#if TEST_PLUGIN_FAULT == FAULT_NO_ENTRY
CHAINBENCH_PLUGIN_EXPORT const cb_engine* not_the_entry_point(void) {
  return &engine;
}
#else
CHAINBENCH_PLUGIN_EXPORT const cb_engine* chainbench_engine_plugin(void) {
  if (TEST_PLUGIN_FAULT == FAULT_ENTRY_CRASH) raise(SIGSEGV);
#if TEST_PLUGIN_FAULT == FAULT_NAME_GUARD
  {
    /* A copy of the table whose name a read past its 5 bytes faults on. */
    static cb_engine guarded;
    const long page = sysconf(_SC_PAGESIZE);
    char* m = mmap(NULL, 2 * page, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (m == MAP_FAILED || mprotect(m + page, page, PROT_NONE) != 0) return NULL;
    memset(m + page - 5, 'a', 5);
    guarded = engine;
    guarded.name = m + page - 5;
    return &guarded;
  }
#endif
  return &engine;
}
#endif
#if TEST_PLUGIN_FAULT == FAULT_LOAD_CRASH
__attribute__((constructor)) static void crash_while_loading(void) {
  raise(SIGSEGV);
}
#endif
