#ifndef BOLTROM_PRIVATE_SOLVE_H
#define BOLTROM_PRIVATE_SOLVE_H
/* Inside the solvers (src/solve/): what the dual loop's files share and no other module sees. */
#include "boltrom.h"

PetscErrorCode BoltDualInnerRegisterAll(void);
PetscErrorCode BoltDualFactor(BoltDual *d);
PetscErrorCode BoltDualSolveWithForces(BoltDual *d, Vec rhs0, const PetscReal lambda[], Vec q);
PetscErrorCode BoltDualGapsOf(BoltDual *d, Vec q, PetscReal gap[]);
#endif
