/*
 * VolPhys — physics plugin C ABI. This is the only public header. C99, no C++ types.
 *
 * Conventions
 * - Every call returns a vpStatus. On failure vpGetLastError() returns a message (owned by
 *   the library, valid until the next VolPhys call on the same thread) that names the bad
 *   argument or field and its value. A failing call changes nothing.
 * - Objects are referred to by small value ids (index + generation). An all-zero id is null.
 *   Using a null, destroyed or foreign id returns vpStatus_InvalidId, never crashes. No id is
 *   issued twice in a process (a slot whose generations run out is retired), and a collider,
 *   deformable or fluid id carries its kind in the top two bits of its generation, so one
 *   kind's id reinterpreted as another's is InvalidId too.
 * - Creation takes an XxxDef struct. Always start from vpDefaultXxxDef() and then change
 *   fields.
 * - Versioned structs (those with a structSize: the defs, vpStepStats, vpActorStats,
 *   vpBodyProperties, vpDeformableMaterial, vpFluidParameters) only ever grow by fields appended at the end, so an older header's
 *   struct is a prefix of this one. The library accepts a structSize equal to its own sizeof or
 *   to the offset where one of its fields begins (the size of an older header's struct). A
 *   struct it reads (defs, vpColliderSetProperties) is read up to structSize only, the missing
 *   fields taking their defaults (for properties: their current values); a struct it fills
 *   (stats, vpColliderGetProperties) is written up to structSize only. A larger structSize (a
 *   header newer than the library), or one that ends inside a field, is VersionMismatch naming
 *   the struct. Set structSize from vpDefaultXxx() or sizeof. vpShapeDef is embedded in
 *   vpColliderDef, so it will not grow within a major version.
 * - Units are SI (metres, seconds, kilograms, pascals). Y is up only by the default gravity.
 *   Values are range-checked where they enter (defs, setters, scene files): positions within
 *   +-1e6 m, lengths (radii, half extents, cell sizes) in [1e-6, 1e5] m, masses in [1e-6, 1e9]
 *   kg, densities in [1e-6, 1e6] kg/m^3, speeds up to 1e5 m/s and rad/s.
 * - Files (tetFile, surfaceFile, meshFile, renderFile, scenes): only regular files are read
 *   (a FIFO or a directory is IoError). Surface files are imported by assimp in a short-lived
 *   child process (POSIX; in-process elsewhere) with a time limit (20 s) and an address-space
 *   cap (4 GiB above the host's): a file that crashes, hangs or exhausts the importer is
 *   ParseError or OutOfMemory, never a crash of the host.
 *
 * Threading contract
 * - Different worlds are independent: any calls on different worlds may run concurrently
 *   from any threads.
 * - Calls on one world (and on its colliders and actors) must not overlap: the host
 *   serializes them. Overlap is a host bug, but it is detected, not raced: every call holds
 *   its world for its whole length (taken in one atomic step with the id check), and a call
 *   that finds the world held by another call (any thread, or a callback inside a step)
 *   returns vpStatus_Busy naming that call, and changes nothing. vpWorldDestroy is such a
 *   call: it never frees a world another call is using.
 * - The task callbacks in vpWorldDef are invoked only from inside vpWorldStep (and the
 *   creation calls that precompute data), on the thread that called it; tasks may then run
 *   on any host threads. Log callbacks may be invoked from any thread that is running a
 *   VolPhys call, including task threads, and must be thread-safe.
 * - vpSetAllocator and vpSetLogCallback are process-wide: call them before the first world
 *   is created (vpSetAllocator returns vpStatus_Busy while any world exists).
 * - During a step nothing the host owns is written; results are read afterwards through
 *   the getters into host buffers.
 * - Scene queries (vpWorldRaycast and the rest) may be called from any thread outside a
 *   step; they hold the world like any other call, so queries on one world run one at a
 *   time (an overlapping one is Busy), and queries on different worlds run concurrently.
 */
#ifndef VOLPHYS_H
#define VOLPHYS_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#  if defined(VP_BUILDING_LIBRARY)
#    define VP_API __declspec(dllexport)
#  else
#    define VP_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__)
#  define VP_API __attribute__((visibility("default")))
#else
#  define VP_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- version */

#define VP_VERSION_MAJOR 0
#define VP_VERSION_MINOR 8
#define VP_VERSION_PATCH 0
/* Major changes break the ABI; minor ones only add. */
#define VP_HEADER_VERSION ((VP_VERSION_MAJOR << 16) | (VP_VERSION_MINOR << 8) | VP_VERSION_PATCH)

typedef struct vpVersion {
  int32_t major, minor, patch;
} vpVersion;

VP_API vpVersion vpGetVersion(void);

/* ---------------------------------------------------------------- status */

typedef enum vpStatus {
  vpStatus_Ok = 0,
  vpStatus_InvalidArgument = 1, /* a value out of range, NaN, malformed; the message names it */
  vpStatus_InvalidId = 2,       /* null, stale, foreign, or of another kind */
  vpStatus_OutOfMemory = 3,     /* the host allocator or the system refused memory or threads;
                                   nothing changed (a step: that actor's step was undone) */
  vpStatus_Unsupported = 4,     /* valid, but not something this build or version does */
  vpStatus_IoError = 5,         /* a file is missing, unreadable or not a regular file */
  vpStatus_ParseError = 6,      /* a file's content is malformed, or crashed or hung its
                                   importer */
  vpStatus_Busy = 7,            /* another call holds the world (see the threading contract),
                                   or vpSetAllocator while worlds exist */
  vpStatus_Diverged = 8,        /* reserved: divergence is reported in vpActorStats.diverged */
  vpStatus_VersionMismatch = 9, /* header and library, or a struct's structSize, disagree */
  vpStatus_Internal = 10,       /* a bug in VolPhys: please report the message */
  vpStatus_PhaseFailed = 11,    /* vpWorldStep only: the step completed what it could, but a phase
                                   of some actor failed (vpActorStats.failedPhases says which, the
                                   message and the log say why); the world stays steppable */
  vpStatus_NotConverged = 12    /* an iterative request (vpDeformableSolveStatic) stopped above its
                                   tolerance; the message says how far it got; nothing changed */
} vpStatus;

/* Message of the last failing call on this thread ("" if none). */
VP_API const char* vpGetLastError(void);
VP_API const char* vpStatusName(vpStatus status);

/* Checks that the library was built from a header compatible with the one the caller
 * compiled against (same major, library minor >= header minor). Use vpCheckVersion(). */
VP_API vpStatus vpCheckHeaderVersion(uint32_t headerVersion, uint32_t worldDefSize);

/* ---------------------------------------------------------------- math */

typedef struct vpVec3 {
  float x, y, z;
} vpVec3;

/* Unit quaternion, w last (as Bullet and most engines store it). */
typedef struct vpQuat {
  float x, y, z, w;
} vpQuat;

typedef struct vpTransform {
  vpVec3 position;
  vpQuat rotation;
} vpTransform;

/* ---------------------------------------------------------------- hooks */

/* Allocator: alignment is a power of two <= 64. Must be thread-safe. Routes VolPhys' bulk
 * simulation arrays and Bullet's allocations; small bookkeeping may use the C++ heap. It may
 * return NULL: the call that needed the memory returns vpStatus_OutOfMemory and changes
 * nothing (creation) or undoes the actor's step (vpWorldStep). Bullet cannot take a refusal
 * part way, so a block it needed comes from the system heap for the moment: a creation call is
 * then undone (OutOfMemory); inside a step the step goes on and the world logs a warning. */
typedef void* vpAllocFn(size_t size, size_t alignment, void* userContext);
typedef void vpFreeFn(void* memory, void* userContext);
/* NULL functions restore the default (aligned malloc/free). Busy while any world exists. */
VP_API vpStatus vpSetAllocator(vpAllocFn* allocFn, vpFreeFn* freeFn, void* userContext);

typedef enum vpLogLevel {
  vpLogLevel_Debug = 0,
  vpLogLevel_Info = 1,
  vpLogLevel_Warning = 2,
  vpLogLevel_Error = 3,
  vpLogLevel_Off = 4
} vpLogLevel;
typedef void vpLogFn(vpLogLevel level, const char* message, void* userContext);
/* NULL restores the default (warnings and errors to stderr). */
VP_API vpStatus vpSetLogCallback(vpLogFn* logFn, void* userContext, vpLogLevel minLevel);

/* Task system, in the style of Box2D v3. VolPhys splits work into `itemCount` items whose
 * boundaries do not depend on the worker count (so results are bitwise identical for any
 * worker count). The host runs task(start, end, workerIndex, taskContext) over sub-ranges
 * covering [0, itemCount), each at least minRange long, possibly in parallel, with
 * workerIndex < vpWorldDef.workerCount. enqueueTask may run everything inline and return
 * NULL; otherwise it returns a handle that finishTask waits for. */
typedef void vpTaskFn(int32_t startIndex, int32_t endIndex, uint32_t workerIndex, void* taskContext);
typedef void* vpEnqueueTaskFn(vpTaskFn* task, int32_t itemCount, int32_t minRange, void* taskContext,
                              void* userContext);
typedef void vpFinishTaskFn(void* userTask, void* userContext);

/* Monotonic clock in seconds used for the frame budget. NULL means the system's steady
 * clock. Hosts with their own frame timer (and tests, replays, lockstep games) can inject
 * one. An injected clock is only called from the thread inside vpWorldStep, in an order
 * that does not depend on the worker count: independent actors then run one after another
 * (each still parallel inside) rather than side by side, so a clock whose readings are
 * deterministic makes a budgeted run bitwise the same for any worker count. It need not be
 * thread-safe. */
typedef double vpClockFn(void* userContext);

/* ---------------------------------------------------------------- ids */

typedef struct vpWorldId {
  uint16_t index1; /* slot + 1; 0 = null */
  uint16_t generation;
} vpWorldId;

typedef struct vpColliderId {
  uint32_t index1; /* slot + 1; 0 = null */
  uint32_t generation;
  vpWorldId world;
} vpColliderId;

typedef struct vpDeformableId {
  uint32_t index1; /* slot + 1; 0 = null */
  uint32_t generation;
  vpWorldId world;
} vpDeformableId;

typedef struct vpFluidId {
  uint32_t index1; /* slot + 1; 0 = null */
  uint32_t generation;
  vpWorldId world;
} vpFluidId;

VP_API int vpWorldIdIsNull(vpWorldId id);
VP_API int vpColliderIdIsNull(vpColliderId id);
VP_API int vpDeformableIdIsNull(vpDeformableId id);
VP_API int vpFluidIdIsNull(vpFluidId id);

/* ---------------------------------------------------------------- world */

/* Where the deformables' implicit solves run (README, "The GPU path"). On a CUDA device each
 * solve is CG with block-Jacobi (the multigrids run on the CPU only); assembly, contacts and
 * the fluids stay on the CPU. Auto takes CUDA when this library was built with it and a device
 * is usable, else the CPU. Cuda without a usable device is refused by vpWorldCreate; a device
 * failure later moves that deformable back to the CPU (logged). Block-Jacobi needs many more
 * iterations than the CPU's multigrid for the same residual, each far cheaper (README, "The
 * GPU path"): raise solverMaxIterations on the device, or its solves stop at the cap above
 * their tolerance. The default is the CPU: its
 * results are the same bits on every machine, and the device's are not. vpActorStats.device
 * says where each actor ran. */
typedef enum vpDevice {
  vpDevice_Auto = 0,
  vpDevice_Cpu = 1,
  vpDevice_Cuda = 2
} vpDevice;

typedef struct vpWorldDef {
  uint32_t structSize;
  vpVec3 gravity;              /* default (0, -9.81, 0) */
  int32_t workerCount;         /* worker threads incl. the caller, 1..64; default 1. The built-in
                                  pool stops handing work to its other threads while the machine
                                  has no core free for them (other processes busy; Linux, from
                                  the threads' scheduler run delay) and tries again later, so
                                  preempted workers do not hold up frame after frame; results
                                  are the same either way. */
  float frameBudgetMs;         /* wall time one vpWorldStep may take; 0 = unlimited; default 16.
                                  The frame plan (docs/choices.md, "Frame budget"): the Bullet step runs
                                  first (not divisible). Deformables then run by priority (higher
                                  first, equal ones in slot order); each solve stops at its share
                                  only once its residual is at or below its targetResidual (the
                                  accuracy floor), else at the frame's end less what the later
                                  floors need. When floors do not fit, the lowest-priority
                                  deformable steps every k-th frame with k * dt (k <= 8), never
                                  below its floor; one within reach of a dynamic rigid body steps
                                  every frame, one in a two-way liquid when the liquid completes
                                  a step (both held to their floors). Fluids take what is left, by priority: a fluid
                                  step is a sequence of slices that may span frames (each step
                                  simulates the time since the last), readers see the last
                                  completed step, and slicing never changes results. A slice
                                  starts only when the time left covers its measured cost;
                                  slabs of grid work shrink until one lasts about 1/8 of the
                                  budget on this machine. Guarantee: a step exceeds the budget
                                  by at most one slice (a CG iteration or one stage or slab of
                                  a fluid step) beyond its estimate. Its limit: a single slice
                                  cannot be cut, and when the floors and the rate caps cannot
                                  fit (a fluid step spanning 8 frames must finish; a deformable
                                  at k = 8 reaches its floor), the step overruns and
                                  vpStepStats.budgetInfeasible says so. Time the threads wait
                                  for a CPU (other processes busy) stretches a slice and is not
                                  bounded. */
  float rigidMaxSubstep;       /* Bullet sub-step length bound in seconds; default 1/120 */
  vpEnqueueTaskFn* enqueueTask;/* both NULL: built-in thread pool with workerCount threads */
  vpFinishTaskFn* finishTask;
  void* userTaskContext;
  vpClockFn* clock;            /* NULL: steady clock */
  void* clockContext;
  void* userData;
  int32_t device;              /* a vpDevice; default vpDevice_Cpu */
} vpWorldDef;

VP_API vpWorldDef vpDefaultWorldDef(void);
VP_API vpStatus vpWorldCreate(const vpWorldDef* def, vpWorldId* outWorld);
VP_API vpStatus vpWorldDestroy(vpWorldId world);
VP_API vpStatus vpWorldIsValid(vpWorldId world); /* Ok or InvalidId */
VP_API vpStatus vpWorldSetGravity(vpWorldId world, vpVec3 gravity);
VP_API vpStatus vpWorldGetGravity(vpWorldId world, vpVec3* outGravity);
VP_API vpStatus vpWorldSetFrameBudget(vpWorldId world, float frameBudgetMs);

/* Advances everything by dt seconds (0 < dt <= 1) under the world's frame budget.
 * OutOfMemory: an actor's step ran out of memory and was undone (that actor is as before the
 * step, a fluid at its last completed step); the other actors stepped, and the world can be
 * stepped and destroyed as usual. PhaseFailed: a part of some actor's step failed (a fluid's
 * fractions, projection, level-set upkeep, velocity extrapolation or viscosity solve); the
 * step went on without it, the message names the actor and the vpPhase, and
 * vpActorStats.failedPhases flags it. */
VP_API vpStatus vpWorldStep(vpWorldId world, float dt);

/* Adds the colliders (and, later, actors) of a JSON scene file to the world; the scene's
 * optional "world" block sets gravity and budget. All-or-nothing: on error nothing is
 * added and the message gives the JSON path of the problem. */
VP_API vpStatus vpWorldLoadScene(vpWorldId world, const char* path);

/* ---------------------------------------------------------------- stats */

typedef enum vpPhase {
  vpPhase_Rigid = 0,     /* Bullet step */
  vpPhase_Corotate = 1,  /* deformables: rotations and element forces */
  vpPhase_Assemble = 2,
  vpPhase_Contacts = 3,
  vpPhase_Solve = 4,
  vpPhase_Embed = 5,     /* render-mesh update */
  vpPhase_Advect = 6,    /* fluids */
  vpPhase_Forces = 7,
  vpPhase_Fractions = 8,
  vpPhase_Pressure = 9,
  vpPhase_Surface = 10,
  vpPhase_Viscosity = 11, /* fluids with a kinematic viscosity > 0: the implicit diffusion solve */
  vpPhase_Coupling = 12, /* fluids: the two-way coupling's work, the face fractions of deformables
                            that moved and the loads on dynamic bodies and deformables (the
                            fractions of rigid colliders stay in vpPhase_Fractions);
                            deformables: taking the fluids' loads and refreshing the surface the
                            fluids see */
  vpPhase_Count = 13
} vpPhase;

#define VP_MAX_PHASES 16

typedef struct vpPhaseStats {
  float ms;
  int32_t iterations; /* solver iterations, 0 for non-iterative phases */
  float residual;     /* final relative residual, 0 if not applicable */
  int32_t budgetCut;  /* 1 if the phase stopped early because the budget was spent */
} vpPhaseStats;

typedef enum vpActorKind {
  vpActorKind_Rigid = 0, /* the world's Bullet step as a whole */
  vpActorKind_Deformable = 1,
  vpActorKind_Fluid = 2
} vpActorKind;

typedef struct vpActorStats {
  uint32_t structSize;
  vpActorKind kind;
  uint32_t index1;    /* the actor id's index1 (0 for the rigid pseudo-actor) */
  float totalMs;
  int32_t diverged;   /* the step blew up (non-finite or absurd speeds, or an energy rise its
                         work does not explain) and was undone: a deformable or rigid body is
                         back to its state before the step (for an energy rise of the rigid
                         bodies, all of them), a fluid to its last completed step
                         (docs/choices.md, "Divergence guard") */
  vpPhaseStats phases[VP_MAX_PHASES]; /* indexed by vpPhase */
  float simulatedDt;  /* seconds this step advanced the actor: 0 unless a step completed in it;
                         the frames' dt since its last step when its step spanned frames or
                         its rate was lowered */
  int32_t interval;   /* frames per step (>= 1): a deformable steps every interval-th frame with
                         interval * dt; a fluid's last completed step spanned interval frames */
  int32_t completedStep; /* 1 if a step of this actor completed in this frame */
  float progress;     /* fluid: fraction of its current step done at the end of this frame, 1 when
                         it completed (readers see the last completed step) */
  int32_t slices;     /* slices of this actor's work run in this frame */
  float residual;     /* final relative residual of its iterative solve in this frame */
  int32_t priority;   /* the def's priority */
  int32_t floorMissed; /* deformable: 1 if the budget stopped its solve above its targetResidual */
  uint32_t failedPhases; /* bit (1 << p) set: phase p (vpPhase) hit an error in this frame and the
                            step went on without it; vpWorldStep then returned PhaseFailed */
  int32_t device;     /* where its solve ran in this frame: vpDevice_Cuda for a deformable solved on
                         the device, else vpDevice_Cpu */
} vpActorStats;

typedef struct vpStepStats {
  uint32_t structSize;
  uint64_t stepIndex;  /* number of completed steps */
  float dt;
  float totalMs;
  float budgetMs;      /* the budget this step ran under (0 = unlimited) */
  int32_t budgetCut;   /* any phase was cut */
  int32_t actorCount;  /* entries available through vpWorldGetActorStats */
  int32_t colliderCount;
  int32_t rigidSubsteps;
  int32_t fluidInterval; /* the largest vpActorStats.interval among the fluids: under a tight
                            budget a fluid steps every interval frames (1 = every step; docs/choices.md) */
  float overBudgetMs;  /* how far totalMs went past budgetMs; 0 when within it or unlimited */
  int32_t budgetInfeasible; /* 1 if the actors' accuracy floors and minimum rates did not fit the
                               budget: some actor ran at its interval cap */
  float maxSliceMs;    /* the longest single slice of work in this frame */
} vpStepStats;

VP_API vpStepStats vpDefaultStepStats(void);
VP_API vpActorStats vpDefaultActorStats(void);
/* Statistics of the last completed step. */
VP_API vpStatus vpWorldGetStepStats(vpWorldId world, vpStepStats* outStats);
/* Per-actor statistics of the last step; actorIndex in [0, actorCount). Entry 0 is the rigid
 * pseudo-actor (the Bullet step). */
VP_API vpStatus vpWorldGetActorStats(vpWorldId world, int32_t actorIndex, vpActorStats* outStats);

/* ---------------------------------------------------------------- collision filtering */

/* Every collider, deformable and fluid has a filter. Two of them meet when each one's
 * categoryBits share a bit with the other's maskBits (Box2D's rule); every value is valid
 * (categoryBits = 0 meets nothing). Default {1, 0xFFFFFFFF}: everything meets everything.
 * Where it applies: rigid pairs in Bullet (two bodies of which neither is dynamic never
 * collide); a deformable's contacts with colliders; a fluid's solid boundaries (its face
 * fractions, and the pressure loads it puts on dynamic bodies) from colliders. Deformables and
 * fluids do not act on each other yet, so their bits matter only against colliders.
 * vpXxxSetCollisionFilter takes effect from the next step (for a fluid, from the next fluid
 * step that begins). */
typedef struct vpCollisionFilter {
  uint32_t categoryBits;
  uint32_t maskBits;
} vpCollisionFilter;

/* ---------------------------------------------------------------- colliders */

typedef enum vpBodyType {
  vpBodyType_Static = 0,
  vpBodyType_Kinematic = 1, /* moved by the host: target pose or velocity */
  vpBodyType_Dynamic = 2
} vpBodyType;

typedef enum vpShapeType {
  vpShapeType_Sphere = 0,       /* radius */
  vpShapeType_Box = 1,          /* halfExtents */
  vpShapeType_Capsule = 2,      /* radius, halfHeight of the cylindrical part, along local Y */
  vpShapeType_Cylinder = 3,     /* radius, halfHeight, along local Y */
  vpShapeType_Plane = 4,        /* normal, offset: points x with dot(normal, x) <= offset are solid */
  vpShapeType_ConvexHull = 5,   /* points, pointCount */
  vpShapeType_TriangleMesh = 6  /* points + indices, or meshFile */
} vpShapeType;

typedef struct vpShapeDef {
  uint32_t structSize;
  vpShapeType type;
  float radius;
  float halfHeight;
  vpVec3 halfExtents;
  vpVec3 normal;
  float offset;
  const float* points;     /* xyz triples, pointCount of them (copied) */
  int32_t pointCount;
  const int32_t* indices;  /* triangle vertex indices, 3 * triangleCount (copied) */
  int32_t triangleCount;
  const char* meshFile;    /* any format assimp reads; used when points == NULL (see below) */
  vpVec3 meshScale;        /* applied to points or file vertices; default (1,1,1) */
} vpShapeDef;

typedef struct vpColliderDef {
  uint32_t structSize;
  vpBodyType bodyType;
  vpShapeDef shape;
  vpTransform pose;
  vpVec3 linearVelocity;
  vpVec3 angularVelocity;
  float mass;            /* dynamic bodies only, > 0; default 1 */
  float friction;        /* >= 0; default 0.5 */
  float restitution;     /* 0..1; default 0 */
  float linearDamping;   /* 0..1; default 0 */
  float angularDamping;  /* 0..1; default 0.05 */
  void* userData;
  vpCollisionFilter filter;
} vpColliderDef;

VP_API vpShapeDef vpDefaultShapeDef(void);
VP_API vpColliderDef vpDefaultColliderDef(void);
VP_API vpStatus vpColliderCreate(vpWorldId world, const vpColliderDef* def, vpColliderId* outCollider);
VP_API vpStatus vpColliderDestroy(vpColliderId collider);
VP_API vpStatus vpColliderIsValid(vpColliderId collider); /* Ok or InvalidId */
VP_API vpStatus vpColliderGetPose(vpColliderId collider, vpTransform* outPose);
/* Teleports the body (any type). Clears a pending kinematic target. */
VP_API vpStatus vpColliderSetPose(vpColliderId collider, const vpTransform* pose);
/* The velocity the body moved with in the last step. What deformables pushed on a dynamic body
 * in that step acts on it over the next one, as their contacts' load. */
VP_API vpStatus vpColliderGetVelocity(vpColliderId collider, vpVec3* outLinear, vpVec3* outAngular);
/* Dynamic: sets the velocity. Kinematic: the body moves with this velocity each step until
 * changed or a target is set. Static: InvalidArgument. */
VP_API vpStatus vpColliderSetVelocity(vpColliderId collider, vpVec3 linear, vpVec3 angular);
/* Kinematic only: the body reaches `target` at the end of the next step, moving with the
 * constant velocity that gets it there (this is what deformables and fluids see). */
VP_API vpStatus vpColliderSetKinematicTarget(vpColliderId collider, const vpTransform* target);
/* Pushing a dynamic body (static and kinematic ones: InvalidArgument). A force or torque acts
 * during the whole next vpWorldStep, on each of its rigid sub-steps, then is cleared; several
 * given before one step add up. An impulse changes the velocity at once (dv = impulse / mass).
 * `point` is where a force or impulse acts, in world space; NULL means the body's origin, which
 * is its centre of mass (a force there adds no torque). Torques and angular impulses are in
 * world axes. Magnitudes above 1e14 (SI units) or not finite are InvalidArgument. Each call
 * wakes the body. */
VP_API vpStatus vpColliderApplyForce(vpColliderId collider, vpVec3 force, const vpVec3* point);
VP_API vpStatus vpColliderApplyTorque(vpColliderId collider, vpVec3 torque);
VP_API vpStatus vpColliderApplyImpulse(vpColliderId collider, vpVec3 impulse, const vpVec3* point);
VP_API vpStatus vpColliderApplyAngularImpulse(vpColliderId collider, vpVec3 angularImpulse);

/* A body's material and mass at run time, validated as in vpColliderDef (the same fields and
 * ranges); a failed set changes nothing. `mass` is used by dynamic bodies only (its inertia is
 * recomputed from the shape); get returns 0 for the others. Set structSize =
 * sizeof(vpBodyProperties) for both calls (or start from vpColliderGetProperties). */
typedef struct vpBodyProperties {
  uint32_t structSize;
  float mass;
  float friction;
  float restitution;
  float linearDamping;
  float angularDamping;
} vpBodyProperties;
VP_API vpStatus vpColliderGetProperties(vpColliderId collider, vpBodyProperties* outProperties);
VP_API vpStatus vpColliderSetProperties(vpColliderId collider, const vpBodyProperties* properties);

/* Sleeping: Bullet puts a dynamic body that stays slow for a while to sleep until something
 * touches or pushes it. Setting sleeping != 0 stops the body (velocities zeroed) and puts it to
 * sleep; 0 wakes it. Static and kinematic bodies never sleep (set: InvalidArgument). */
VP_API vpStatus vpColliderIsSleeping(vpColliderId collider, int32_t* outSleeping);
VP_API vpStatus vpColliderSetSleeping(vpColliderId collider, int32_t sleeping);
VP_API vpStatus vpColliderGetCollisionFilter(vpColliderId collider, vpCollisionFilter* outFilter);
VP_API vpStatus vpColliderSetCollisionFilter(vpColliderId collider, vpCollisionFilter filter);
VP_API vpStatus vpColliderGetBodyType(vpColliderId collider, vpBodyType* outType);
VP_API vpStatus vpColliderGetUserData(vpColliderId collider, void** outUserData);
/* A triangle mesh of the collider's shape in its local frame, for drawing and export (place
 * it with vpColliderGetPose). Round shapes are tessellated; a plane becomes a square 20 m on a
 * side centred on the point of the plane nearest the local origin. Normals point out of the
 * solid, triangles are counter-clockwise seen from outside (triangle meshes keep their own
 * winding). Any output may be NULL; capacities are in vertices and triangles. */
VP_API vpStatus vpColliderGetShapeMeshSize(vpColliderId collider, int32_t* outVertexCount,
                                           int32_t* outTriangleCount);
VP_API vpStatus vpColliderGetShapeMesh(vpColliderId collider, float* outPositions, float* outNormals,
                                       int32_t vertexCapacity, int32_t* outTriangles, int32_t triangleCapacity);
/* Number of colliders and their ids, in slot order (stable while none is destroyed). */
VP_API vpStatus vpWorldGetColliderCount(vpWorldId world, int32_t* outCount);
VP_API vpStatus vpWorldGetColliders(vpWorldId world, vpColliderId* outIds, int32_t capacity, int32_t* outCount);
/* Scene files may name colliders; finds the first one with that name. */
VP_API vpStatus vpWorldFindCollider(vpWorldId world, const char* name, vpColliderId* outCollider);
/* The collider's name from its scene file ("" when it has none) as a NUL-terminated string.
 * *outLength = the bytes it needs, the terminator included. buffer NULL with capacity 0 asks
 * only for the length; capacity < that length: vpStatus_InvalidArgument, *outLength set,
 * nothing written. (vpDeformableGetName and vpFluidGetName work the same way.) */
VP_API vpStatus vpColliderGetName(vpColliderId collider, char* buffer, int32_t capacity, int32_t* outLength);

/* ---------------------------------------------------------------- deformables */

/* How a surfaceFile becomes tets. Stuffing (isosurface stuffing, Labelle & Shewchuk 2007) fills
 * the surface with tets whose boundary vertices lie on it and are then moved up to half a cell
 * off it so that the boundary keeps the enclosed volume (its triangles are chords of a curved
 * surface), and the paper proves its dihedral angles within 10.7 to 164.8 degrees, which the
 * move keeps (this implementation's warp order is its own: docs/choices.md;
 * vpDeformableGetMeshQuality reports a mesh's range); parts thinner than about a cell and a
 * half may lose pieces or vanish. Voxel keeps every cube of the grid the surface touches (6
 * tets each): it always covers the surface but swells thin parts by up to a cell. */
typedef enum vpSurfaceMesher {
  vpSurfaceMesher_Default = 0,  /* Stuffing */
  vpSurfaceMesher_Stuffing = 1,
  vpSurfaceMesher_Voxel = 2
} vpSurfaceMesher;

/* A deformable volume: corotational linear elasticity on a tetrahedral mesh, implicit
 * (backward Euler), solved by preconditioned CG within the frame budget. Nodes are the mesh
 * vertices (same indices) followed, for degree > 1, by the shared edge and face control
 * points; pinning all vertices of an edge or face pins its control points. Give exactly one
 * mesh source: vertices + tets, tetFile, or surfaceFile. Meshes are in the actor's local
 * frame; `pose` places them. The render mesh is renderVertices/renderTriangles if given, the
 * surface file's own mesh for surfaceFile, else the boundary of the tet mesh; it is embedded
 * in the tets and follows them. */
/* Contact of a deformable with itself: its surface nodes against its own boundary triangles,
 * away from each node's own elements. Auto: on for a mesh with more than one layer of elements
 * (a corner node inside it), off for a single layer (a sheet, whose two sides are closer than
 * the contacts' reach). Contacts with other deformables follow `filter` either way. */
typedef enum vpSelfCollision {
  vpSelfCollision_Auto = 0,
  vpSelfCollision_Off = 1,
  vpSelfCollision_On = 2
} vpSelfCollision;

typedef struct vpDeformableDef {
  uint32_t structSize;
  int32_t degree;               /* element degree: 1 linear, 2 quadratic, 3 cubic (Bernstein–Bézier) */
  const float* vertices;        /* xyz per node, vertexCount of them (copied) */
  int32_t vertexCount;
  const int32_t* tets;          /* 4 node indices per tet, tetCount of them (copied) */
  int32_t tetCount;
  const char* tetFile;          /* Gmsh .msh (2.2 / 4.1 ASCII), TetGen .node/.ele, legacy VTK */
  const char* surfaceFile;      /* closed surface, any format assimp reads: tetrahedralized by
                                   surfaceMesher; one that is not closed (after welding equal
                                   positions) is InvalidArgument naming an open edge */
  int32_t voxelResolution;      /* for surfaceFile, either mesher: lattice cells along the
                                   longest axis of the surface's bounding box, 1..48 (finer
                                   meshes come as tetFile); default 12 */
  const float* renderVertices;  /* optional explicit render mesh (copied) */
  int32_t renderVertexCount;
  const int32_t* renderTriangles;
  int32_t renderTriangleCount;
  vpTransform pose;
  vpVec3 linearVelocity;
  float youngsModulus;          /* Pa, default 1e6 */
  float poissonRatio;           /* (-0.999, 0.4999), default 0.3 */
  float density;                /* kg/m^3, default 1000 */
  float massDamping;            /* Rayleigh alpha (1/s), default 0 */
  float stiffnessDamping;       /* Rayleigh beta (s), default 0.01 */
  float friction;               /* Coulomb coefficient against colliders, default 0.5 */
  float solverTolerance;        /* relative residual, default 1e-3 */
  int32_t solverMaxIterations;  /* default 200 */
  void* userData;
  float targetResidual;         /* the accuracy floor: the relative residual of the implicit solve
                                   that the frame plan guarantees before fluids get time; finite, in
                                   [solverTolerance, 1]; default 1e-2 */
  int32_t priority;             /* -1000000..1000000: higher is served first when the frame budget
                                   is short (deformables and fluids share the scale); default 0 */
  vpCollisionFilter filter;     /* the colliders and the other deformables it contacts */
  int32_t surfaceMesher;        /* for surfaceFile: a vpSurfaceMesher; default vpSurfaceMesher_Default */
  int32_t selfCollision;        /* a vpSelfCollision; default vpSelfCollision_Auto */
  int32_t meshGrading;          /* for surfaceFile with the stuffing mesher: levels of coarsening
                                   inside the body, 0..8; the tets stay of the lattice's size near
                                   the surface and grow by up to 2^meshGrading deep inside (an
                                   octree-graded lattice, fewer tets for the same surface detail,
                                   same dihedral angle bounds). 0 (default): a uniform lattice.
                                   The voxel mesher ignores it. */
} vpDeformableDef;

VP_API vpDeformableDef vpDefaultDeformableDef(void);
VP_API vpStatus vpDeformableCreate(vpWorldId world, const vpDeformableDef* def, vpDeformableId* outDeformable);
VP_API vpStatus vpDeformableDestroy(vpDeformableId deformable);
VP_API vpStatus vpDeformableIsValid(vpDeformableId deformable); /* Ok or InvalidId */
VP_API vpStatus vpDeformableGetCollisionFilter(vpDeformableId deformable, vpCollisionFilter* outFilter);
VP_API vpStatus vpDeformableSetCollisionFilter(vpDeformableId deformable, vpCollisionFilter filter);
VP_API vpStatus vpDeformableGetNodeCount(vpDeformableId deformable, int32_t* outCount);
/* Node positions / velocities, xyz per node, into a host array of capacity nodes. */
VP_API vpStatus vpDeformableGetPositions(vpDeformableId deformable, float* outXyz, int32_t capacity);
VP_API vpStatus vpDeformableGetVelocities(vpDeformableId deformable, float* outXyz, int32_t capacity);
VP_API vpStatus vpDeformableSetVelocities(vpDeformableId deformable, const float* xyz, int32_t nodeCount);
/* Teleport: every node to a new position (xyz per node, nodeCount = the node count), velocities
 * zeroed when resetVelocities != 0; the render mesh follows at once. Positions are checked as
 * everywhere (finite, within +-1e6 m); on failure nothing moves. */
VP_API vpStatus vpDeformableSetPositions(vpDeformableId deformable, const float* xyz, int32_t nodeCount,
                                         int32_t resetVelocities);

/* The material at run time, validated as in vpDeformableDef (same fields and ranges; a failed
 * set changes nothing); it acts from the next step. Stiffness, Poisson ratio and density
 * rebuild what depends on them (element stiffness for degree > 1, lumped masses). Set
 * structSize = sizeof(vpDeformableMaterial) or start from vpDeformableGetMaterial. */
typedef struct vpDeformableMaterial {
  uint32_t structSize;
  float youngsModulus;
  float poissonRatio;
  float density;
  float massDamping;
  float stiffnessDamping;
  float friction;
} vpDeformableMaterial;
VP_API vpStatus vpDeformableGetMaterial(vpDeformableId deformable, vpDeformableMaterial* outMaterial);
VP_API vpStatus vpDeformableSetMaterial(vpDeformableId deformable, const vpDeformableMaterial* material);
/* A force acts during the next step only; an impulse changes the velocity now. */
VP_API vpStatus vpDeformableApplyForce(vpDeformableId deformable, int32_t node, vpVec3 force);
VP_API vpStatus vpDeformableApplyImpulse(vpDeformableId deformable, int32_t node, vpVec3 impulse);
/* Pinned nodes stay where they are (zero velocity) until unpinned. All-or-nothing. */
VP_API vpStatus vpDeformablePin(vpDeformableId deformable, const int32_t* nodes, int32_t count);
VP_API vpStatus vpDeformableUnpin(vpDeformableId deformable, const int32_t* nodes, int32_t count);
/* The nodes follow the collider rigidly from their current offset in its frame (until the
 * collider is destroyed). The collider must belong to the same world. A dynamic collider is
 * pulled back: each attachment is then a stiff spring solved with the body's velocities, so the
 * two hang on each other (one way only while the deformable steps on a device or at a lowered
 * rate). */
VP_API vpStatus vpDeformableAttach(vpDeformableId deformable, const int32_t* nodes, int32_t count,
                                   vpColliderId collider);
VP_API vpStatus vpDeformableGetRenderMeshSize(vpDeformableId deformable, int32_t* outVertexCount,
                                              int32_t* outTriangleCount);
/* Any output may be NULL. Capacities are in vertices and triangles. */
VP_API vpStatus vpDeformableGetRenderMesh(vpDeformableId deformable, float* outPositions, float* outNormals,
                                          int32_t vertexCapacity, int32_t* outTriangles, int32_t triangleCapacity);
/* Statistics of this actor in the last step (zeros before the first). */
VP_API vpStatus vpDeformableGetStats(vpDeformableId deformable, vpActorStats* outStats);
/* The simulation mesh as created: the smallest and largest dihedral angle of its tets (degrees;
 * the six angles at a tet's edges), the tets' total volume, and the volume its render surface
 * encloses (the surface file's mesh, the given render mesh, else the tets' boundary; m^3, in
 * the scene's scale). A mesher that swells thin parts shows as tetVolume above surfaceVolume.
 * Any output may be NULL. */
VP_API vpStatus vpDeformableGetMeshQuality(vpDeformableId deformable, float* outMinDihedralDegrees,
                                           float* outMaxDihedralDegrees, float* outTetVolume,
                                           float* outSurfaceVolume);
/* Moves the deformable to its static equilibrium and leaves it there at rest (outside a step:
 * no time passes, nothing else moves): elastic forces balance gravity and the forces applied
 * for the next step (which stay pending), pinned and attached nodes held, contacts against the
 * colliders as they stand. Newton steps on the corotational elasticity with the actor's own
 * linear solver (p-multigrid for degree 2 and 3; its tolerance, and an iteration cap of ten per
 * unknown rather than solverMaxIterations, a per-frame cap), globalized by pseudo-time continuation and a
 * line search on the potential energy; a body that starts above the ground descends onto it.
 * Converged when the unbalanced force (what pins and contacts cannot carry, friction included)
 * is at most `tolerance` times the load (gravity and applied forces). maxIterations in
 * [1, 10000]; tolerance finite in (0, 1) and above the rounding floor of very stiff or thin
 * bodies (1e-4 is safe, 1e-6 often). NotConverged: the deformable is unchanged and the message
 * gives the residual reached. outIterations and outResidual (relative) may be NULL. */
VP_API vpStatus vpDeformableSolveStatic(vpDeformableId deformable, int32_t maxIterations, float tolerance,
                                        int32_t* outIterations, float* outResidual);
/* Number of deformables and their ids, in slot order (stable while none is destroyed). */
VP_API vpStatus vpWorldGetDeformableCount(vpWorldId world, int32_t* outCount);
VP_API vpStatus vpWorldGetDeformables(vpWorldId world, vpDeformableId* outIds, int32_t capacity, int32_t* outCount);
VP_API vpStatus vpWorldFindDeformable(vpWorldId world, const char* name, vpDeformableId* outDeformable);
/* The deformable's name from its scene file ("" when it has none), as vpColliderGetName. */
VP_API vpStatus vpDeformableGetName(vpDeformableId deformable, char* buffer, int32_t capacity, int32_t* outLength);

/* A tet mesh of the box [minCorner, minCorner + size] for vpDeformableDef.vertices / tets: the
 * mesher of scene files' "box" deformables. cells[0] x cells[1] x cells[2] cubes, each split
 * into 6 positively oriented tets: (cells[0]+1)(cells[1]+1)(cells[2]+1) vertices in lattice
 * order (x fastest; xyz per vertex into outVertices) and 6 cells[0] cells[1] cells[2] tets (4
 * vertex indices each into outTets). Capacities are in vertices and tets; an output array may
 * be NULL (with capacity 0), so NULL for both asks only for the counts. *outVertexCount and
 * *outTetCount (either may be NULL) are set on success, and also when a capacity is too small
 * (vpStatus_InvalidArgument, nothing else written). Each cells[k] in [1, 512], at most 2^21
 * cells in all; each side of size a length and minCorner and minCorner + size positions (the
 * ranges in the conventions above). */
VP_API vpStatus vpBoxTetMesh(vpVec3 size, const int32_t cells[3], vpVec3 minCorner, float* outVertices,
                             int32_t vertexCapacity, int32_t* outTets, int32_t tetCapacity, int32_t* outVertexCount,
                             int32_t* outTetCount);

/* ---------------------------------------------------------------- fluids */

/* A fluid actor: smoke or liquid on a MAC grid filling an axis-aligned box (the domain).
 * Colliders inside the domain are solid boundaries through the exact open fraction of each
 * grid face (cut cells): a sphere is round to the fluid, a thin slanted plate does not leak.
 * Moving colliders push the fluid with their velocity; with twoWayCoupling, the pressure
 * pushes back on dynamic colliders (buoyancy, drag), applied during the next step.
 * Each step: advection (sub-stepped by the CFL number), sources and forces, cut-cell pressure
 * projection within the frame budget (warm-started; a cut solve keeps its best iterate).
 * Grids are cell-centred with x fastest: cell (i, j, k) is at index i + nx * (j + ny * k),
 * centred at origin + cellSize * (i + 0.5, j + 0.5, k + 0.5). */

typedef enum vpFluidKind {
  vpFluidKind_Smoke = 0,  /* density and temperature carried by air; buoyancy, vorticity */
  vpFluidKind_Liquid = 1  /* a level set with a free surface under gravity */
} vpFluidKind;

typedef enum vpAdvection {
  vpAdvection_SemiLagrangian = 0, /* RK2 back-trace; stable, dissipative */
  vpAdvection_MacCormack = 1      /* with the min/max clamp; keeps more detail (default) */
} vpAdvection;

typedef enum vpDomainSide {
  vpDomainSide_Wall = 0, /* closed, motionless */
  vpDomainSide_Open = 1  /* the fluid continues outside at zero pressure; for a liquid, air is
                            outside: what flows in there is air */
} vpDomainSide;

typedef enum vpRegionType {
  vpRegionType_Box = 0,   /* centre, halfExtents (axis-aligned) */
  vpRegionType_Sphere = 1 /* centre, radius */
} vpRegionType;

/* A region in world coordinates. */
typedef struct vpFluidRegion {
  vpRegionType type;
  vpVec3 centre;
  vpVec3 halfExtents;
  float radius;
} vpFluidRegion;

/* Smoke: each step adds densityRate * dt of smoke in the region, sets the temperature there
 * and the velocity of the fluid in it. Liquid: keeps the region full of liquid moving with
 * `velocity` (densityRate and temperature unused). */
typedef struct vpFluidEmitter {
  vpFluidRegion region;
  vpVec3 velocity;
  float densityRate;
  float temperature;
} vpFluidEmitter;

typedef struct vpFluidDef {
  uint32_t structSize;
  vpFluidKind kind;                 /* default smoke */
  vpVec3 origin;                    /* the domain's low corner */
  int32_t resolution[3];            /* cells along x, y, z: each 2..1024, 2^27 in all; default 32^3 */
  float cellSize;                   /* metres; default 1/32 */
  vpDomainSide sides[6];            /* -x, +x, -y, +y, -z, +z; default all walls */
  float density;                    /* kg/m^3 (water 1000, air 1.2); scales the forces on colliders; default 1000 */
  vpAdvection advection;            /* velocity and smoke; default MacCormack. A liquid's level set
                                       is always semi-Lagrangian (MacCormack gained energy there) */
  float cflNumber;                  /* most cells moved per sub-step, 0.1..100; default 2 */
  int32_t maxSubsteps;              /* 1..64; default 4 */
  float pressureTolerance;          /* relative residual of the pressure solve; default 1e-4 */
  int32_t pressureMaxIterations;    /* default 200 */
  /* smoke */
  float ambientTemperature;         /* default 0 */
  float densityBuoyancy;            /* m/s^2 per unit density, pulls smoke down; default 0.05 */
  float thermalBuoyancy;            /* m/s^2 per unit temperature above ambient; default 1 */
  float vorticityConfinement;       /* epsilon, 0..100; default 0.2 */
  float densityDissipation;         /* 1/s; default 0 */
  float temperatureDissipation;     /* 1/s; default 0 */
  /* sources (copied) */
  const vpFluidRegion* initialLiquid; /* liquid: regions filled at creation */
  int32_t initialLiquidCount;
  const vpFluidEmitter* emitters;
  int32_t emitterCount;
  const vpFluidRegion* drains;        /* liquid: removed where these are */
  int32_t drainCount;
  int32_t twoWayCoupling;           /* pressure forces act on dynamic colliders; default 1 */
  void* userData;
  float kinematicViscosity;         /* m^2/s, 0..10 (water 1e-6, honey ~1e-2): implicit diffusion of
                                       the velocity, solids no-slip; default 0 = inviscid, no cost */
  int32_t priority;                 /* -1000000..1000000: higher is served first when the frame budget
                                       is short (as vpDeformableDef.priority); default 0 */
  vpCollisionFilter filter;         /* the colliders that bound it */
} vpFluidDef;

typedef enum vpFluidField {
  vpFluidField_SmokeDensity = 0,
  vpFluidField_Temperature = 1,
  vpFluidField_LevelSet = 2,  /* liquid: signed distance, negative inside the liquid */
  vpFluidField_Pressure = 3   /* Pa above the open sides' pressure; 0 in solids and air */
} vpFluidField;

VP_API vpFluidDef vpDefaultFluidDef(void);
VP_API vpStatus vpFluidCreate(vpWorldId world, const vpFluidDef* def, vpFluidId* outFluid);
VP_API vpStatus vpFluidDestroy(vpFluidId fluid);
VP_API vpStatus vpFluidIsValid(vpFluidId fluid); /* Ok or InvalidId */
VP_API vpStatus vpFluidGetCollisionFilter(vpFluidId fluid, vpCollisionFilter* outFilter);
VP_API vpStatus vpFluidSetCollisionFilter(vpFluidId fluid, vpCollisionFilter filter);
VP_API vpStatus vpFluidGetResolution(vpFluidId fluid, int32_t* outNx, int32_t* outNy, int32_t* outNz);
/* What the fluid was created as, so a host can draw one it did not create (a scene's). Any
 * output may be NULL. Cell (i, j, k) is centred at origin + cellSize * (i + 0.5, j + 0.5, k + 0.5). */
VP_API vpStatus vpFluidGetKind(vpFluidId fluid, vpFluidKind* outKind);
VP_API vpStatus vpFluidGetDomain(vpFluidId fluid, vpVec3* outOrigin, float* outCellSize);
/* A copy of a cell-centred field, nx * ny * nz values (capacity in values). */
VP_API vpStatus vpFluidGetField(vpFluidId fluid, vpFluidField field, float* outValues, int64_t capacity);
/* The velocity at the cell centres, xyz per cell (capacity in cells). */
VP_API vpStatus vpFluidGetVelocityGrid(vpFluidId fluid, float* outXyz, int64_t capacity);
/* The velocity at world points (trilinear from the grid; clamped to the domain). */
VP_API vpStatus vpFluidSampleVelocity(vpFluidId fluid, const vpVec3* points, int32_t count, vpVec3* outVelocities);
/* Liquid: the free surface as a triangle mesh (marching cubes of the level set, normals out
 * of the liquid), built on request from the last step. Smoke: an empty mesh. */
VP_API vpStatus vpFluidGetSurfaceMeshSize(vpFluidId fluid, int32_t* outVertexCount, int32_t* outTriangleCount);
VP_API vpStatus vpFluidGetSurfaceMesh(vpFluidId fluid, float* outPositions, float* outNormals, int32_t vertexCapacity,
                                      int32_t* outTriangles, int32_t triangleCapacity);
/* Liquid: volume in m^3 (0 for smoke). Smoke: total smoke (density * m^3; 0 for liquid). */
VP_API vpStatus vpFluidGetAmount(vpFluidId fluid, float* outAmount);

/* A fluid's forces, viscosity and domain sides at run time, validated as in vpFluidDef; they
 * act from the next fluid step that begins (a step spanning frames finishes with the values it
 * began with). Get returns the values last set. Set structSize from vpFluidGetParameters or
 * sizeof (an older header's struct, without sides, leaves them as they are). A side that
 * becomes a wall closes at that step's projection: the fluid stops flowing through it. */
typedef struct vpFluidParameters {
  uint32_t structSize;
  float ambientTemperature;
  float densityBuoyancy;
  float thermalBuoyancy;
  float vorticityConfinement;
  float densityDissipation;
  float temperatureDissipation;
  float kinematicViscosity;  /* 0 switches the viscosity solve off */
  vpDomainSide sides[6];     /* -x, +x, -y, +y, -z, +z, as vpFluidDef.sides (since 0.5) */
} vpFluidParameters;
VP_API vpStatus vpFluidGetParameters(vpFluidId fluid, vpFluidParameters* outParameters);
VP_API vpStatus vpFluidSetParameters(vpFluidId fluid, const vpFluidParameters* parameters);
/* Emitter `index` of the def's emitters (0..emitterCount-1): on or off, and its rate, velocity
 * and temperature (its region stays); from the next fluid step that begins, as above. */
VP_API vpStatus vpFluidGetEmitterCount(vpFluidId fluid, int32_t* outCount);
VP_API vpStatus vpFluidSetEmitter(vpFluidId fluid, int32_t index, int32_t enabled, float densityRate,
                                  vpVec3 velocity, float temperature);
VP_API vpStatus vpFluidGetStats(vpFluidId fluid, vpActorStats* outStats);
/* Number of fluids and their ids, in slot order (stable while none is destroyed). */
VP_API vpStatus vpWorldGetFluidCount(vpWorldId world, int32_t* outCount);
VP_API vpStatus vpWorldGetFluids(vpWorldId world, vpFluidId* outIds, int32_t capacity, int32_t* outCount);
VP_API vpStatus vpWorldFindFluid(vpWorldId world, const char* name, vpFluidId* outFluid);
/* The fluid's name from its scene file ("" when it has none), as vpColliderGetName. */
VP_API vpStatus vpFluidGetName(vpFluidId fluid, char* buffer, int32_t capacity, int32_t* outLength);

/* ---------------------------------------------------------------- contact events */

/* Deformable-collider contacts that began or ended in the last vpWorldStep, read after it (no
 * callbacks run during a step). A pair touches while at least one node of the deformable is in
 * contact with the collider (colliders it meets by the collision filter). A deformable that did
 * not step in a frame (its rate lowered by the budget) keeps its pairs; destroying a deformable
 * drops its pairs without events; a destroyed collider's pairs end at the next step (the event
 * carries its now stale id). */
typedef enum vpContactEventType {
  vpContactEventType_Begin = 0,
  vpContactEventType_End = 1
} vpContactEventType;

typedef struct vpContactEvent {
  vpContactEventType type;
  vpDeformableId deformable;
  vpColliderId collider;
  int32_t nodeCount;  /* Begin: nodes touching; End: 0 */
  vpVec3 point;       /* Begin: mean position of the touching nodes */
  vpVec3 normal;      /* Begin: their mean contact normal, out of the collider */
} vpContactEvent;

/* min(capacity, total) events of the last step into outEvents (Begin and End in the order the
 * deformables stepped), *outCount = the total. */
VP_API vpStatus vpWorldGetContactEvents(vpWorldId world, vpContactEvent* outEvents, int32_t capacity,
                                        int32_t* outCount);

/* ---------------------------------------------------------------- saved states */

/* A world's state as bytes, and back: rollback networking, checkpoints, tests. The state is
 * everything that evolves: rigid bodies (Bullet's motion and sleep state and its contact
 * points), deformables (positions, velocities, rotations, contact state, pending forces),
 * fluids (fields, face fractions, the level set's upkeep, pending loads) and the frame plan's
 * pacing and slice sizing. What the host sets is not in it (actors, shapes, materials, pins,
 * attachments, filters, fluid controls, gravity, the budget): a state goes back into the world
 * it came from, or into one built the same way (the same scene or calls), with the same actor
 * ids; anything else is refused.
 *
 * Stepping after vpWorldRestoreState gives bitwise the results of stepping after the
 * vpWorldSaveState that made the buffer (with the same dt, budget and clock readings). To make
 * that hold, saving (1) completes any fluid step in progress, running its remaining slices in
 * the call, which can cost up to a fluid step, and (2) rebuilds Bullet's internal caches from
 * the state, as a restore does. So a world that saves may differ in the last bits from one
 * that does not, and its fluids' results may come a frame or more sooner.
 *
 * The format is versioned and checksummed, for the same build of VolPhys on the same kind of
 * machine (byte order, number sizes). */

/* Writes the state into buffer and sets *outSize to its size. buffer NULL with capacity 0
 * asks only for the size (the call does the work of a save all the same, completing steps in
 * progress). capacity < the size: vpStatus_InvalidArgument, *outSize set, nothing written. */
VP_API vpStatus vpWorldSaveState(vpWorldId world, void* buffer, size_t capacity, size_t* outSize);
/* Puts back a state saved by vpWorldSaveState. The whole buffer is read and checked before
 * anything changes: a truncated, corrupted (checksum), foreign (another format, or a world
 * with other actors, ids, kinds or sizes) buffer is refused (vpStatus_ParseError,
 * vpStatus_VersionMismatch or vpStatus_InvalidArgument, the reason in vpGetLastError()) and
 * the world is unchanged. A fluid step in progress in the world is dropped. Contact events
 * and the last step's statistics are cleared; the step index is the saved one. */
VP_API vpStatus vpWorldRestoreState(vpWorldId world, const void* buffer, size_t size);

/* ---------------------------------------------------------------- scene queries */

/* Rays and overlaps against colliders, deformables and liquids. Call them outside a step, from
 * any thread; like every call on a world they hold it while they run (two at once on one world:
 * the second is Busy). Colliders are tested through Bullet's shapes; a deformable through its
 * render surface at the current positions (what the host draws); a liquid through the zero
 * level set of its last completed step. Smoke is never hit. Each object is reported at most
 * once: for a ray, its nearest hit on it. docs/choices.md, "Scene queries", has the costs. */
typedef enum vpQueryKind {
  vpQueryKind_Colliders = 1,
  vpQueryKind_Deformables = 2,
  vpQueryKind_Liquids = 4,
  vpQueryKind_All = 7
} vpQueryKind;

/* Which objects a query sees: those of `kinds` (vpQueryKind bits) that meet `filter` by the
 * collision rule above. NULL where a query takes a filter: vpDefaultQueryFilter(). */
typedef struct vpQueryFilter {
  int32_t kinds;             /* default vpQueryKind_All */
  vpCollisionFilter filter;  /* default {1, 0xFFFFFFFF} */
} vpQueryFilter;
VP_API vpQueryFilter vpDefaultQueryFilter(void);

typedef struct vpRay {
  vpVec3 origin;
  vpVec3 direction;   /* unit length (within 1e-3) */
  float maxDistance;  /* metres, >= 0 */
} vpRay;

typedef enum vpHitKind {
  vpHitKind_None = 0,  /* a batch entry whose ray hit nothing */
  vpHitKind_Collider = 1,
  vpHitKind_Deformable = 2,
  vpHitKind_Liquid = 3
} vpHitKind;

typedef struct vpQueryHit {
  vpHitKind kind;
  vpColliderId collider;      /* the object hit, by kind; the other two ids are null */
  vpDeformableId deformable;
  vpFluidId fluid;
  float distance;             /* rays: along the ray; overlaps: 0 */
  vpVec3 point;               /* rays: the hit point */
  vpVec3 normal;              /* rays: the surface's outward normal there (a liquid's: out of the
                                 liquid); a ray starting inside a liquid hits at distance 0 */
  int32_t triangle;           /* deformables: the render-mesh triangle hit; else -1 */
  vpVec3 barycentric;         /* deformables: weights of that triangle's three vertices */
  int32_t nearestNode;        /* deformables: the simulation node nearest the hit; else -1 */
} vpQueryHit;

/* The nearest hit: *outHitCount = 1 and *outHit filled, or *outHitCount = 0. */
VP_API vpStatus vpWorldRaycast(vpWorldId world, const vpRay* ray, const vpQueryFilter* filter, vpQueryHit* outHit,
                               int32_t* outHitCount);
/* Every object the ray hits, nearest first: min(capacity, total) entries are written and
 * *outCount = the total (call again with a larger buffer when it exceeds capacity). */
VP_API vpStatus vpWorldRaycastAll(vpWorldId world, const vpRay* ray, const vpQueryFilter* filter, vpQueryHit* outHits,
                                  int32_t capacity, int32_t* outCount);
/* rays[i]'s nearest hit into outHits[i] (kind vpHitKind_None for a miss); count in [0, 2^20]. */
VP_API vpStatus vpWorldRaycastBatch(vpWorldId world, const vpRay* rays, int32_t count, const vpQueryFilter* filter,
                                    vpQueryHit* outHits);
/* Every object sharing a point with the sphere or the box (pose: its centre and rotation), as
 * vpWorldRaycastAll returns them (colliders, deformables, liquids; slot order within each). */
VP_API vpStatus vpWorldOverlapSphere(vpWorldId world, vpVec3 centre, float radius, const vpQueryFilter* filter,
                                     vpQueryHit* outHits, int32_t capacity, int32_t* outCount);
VP_API vpStatus vpWorldOverlapBox(vpWorldId world, const vpTransform* pose, vpVec3 halfExtents,
                                  const vpQueryFilter* filter, vpQueryHit* outHits, int32_t capacity,
                                  int32_t* outCount);

/* ---------------------------------------------------------------- build information */

typedef struct vpBuildInfo {
  int32_t cudaCompiled;    /* the CUDA path was compiled into this library */
  int32_t cudaDeviceCount; /* CUDA devices usable now (0 without a GPU or driver) */
  int32_t hardwareThreads;
} vpBuildInfo;
VP_API vpStatus vpGetBuildInfo(vpBuildInfo* outInfo);

/* One CUDA device, device in [0, vpBuildInfo.cudaDeviceCount): what vpDevice_Auto and
 * vpDevice_Cuda use is device 0. Start from vpDefaultDeviceInfo() (it sets structSize). */
typedef struct vpDeviceInfo {
  uint32_t structSize;
  char name[256];                 /* NUL-terminated */
  uint64_t totalMemoryBytes;
  int32_t computeCapabilityMajor;
  int32_t computeCapabilityMinor;
  int32_t multiprocessorCount;
} vpDeviceInfo;
VP_API vpDeviceInfo vpDefaultDeviceInfo(void);
VP_API vpStatus vpGetDeviceInfo(int32_t device, vpDeviceInfo* outInfo);

/* ---------------------------------------------------------------- version check */

/* Returns vpStatus_Ok when this header matches the loaded library. Call once at start-up. */
static inline vpStatus vpCheckVersion(void) {
  return vpCheckHeaderVersion(VP_HEADER_VERSION, (uint32_t)sizeof(vpWorldDef));
}

#ifdef __cplusplus
}
#endif

#endif /* VOLPHYS_H */
