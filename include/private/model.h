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

struct _n_BoltLoadSet {
  BoltMesh *mesh;
  char      loadGroup[BOLTROM_NAME_LEN];
  PetscReal loadDirection[3], loadForce;
  char      preloadGroup[2][BOLTROM_NAME_LEN];
  PetscReal preloadAxis[3], preloadForce;
  PetscBool hasPreload;
  Vec       load, preload; /* the load and preload vectors, global layout */
  Vec       loadUnit;      /* the load pattern of a 1 N force */
  char      probeGroup[BOLTROM_NAME_LEN]; /* probe: displacement component at this point group */
  PetscInt  probeComponent;
  PetscInt  probeDof;               /* global DOF of the probe on its owner, -1 elsewhere */
  PetscReal probeCoord[3];
};

struct _n_BoltMaterial {
  char      name[BOLTROM_NAME_LEN];
  PetscReal E, nu, rho;
};

struct _n_BoltMaterialTable {
  PetscInt     nmat;
  BoltMaterial mat[BOLTROM_MAX_PARTS];
};

#endif
