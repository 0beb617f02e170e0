#ifndef BOLTROM_APP_H
#define BOLTROM_APP_H
/* boltrom's public app API (src/app): the program: output, summary, run options and stages. Included by boltrom.h. */

/* ------------------------------------------------------------------ app/output.c, app/json.c */
typedef struct _n_BoltOutput BoltOutput;

PetscErrorCode BoltOutputOpen(BoltMesh *, const char[], const char[], BoltOutput *);
PetscErrorCode BoltOutputVertexField(BoltOutput *, BoltMesh *, Vec, const char[]);
PetscErrorCode BoltOutputClose(BoltOutput *, BoltMesh *);
PetscErrorCode BoltOutputSeries(BoltOutput *, const char[], const char[], PetscInt, const PetscReal[]);
PetscErrorCode BoltOutputPairForces(BoltOutput *, const char[], BoltContactSet *, PetscInt, const PetscReal[]);
PetscErrorCode BoltOutputSnapshot(BoltOutput *, BoltMesh *, const char[], PetscInt, Vec);
PetscErrorCode BoltOutputSnapshotSeries(BoltOutput *, const char[], PetscInt, const PetscReal[], PetscBool);
PetscErrorCode BoltOutputContactState(BoltOutput *, BoltMesh *, BoltContactSet *, const unsigned char[], const char[]);
PetscErrorCode BoltOutputSnapshotStates(BoltOutput *, BoltMesh *, const char[], BoltContactSet *, PetscInt, const unsigned char[]);

/* ------------------------------------------------------------------ run.c */
/* What a run does and where it writes (main's options). */
typedef struct _n_BoltRunOptions BoltRunOptions;

PetscErrorCode BoltRunOptionsSetFromOptions(MPI_Comm, BoltRunOptions *);

/* ------------------------------------------------------------------ preflight.c */
/* Checks before any computation: options nobody reads, folders that cannot be written. */
typedef enum { BOLT_OPTIONS_BEFORE_SETUP, BOLT_OPTIONS_BEFORE_SOLVE, BOLT_OPTIONS_FINAL } BoltOptionsStage;
PetscErrorCode BoltOptionsCheckUnused(MPI_Comm, BoltOptionsStage);
PetscErrorCode BoltCheckWritableDir(MPI_Comm, const char[], const char[]);
PetscErrorCode BoltCheckWritableParent(MPI_Comm, const char[], const char[]);
PetscErrorCode BoltPreflightSetFromOptions(MPI_Comm, const BoltRunOptions *, char[]);
PetscErrorCode BoltPreflightCheck(MPI_Comm, const BoltRunOptions *, BoltROM *, const char[]);

/* ------------------------------------------------------------------ verify.c */
/* Checks of the assembled model (-verify_fields, -check_rigid) and the export of the tied and
   reduced matrices (-export_matrices) for petsc4py. */
PetscErrorCode BoltExportMatrix(Mat, const char[], const char[]);
PetscErrorCode BoltExportTied(const char[], Mat, Mat);
PetscErrorCode BoltExportReduced(const char[], BoltROM *, BoltOperator *);
PetscErrorCode BoltVerifyFields(BoltMesh *, Mat, Mat, Vec, PetscInt, Vec *, Vec *, Vec *);
PetscErrorCode BoltCheckRigid(BoltAssembler *, Vec, PetscReal[]);

/* ------------------------------------------------------------------ summary.c */
/* A run's results: its objects and the figures of its stages, written as the JSON summary
   (-summary) and the HDF5/XDMF fields. A stage that did not run leaves its pointer NULL or its
   flag false, and has no block. */
typedef struct _n_BoltSummary BoltSummary;

PetscErrorCode BoltSummaryWrite(MPI_Comm, const char[], const BoltSummary *);
PetscErrorCode BoltSummaryWriteFields(const BoltSummary *, const char[], const char[]);
/* metadata.c: the result file's root attributes and the summary's load and friction fields */
PetscErrorCode BoltSummaryWriteAttributes(const BoltSummary *, PetscViewer);
PetscErrorCode BoltSummaryWriteLoad(BoltJSON *, const BoltSummary *);

/* ------------------------------------------------------------------ run.c (stages) */
/* A run's objects, made and configured by main; sum collects what the stages report. */
typedef struct _n_BoltRun BoltRun;

PetscErrorCode BoltRunTied(BoltRun *);
PetscErrorCode BoltRunFOM(BoltRun *);
PetscErrorCode BoltRunROM(BoltRun *);

#endif
