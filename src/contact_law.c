/* The contact law at one Gauss point: augmented Lagrangian with normal and tangential
   penalties, stick with elastic slip only (no Coulomb slip yet). Physics only. */
#include "boltrom.h"

/* Trial traction t = lambda + epsN (g.n) n + epsT (g - (g.n) n); g = u_b - u_a, n out of a. */
void BoltContactTrialTraction(const PetscReal lambda[3], const PetscReal g[3], const PetscReal n[3], PetscReal epsN, PetscReal epsT, PetscReal t[3])
{
  const PetscReal gn = g[0] * n[0] + g[1] * n[1] + g[2] * n[2];

  for (PetscInt k = 0; k < 3; k++) t[k] = lambda[k] + epsT * g[k] + (epsN - epsT) * gn * n[k];
}

/* Active where the trial normal traction is compressive. */
PetscBool BoltContactIsActive(const PetscReal t[3], const PetscReal n[3])
{
  return (t[0] * n[0] + t[1] * n[1] + t[2] * n[2]) < 0 ? PETSC_TRUE : PETSC_FALSE;
}
