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
  PetscBool preloadAsked;  /* a nonzero preload, or its layers, given as options */
  /* -preload_bolts: several bolts, bolt b's layers preload_<name>_lower/_upper and its force
     (-preload_<name>_force); none: the one bolt of -preload_lower_group/-preload_upper_group */
  PetscInt  nbolts;
  char      boltName[BOLTROM_MAX_BOLTS][BOLTROM_NAME_LEN];
  char      boltGroup[BOLTROM_MAX_BOLTS][2][BOLTROM_NAME_LEN];
  PetscReal boltForce[BOLTROM_MAX_BOLTS];
  Vec       boltUnit[BOLTROM_MAX_BOLTS]; /* bolt b's layer pattern for 1 N */
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

struct _n_BoltMesh {
  MPI_Comm          comm;
  char              filename[PETSC_MAX_PATH_LEN];
  char              clampGroup[BOLTROM_NAME_LEN];
  PetscBool         clamp;          /* remove the clamp group's DOFs from the global system */
  char              supportGroup[BOLTROM_NAME_LEN]; /* -support_group: nodes held in some components only ("": none) */
  PetscInt          supportComponents[3], nsupportComponents; /* the components held there, ascending */
  char              partitioner[64]; /* metis (ours, through a shell partitioner) or a PETSc type */
  DM                dm;
  PetscInt          nparts;
  char              partName[BOLTROM_MAX_PARTS][BOLTROM_NAME_LEN];
  PetscInt          partMaterial[BOLTROM_MAX_PARTS]; /* index in the material table */
  char              partMaterialMap[PETSC_MAX_PATH_LEN]; /* part:material,... */
  PetscInt          cStart, cEnd, vStart, vEnd;
  PetscInt         *cellPart;        /* part index of each local cell */
  PetscInt          pStart, pEnd;
  PetscBT           pointGhost;      /* point owned by another rank (pStart-based) */
  PetscInt         *pointOriginal;   /* number of each local point in the mesh as read (pStart-based) */
  PetscInt          partTag[BOLTROM_MAX_PARTS]; /* gmsh physical tag = label value */
  PetscInt          nverticesGlobal, ncellsGlobal, ndofsFree;
  PetscInt          edgeCut;         /* faces between cells of different ranks, after distribution */
  BoltMaterialTable *materials;  /* owned */
  Hex8Formulation   formulation;
};

#endif
