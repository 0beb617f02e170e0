#ifndef BOLTROM_PRIVATE_KRYLOV_H
#define BOLTROM_PRIVATE_KRYLOV_H
/* Inside the Krylov basis (src/rom/krylov*.c): what its files share. */
#include "boltrom.h"
#include "private/boltrom_krylov.h"

PetscErrorCode KrylovSolve(BoltKrylov *kr, Mat F, BV Rhs, BV Sol, PetscInt nc);
PetscErrorCode KrylovFactor(BoltKrylov *kr, Mat M, Mat C, Mat K, Mat *Kt, KSP *ksp, Mat *F);
#endif
