#ifndef BOLTROM_INTERFACE_H
#define BOLTROM_INTERFACE_H
/* Interface reduction (CCM + JIM) and the bordered solve of the interface-reduced model. */
#include "boltrom.h"

typedef struct {
  MPI_Comm  comm;
  PetscReal s0, deflationTol;
  IS        isI, isG, isTop, isBottom; /* interface and interior DOFs (owned); halves of 2n_I vectors */
  PetscInt  nI, nIR, rankCCM, rankJIM;
  Mat       Kt, Ct, M, KtGG, KtGI, KtIG, SIR;
  KSP       kspFull, kspGG;
  BV        VIR;                       /* interface basis, n_I x n_IR */
  Vec       full, gA, gB, gC, iA, iB, eta, etaRhs;
  PetscInt  nFullSolves, nInteriorSolves;
  PetscReal tFactor, tKrylov;
} BoltInterface;

PetscErrorCode BoltInterfaceBuild(BoltContactSet *, Mat, Mat, Mat, PetscReal, PetscInt, PetscInt, PetscReal, BoltInterface **);
PetscErrorCode BoltInterfaceInputs(BoltInterface *, BV, PetscInt);
PetscErrorCode BoltInterfaceSolve(void *, BV, BV, PetscInt);
PetscErrorCode BoltInterfaceDestroy(BoltInterface **);
#endif
