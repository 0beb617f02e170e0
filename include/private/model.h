#ifndef BOLTROM_PRIVATE_MODEL_H
#define BOLTROM_PRIVATE_MODEL_H
#include "boltrom.h"

struct _n_BoltAssembler {
  BoltMesh  *mesh;
  Mat        K, M;             /* structural stiffness and consistent mass, clamp removed */
  PetscReal  rayleighAlpha, rayleighBeta;
  PetscReal  massPerPart[BOLTROM_MAX_PARTS], volumePerPart[BOLTROM_MAX_PARTS];
  PetscInt   elementsPerPart[BOLTROM_MAX_PARTS];
};

#endif
