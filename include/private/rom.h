#ifndef BOLTROM_PRIVATE_ROM_H
#define BOLTROM_PRIVATE_ROM_H
/* Inside the reduced operator (src/rom/rom*.c): what its files share and no other module sees. */
#include "boltrom.h"

/* A point at a node pair (a changed point of the nodal quadrature, or an element's corner): its
   node pair (global DOFs of the x components on sides b and a, -1 where clamped), its name
   (4 x element key + corner) and where its record is. */
typedef struct {
  PetscInt dofB, dofA, name, pos;
} ROMPointRecord;

void ROMRowsTimes(PetscInt m, PetscInt n, const PetscScalar *A, PetscInt lda, const PetscScalar *x, PetscScalar *u);
PetscInt ROMNodePairs(PetscInt nrec, ROMPointRecord rec[], ROMPointRecord first[]);
PetscErrorCode ROMContactDisplacements(BoltOperator *op, Vec q);
PetscErrorCode ROMSetUpPairForces(BoltROM *rom, const PetscBool mayChange[]);
PetscErrorCode ROMContactStiffness(BoltOperator *op, Mat *Kc);
PetscErrorCode ROMSetUpGapRows(BoltROM *rom, const PetscBool mayChange[]);
PetscErrorCode ROMContactForces(BoltOperator *op, const PetscReal lambda[], Vec F);
PetscErrorCode ROMContactGaps(BoltOperator *op, Vec q, PetscReal gap[]);
PetscErrorCode ROMOpenTraction(BoltOperator *op, PetscReal tn[]);
PetscErrorCode BoltNodePairsDirected(BoltContactSet *c, const PetscBool mask[], PetscInt nd, const PetscReal pointDir[], PetscInt *npairsOut, PetscInt **pairsOut, PetscReal **dirOut);
PetscErrorCode BoltNodePairs(BoltContactSet *c, const PetscBool mask[], PetscInt *npairsOut, PetscInt **pairsOut);
PetscErrorCode BoltNodePairsCombination(PetscInt npair, const PetscInt pairs[], const PetscReal dirs[], PetscInt stride, const PetscReal coef[], Vec v);
PetscErrorCode BoltNodePairVectorAlong(PetscInt a, PetscInt b, const PetscReal dir[3], Vec v);
PetscErrorCode BoltNodePairVector(PetscInt a, PetscInt b, PetscInt d, Vec v);
PetscErrorCode BoltNodePairPatterns(MPI_Comm comm, PetscInt npair, const PetscInt pairs[], const PetscReal dirs[], PetscInt stride, PetscInt nsnap, Vec snap[], PetscInt kmax, PetscInt *kout, PetscReal **patterns);
PetscErrorCode BoltROMPreloadSolve(BoltAssembler *asmb, BoltContactSet *c, BoltLoadSet *loads, BoltROM *rom, PetscInt nClosed, PetscReal staticPenaltyScale, PetscBool keepActive, PetscReal openingScale, PetscInt nOpenKrylov, const BoltPreloadState *shared, PetscInt nsnap, Vec snap[], PetscInt *nextra, Vec **extrap, Vec *preload);
PetscErrorCode ROMResolveSettings(BoltROM *rom, BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads);
PetscErrorCode ROMResolveOnline(BoltROM *rom, BoltContactSet *contact);
PetscErrorCode ROMReuseFile(BoltROM *rom, BoltContactSet *contact, BoltLoadSet *loads, PetscLogDouble t0, PetscBool *reused);
PetscErrorCode ROMBuild(BoltROM *rom, BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads, PetscLogDouble t0);
PetscErrorCode ROMOnlineDestroy(BoltROM *rom);
PetscErrorCode BoltROMSave(BoltROM *rom, BV V, BoltAssembler *asmb, BoltLoadSet *loads, const char file[]);
PetscErrorCode BoltROMLoad(const char file[], BoltROM *rom, BoltContactSet *c, BoltLoadSet *loads, PetscBool *matched, char why[], size_t whylen);
PetscErrorCode BoltROMFingerprintInt(BoltROMFingerprint *, const char[], PetscInt);
PetscErrorCode BoltROMFingerprintReal(BoltROMFingerprint *, const char[], PetscReal);
PetscErrorCode BoltROMFingerprintString(BoltROMFingerprint *, const char[], const char[]);
PetscErrorCode BoltROMFingerprintScene(BoltAssembler *, BoltContactSet *, BoltLoadSet *, PetscInt, PetscReal, PetscReal, PetscInt, PetscInt, BoltROMFingerprint *);
PetscErrorCode BoltROMFingerprintWrite(const BoltROMFingerprint *, PetscViewer);
PetscErrorCode BoltROMFingerprintMatch(const BoltROMFingerprint *, PetscViewer, PetscBool *, char[], size_t);
#endif
