#ifndef BOLTROM_PRIVATE_SYS_H
#define BOLTROM_PRIVATE_SYS_H
/* Inside src/sys: the bodies of its objects. */
#include "boltrom.h"

struct _n_BoltJSON {
  FILE     *fp;
  char      tmp[PETSC_MAX_PATH_LEN], final[PETSC_MAX_PATH_LEN];
  PetscInt  depth;
  PetscBool first[16];
};

struct _n_BoltExactSum {
  PetscInt   n, nalloc;
  PetscReal  sigma[2];
  PetscReal *acc; /* 2 n: the exact partial sums of the two grids */
};

struct _n_BoltKeyIndex {
  PetscInt  n, *key, *row;
};

#endif
