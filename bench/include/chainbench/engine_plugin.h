// SPDX-License-Identifier: MIT
/* chainbench engine plugins: put your own collision resolver on the bench.
 *
 * A plugin is a shared library that exports one function, chainbench_engine_plugin(), returning
 * a table of functions (cb_engine). chainbench loads it with
 *     chainbench run --scene pyramid --engines plugin:path=./librelaxation.so,iterations=4
 * and builds one world per run from a flat description of the scene, then, every step, sets the
 * velocities of driven bodies, steps, and reads every body's state back. A plugin declares its keys
 * (cb_key): chainbench checks a spec's keys and values against them when it reads the spec, before
 * any engine runs, and hands the plugin every declared key as a setting, defaults filled in.
 *
 * Units are metres, kilograms and seconds, y up; bodies are axis-aligned boxes given by centre and
 * half extents, in scene order, and every index below is a body's place in that order. The
 * library is C: a plugin can be written in C, C++ or anything that exports C functions.
 *
 * Versioning: CHAINBENCH_PLUGIN_ABI changes whenever a structure or a function here changes; a
 * plugin built against another version is refused with a message naming both, never called.
 * ABI 2 added declared keys and counters' aggregates, body names, drivers, the step count and
 * bodies that come and go.
 */
#ifndef CHAINBENCH_ENGINE_PLUGIN_H
#define CHAINBENCH_ENGINE_PLUGIN_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CHAINBENCH_PLUGIN_ABI 2

/* Body kinds. */
enum { CB_STATIC = 0, CB_KINEMATIC = 1, CB_DYNAMIC = 2 };

/* What a plugin can simulate (cb_engine.capabilities). A scene that needs more is refused by
 * chainbench with a message, so a plugin never sees what it cannot do. */
enum {
  CB_CAN_ROTATE = 1,       /* bodies turn when cb_world_desc.rotation is set */
  CB_CAN_FRICTION = 2,     /* cb_body.friction is honoured */
  CB_CAN_RESTITUTION = 4,  /* cb_body.restitution is honoured */
  CB_CAN_KINEMATIC = 8,    /* CB_KINEMATIC bodies */
  CB_CAN_AXIS_DRIVES = 16, /* set_velocity with one axis only */
  CB_CAN_LIFETIMES = 32    /* bodies that come and go: add_body and remove_body are given */
};

/* Axes of a velocity to set (set_velocity). */
enum { CB_AXIS_X = 1, CB_AXIS_Y = 2 };

typedef struct cb_body {
  int32_t kind;           /* CB_STATIC, CB_KINEMATIC or CB_DYNAMIC */
  double center[2];       /* m */
  double half_extents[2]; /* m, > 0 */
  double mass;            /* kg, > 0 for a dynamic body; 0 otherwise */
  double velocity[2];     /* m/s, initial; a kinematic body keeps it */
  double gravity_scale;   /* multiplies gravity for this body (dynamic bodies) */
  double friction;        /* >= 0, as the scene gives it */
  double restitution;     /* in [0, 1] */
  const char* name;       /* the scene's, printable ASCII, terminated; kept until destroy */
  /* Its life: in the world for steps from_step <= n < to_step. create builds the bodies of
   * from_step 0 only; the others enter through add_body (CB_CAN_LIFETIMES). */
  int32_t from_step; /* >= 0 */
  int32_t to_step;   /* > from_step; INT32_MAX: to the end */
} cb_body;

/* What a scene's driver holds: chainbench sets it through set_velocity at the start of every step
 * from from_step to to_step - 1; a plugin may read it to plan ahead, but need not. */
typedef struct cb_driver {
  uint32_t body;      /* the driven body's index */
  uint32_t axes;      /* CB_AXIS_X | CB_AXIS_Y: the axes it holds; the other is left free */
  double velocity[2]; /* m/s along the held axes (0 on a free one) */
  int32_t from_step;  /* >= 0: the first step it holds at, counted from 0 */
  int32_t to_step;    /* > from_step: it holds before this step; INT32_MAX: to the end */
} cb_driver;

/* How chainbench sums a counter's per-step values up over a run (cb_counter.aggregate). */
enum { CB_AGG_MEAN = 0, CB_AGG_MAX = 1, CB_AGG_SUM = 2, CB_AGG_LAST = 3 };

/* A figure the plugin reports about every step, e.g. pair pushes; its strings printable ASCII. */
typedef struct cb_counter {
  /* [a-z0-9_], terminated within 32 bytes, distinct, none of budget_hits and crush_events (kept
   * for the chain solver's counters). */
  const char* name;
  const char* description; /* one line, terminated within 128 bytes */
  int32_t aggregate;       /* CB_AGG_MEAN per step, MAX of any step, SUM over the run, LAST step */
} cb_counter;

/* Types of a key's value (cb_key.type). */
enum { CB_KEY_NUMBER = 0, CB_KEY_INTEGER = 1, CB_KEY_TEXT = 2 };

/* A key a spec may give the plugin, e.g. iterations=8. Every string is printable ASCII. */
typedef struct cb_key {
  const char* name; /* [a-z0-9_], terminated within 32 bytes, distinct, not "path" */
  int32_t type;     /* CB_KEY_NUMBER, CB_KEY_INTEGER or CB_KEY_TEXT */
  double min;       /* finite, <= max, whole for an integer; unused for text */
  double max;       /* finite; an integer's range within +-2^53 */
  /* Terminated within 64 bytes: a value the key accepts (a text key's is not empty). */
  const char* default_value;
  const char* help; /* one line, terminated within 128 bytes */
} cb_key;

typedef struct cb_setting {
  const char* key;   /* a declared key's name, every one in declaration order */
  const char* value; /* checked against its cb_key: a number in its shortest form, text as typed */
} cb_setting;

typedef struct cb_world_desc {
  uint32_t abi; /* CHAINBENCH_PLUGIN_ABI */
  uint32_t body_count;
  double gravity[2];     /* m/s^2 */
  double dt;             /* s, the length of every step */
  int32_t rotation;      /* nonzero: the scene lets bodies turn */
  const cb_body* bodies; /* body_count bodies, in scene order; valid during create only */
  uint32_t setting_count;
  const cb_setting* settings; /* every declared key, in declaration order */
  int32_t steps;              /* > 0: the steps the scene runs (a run may stop earlier) */
  uint32_t driver_count;
  const cb_driver* drivers; /* driver_count drivers, in scene order */
} cb_world_desc;

/* A plugin's world, opaque to chainbench. */
typedef struct cb_world cb_world;

typedef struct cb_engine {
  uint32_t abi;  /* CHAINBENCH_PLUGIN_ABI */
  uint32_t size; /* sizeof(cb_engine) */
  /* Shown in messages, e.g. "relaxation": printable ASCII, terminated within 64 bytes. */
  const char* name;
  uint32_t capabilities;      /* CB_CAN_* only: an unknown bit is refused */
  uint32_t counter_count;     /* figures read_counters reports per step (<= 16) */
  const cb_counter* counters; /* counter_count counters, in the order read_counters writes them */
  uint32_t key_count; /* keys a spec may give (<= 32); a spec key it does not declare is refused */
  const cb_key* keys; /* key_count keys, listed by `chainbench engines plugin:path=FILE` */

  /* A world built from desc, or NULL with a message written to error (at most error_size bytes,
   * terminated; printable ASCII, or only its printable start is shown). Settings are already
   * checked against the declared keys. */
  cb_world* (*create)(const cb_world_desc* desc, char* error, size_t error_size);
  /* Sets the velocity of body along the axes set in axes (CB_AXIS_X | CB_AXIS_Y), leaving the
   * other axis as it is: chainbench drives bodies this way at the start of a step. 0, or nonzero
   * for a bad body or axes. */
  int (*set_velocity)(cb_world* world, uint32_t body, double vx, double vy, uint32_t axes);
  /* Advances the world by desc->dt. Returns 0; 1 when the step was cut short to bound its work
   * (chainbench then judges the run `budget`); a negative value with a message on error (as for
   * create). Any other value is refused. */
  int (*step)(cb_world* world, char* error, size_t error_size);
  /* Writes the state of the first `capacity` bodies: positions and velocities as x, y pairs,
   * angles in radians (any of the three may be NULL: skip it); the entries of bodies not in the
   * world now are not read. Returns body_count (every index, in the world or not). */
  uint32_t (*read_state)(const cb_world* world, double* positions, double* velocities,
                         double* angles, uint32_t capacity);
  /* Writes counter_count finite values about the last step (NaN or infinity is refused); may be
   * NULL when counter_count is 0. */
  void (*read_counters)(const cb_world* world, double* values);
  void (*destroy)(cb_world* world);
  /* Bodies that come and go, by index: add_body puts body (not in the world) in as desc described
   * it (centre, velocity), before step from_step; remove_body takes it out before step to_step.
   * 0, or nonzero for a bad body. Both given with CB_CAN_LIFETIMES, else may be NULL. */
  int (*add_body)(cb_world* world, uint32_t body);
  int (*remove_body)(cb_world* world, uint32_t body);
} cb_engine;

/* The one function a plugin exports. */
#define CHAINBENCH_PLUGIN_ENTRY "chainbench_engine_plugin"
typedef const cb_engine* (*cb_entry_fn)(void);

#if defined(_WIN32)
#define CHAINBENCH_PLUGIN_EXPORT __declspec(dllexport)
#else
#define CHAINBENCH_PLUGIN_EXPORT __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
}
#endif

#endif /* CHAINBENCH_ENGINE_PLUGIN_H */
