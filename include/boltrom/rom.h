#ifndef BOLTROM_ROM_H
#define BOLTROM_ROM_H
/* boltrom's public rom API (src/rom): the reduced model. Included by boltrom.h. */

/* ------------------------------------------------------------------ reduction.c, rom.c */
/* The reduction's options as given (-rom_*, read by BoltROMSetFromOptions); 0 or -1 where the
   default is resolved by BoltROMSetUp */
typedef struct _n_BoltReductionOptions BoltReductionOptions;

/* The ROM file's fingerprint: typed fields, each a setting the basis depends on. */
#define BOLTROM_FINGERPRINT_FIELDS 256
typedef struct _n_BoltROMFingerprintField BoltROMFingerprintField;
typedef struct _n_BoltROMFingerprint BoltROMFingerprint;

/* The reduced model: projected matrices (replicated on every rank, small and dense), the rows
   of the basis at this rank's contact DOFs and at the probe, and the reduced contact stiffness
   kept up to date element by element. */
typedef struct _n_BoltROM BoltROM;

/* rom_update.c: the online factorisation kept across changes of the active set */
typedef struct BoltROMUpdate_s BoltROMUpdate;
PetscErrorCode BoltROMUpdateCreate(BoltROM *, BoltOperator *, PetscInt);
PetscErrorCode BoltROMUpdateSettle(BoltOperator *);
void           BoltROMUpdateSummed(BoltROMUpdate *, BoltROM *, PetscInt);
PetscErrorCode BoltROMUpdateView(BoltROMUpdate *, PetscViewer);
PetscInt       BoltROMUpdateLargestBatch(const BoltROMUpdate *);
PetscErrorCode BoltROMUpdateDestroy(BoltROMUpdate **);


/* The ROM's life cycle (rom_object.c): options read once at the start whatever -rom says (a
   scene may carry them with the ROM off), every default resolved by SetUp, which builds the ROM
   or reads a matching -rom_file; the online operator owns its caches. */
PetscErrorCode BoltROMCreate(MPI_Comm, BoltROM **);
PetscErrorCode BoltROMSetFromOptions(BoltROM *);
PetscErrorCode BoltROMSolversSetFromOptions(BoltROM *);
PetscErrorCode BoltROMCheckOptions(BoltROM *, BoltContactSet *);
PetscErrorCode BoltROMSetTraining(BoltROM *, const BoltPreloadState *, PetscInt, Vec[], const PetscBool[]);
PetscErrorCode BoltROMSetPeriodicLoad(BoltROM *, PetscBool);
PetscBool      BoltROMIsTrained(const BoltROM *);
PetscErrorCode BoltROMSetUp(BoltROM *, BoltAssembler *, BoltContactSet *, BoltLoadSet *);
PetscErrorCode BoltROMView(BoltROM *, PetscViewer);
PetscErrorCode BoltROMSummaryWrite(BoltROM *, BoltJSON *);
PetscErrorCode BoltROMGetMatrices(BoltROM *, Mat *, Mat *);
PetscErrorCode BoltROMDestroy(BoltROM **);
PetscErrorCode BoltROMGetFile(BoltROM *, const char *[], const char *[]);
PetscErrorCode BoltROMCheckFile(BoltROM *, BoltAssembler *, BoltContactSet *, BoltLoadSet *);
PetscErrorCode BoltROMGetSnapshotModes(BoltROM *, PetscInt *);
PetscBool      BoltROMVerifies(BoltROM *);
PetscErrorCode BoltROMCheckFileIntact(BoltROM *, PetscBool *);
PetscErrorCode BoltROMOperatorCreate(BoltROM *, BoltOperator **);
PetscErrorCode BoltROMSetPreloadState(BoltROM *, BoltNewmark *, PetscReal);
PetscErrorCode BoltROMCheckAtS0(BoltROM *, BoltOperator *, BoltAssembler *, BoltContactSet *, BoltLoadSet *, PetscReal *);
PetscErrorCode BoltHistoryErrors(PetscInt, const PetscReal[], const PetscReal[], PetscReal *, PetscReal *);
/* rom_field.c: the ROM's displacement in full, u = V q, while the ROM keeps its whole basis (built, or read from its file) */
PetscErrorCode BoltROMKeepBasis(BoltROM *, BV);
PetscErrorCode BoltROMHasBasis(BoltROM *, PetscBool *);
PetscErrorCode BoltROMExpand(BoltROM *, Vec, Vec);
PetscErrorCode BoltROMReleaseBasis(BoltROM *);
PetscErrorCode BoltROMBasisSave(BoltROM *, BV, BoltMesh *, PetscViewer);
PetscErrorCode BoltROMBasisEnsure(BoltROM *, BoltMesh *, Vec, PetscBool *);

#endif
