#ifndef BOLTROM_SYS_H
#define BOLTROM_SYS_H
/* boltrom's public sys API (src/sys): services every module may use: logging, sums and gathers over ranks, files, HDF5, JSON, direct solvers. Included by boltrom.h. */

/* ------------------------------------------------------------------ log_events.c */
/* Every -log_view event and stage of boltrom (the paper's Table 2 phases: CONTACT_STIFFNESS,
   DISPLACEMENTS, CONTACT_FORCES), registered once by BoltLogRegister */
extern PetscLogEvent BOLT_EVENT_MESH_READ, BOLT_EVENT_MESH_DISTRIBUTE, BOLT_EVENT_ASSEMBLY,
                     BOLT_EVENT_CONTACT_SET_UP, BOLT_EVENT_CONTACT_ASSEMBLY, BOLT_EVENT_LOADS,
                     BOLT_EVENT_FACTORIZATION, BOLT_EVENT_STATIC_SOLVE, BOLT_EVENT_MODAL_SOLVE,
                     BOLT_EVENT_OUTPUT, BOLT_EVENT_CONTACT_STIFFNESS, BOLT_EVENT_DISPLACEMENTS,
                     BOLT_EVENT_CONTACT_FORCES, BOLT_EVENT_CONTACT_UPDATE, BOLT_EVENT_BASIS,
                     BOLT_EVENT_PROJECTION, BOLT_EVENT_KRYLOV_FACTOR, BOLT_EVENT_KRYLOV_SOLVE,
                     BOLT_EVENT_KRYLOV_ORTH, BOLT_EVENT_INTERFACE_REDUCTION, BOLT_EVENT_CONTACT_CHECK;
extern PetscLogStage BOLT_STAGE_SET_UP, BOLT_STAGE_STATIC, BOLT_STAGE_MODAL, BOLT_STAGE_OUTPUT,
                     BOLT_STAGE_PRELOAD, BOLT_STAGE_TRANSIENT;
PetscErrorCode BoltLogRegister(void);
PetscErrorCode BoltMemoryPrint(MPI_Comm, const char[]);
PetscErrorCode BoltMemoryRelease(void);

/* The JSON summary writer (src/sys/json.c); docs/outputs.md lists the keys. */
PetscErrorCode BoltJSONOpen(MPI_Comm, const char[], BoltJSON **);
PetscErrorCode BoltJSONBeginObject(BoltJSON *, const char[]);
PetscErrorCode BoltJSONEndObject(BoltJSON *);
PetscErrorCode BoltJSONInt(BoltJSON *, const char[], PetscInt);
PetscErrorCode BoltJSONReal(BoltJSON *, const char[], PetscReal);
PetscErrorCode BoltJSONString(BoltJSON *, const char[], const char[]);
PetscErrorCode BoltJSONRealArray(BoltJSON *, const char[], PetscInt, const PetscReal[]);
PetscErrorCode BoltJSONNamedValues(BoltJSON *, const char[], PetscInt, const char[][BOLTROM_NAME_LEN], const PetscInt[], const PetscReal[]);
PetscErrorCode BoltJSONClose(BoltJSON **);

/* ------------------------------------------------------------------ exact_sum.c */
/* n sums over ranks that give the same bits on any partition (two fixed grids per term) */
typedef struct _n_BoltCapacitance BoltCapacitance; /* the small system of a Woodbury correction */
PetscErrorCode BoltCapacitanceCreate(BoltCapacitance **);
PetscErrorCode BoltCapacitanceFactor(BoltCapacitance *, PetscInt, const PetscReal[], const PetscReal[], PetscInt, const PetscInt[], PetscBool *);
PetscErrorCode BoltCapacitanceFactorBlocks(BoltCapacitance *, PetscInt, const PetscReal[], const PetscReal[], PetscInt, const PetscInt[], PetscBool *);
PetscErrorCode BoltCapacitanceSolve(BoltCapacitance *, const PetscReal[], PetscReal[]);
PetscErrorCode BoltCapacitanceDestroy(BoltCapacitance **);

typedef struct _n_BoltExactSum BoltExactSum;
PetscErrorCode BoltExactSumBegin(BoltExactSum *, PetscInt, PetscReal, PetscInt);
void           BoltExactSumAdd(BoltExactSum *, const PetscReal[]);
void           BoltExactSumAddParts(BoltExactSum *, const PetscReal[], PetscReal[], PetscReal[]);
void           BoltExactSumReplaceParts(BoltExactSum *, const PetscReal[], PetscReal[], PetscReal[]);
PetscErrorCode BoltExactSumEnd(BoltExactSum *, MPI_Comm, PetscReal[]);
PetscErrorCode BoltExactSumCreate(BoltExactSum **);
PetscErrorCode BoltExactSumGetPartials(BoltExactSum *, PetscReal[]);
PetscErrorCode BoltExactSumSetPartials(BoltExactSum *, const PetscReal[]);
PetscErrorCode BoltExactSumDestroy(BoltExactSum **);

/* ------------------------------------------------------------------ gather.c */
PetscErrorCode BoltGatherAll(MPI_Comm, MPI_Datatype, const void *, PetscInt, void *, PetscInt *, PetscInt *, PetscInt *);
PetscErrorCode BoltGrowReal(PetscReal **, PetscInt *, PetscInt);

/* sys/hdf5_seal.c: a checksum of a file's datasets, written into it when complete, checked before it is read */
typedef enum { BOLT_SEAL_OK, BOLT_SEAL_NONE, BOLT_SEAL_BAD } BoltSealState;
PetscErrorCode BoltHDF5Quiet(void);
PetscErrorCode BoltHDF5Seal(const char[]);
PetscErrorCode BoltHDF5CheckSeal(const char[], BoltSealState *);
/* ------------------------------------------------------------------ sys/hdf5.c: folders, datasets */
PetscErrorCode BoltMakeDir(MPI_Comm, const char[]);
PetscErrorCode BoltMakeParentDir(MPI_Comm, const char[]);
/* sys/option_vector.c: a vector option of exactly n finite reals, inside PetscOptionsBegin/End; no option
   given a value that is not finite */
PetscErrorCode BoltOptionsRealVector(PetscOptionItems *, const char[], const char[], PetscInt, PetscReal[], PetscBool *);
PetscErrorCode BoltOptionsCheckFinite(MPI_Comm);
PetscErrorCode BoltHDF5WriteValues(PetscViewer, MPI_Comm, const char[], PetscInt, PetscInt, const PetscScalar[], PetscBool);
PetscErrorCode BoltHDF5WriteVecs(PetscViewer, MPI_Comm, PetscInt, const char *const[], Vec[], PetscBool);
PetscErrorCode BoltReadAll(PetscViewer, MPI_Comm, const char[], PetscInt *, PetscReal **);
/* Sorted keys of a keyed dataset and the permutation to their rows. */
typedef struct _n_BoltKeyIndex BoltKeyIndex;
PetscErrorCode BoltKeyIndexCreate(PetscInt, const PetscReal[], BoltKeyIndex **);
PetscInt       BoltKeyIndexSize(const BoltKeyIndex *);
PetscErrorCode BoltKeyIndexFind(BoltKeyIndex *, PetscInt, PetscInt *);
PetscErrorCode BoltKeyIndexDestroy(BoltKeyIndex **);
/* Attributes of the root group "/" of an open HDF5 viewer's file (collective, same values on every rank) */
PetscErrorCode BoltHDF5AttributeString(PetscViewer, const char[], const char[]);
PetscErrorCode BoltHDF5AttributeStrings(PetscViewer, const char[], PetscInt, const char *const[]);
PetscErrorCode BoltHDF5AttributeInt(PetscViewer, const char[], PetscInt);
PetscErrorCode BoltHDF5AttributeReals(PetscViewer, const char[], PetscInt, const PetscReal[]);

/* ------------------------------------------------------------------ solver.c */
/* Direct solvers (PREONLY + LU or Cholesky) of the analyses, the reduction and the time
   integrators; prefix NULL: not configurable from the command line. */
PetscErrorCode BoltDirectSolverSetType(KSP, PetscBool, MatSolverType);
PetscErrorCode BoltDirectSolverCreate(MPI_Comm, const char[], Mat, PetscBool, MatSolverType, KSP *);
PetscErrorCode BoltBVTolerateCancellation(BV);
PetscErrorCode BoltDirectSolverSetFromOptions(MPI_Comm, const char[], PetscBool, MatSolverType);
PetscErrorCode BoltDirectSolverFactor(KSP, PCFailedReason *);
PetscErrorCode BoltModalSetFromOptions(MPI_Comm, PetscInt, const char[]); /* analysis.c */

#endif
