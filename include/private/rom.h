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
#endif
