#ifndef BOLTROM_MODEL_H
#define BOLTROM_MODEL_H
/* boltrom's public model API (src/model): the structure: materials, mesh, assembly, loads, linear analyses. Included by boltrom.h. */

/* ------------------------------------------------------------------ material.c */
typedef struct _n_BoltMaterial BoltMaterial;

typedef struct _n_BoltMaterialTable BoltMaterialTable;

PetscErrorCode BoltMaterialTableSetFromOptions(MPI_Comm, BoltMaterialTable *);
PetscErrorCode BoltMaterialTableFind(MPI_Comm, const BoltMaterialTable *, const char[], PetscInt *);
PetscErrorCode BoltMaterialTableDestroy(BoltMaterialTable **);

/* ------------------------------------------------------------------ mesh.c */
/* The distributed mesh, its parts and groups, and the DOF layout (3 per vertex, clamp removed). */
typedef struct {
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
} BoltMesh;

PetscErrorCode BoltMeshCreate(MPI_Comm, BoltMesh **);
PetscErrorCode BoltMeshSetFromOptions(BoltMesh *);
PetscErrorCode BoltMeshSetUp(BoltMesh *);
PetscErrorCode BoltMeshView(BoltMesh *, PetscViewer);
PetscErrorCode BoltMeshDestroy(BoltMesh **);
/* Part p's material: its name, Young's modulus [Pa], Poisson's ratio and density [kg/m^3] */
PetscErrorCode BoltMeshPartMaterial(BoltMesh *, PetscInt, const char **, PetscReal *, PetscReal *, PetscReal *);
PetscErrorCode BoltMeshHasGroup(BoltMesh *, const char[], PetscBool *);
PetscErrorCode BoltMeshCellCoordinates(BoltMesh *, PetscInt, PetscReal[24]);
PetscErrorCode BoltMeshCellDofs(BoltMesh *, PetscInt, PetscInt[24]);
PetscErrorCode BoltMeshCellVertices(BoltMesh *, PetscInt, PetscInt[8]);
PetscErrorCode BoltMeshVertexDofs(BoltMesh *, PetscInt, PetscInt[3]);
PetscErrorCode BoltMeshSetNodeValues(Vec, const PetscInt[3], const PetscScalar[3], InsertMode);
PetscErrorCode BoltMeshDofKeys(BoltMesh *, Vec, Vec *);
PetscErrorCode BoltMeshVertexOwned(BoltMesh *, PetscInt, PetscBool *);
PetscErrorCode BoltMeshGroupPoints(BoltMesh *, const char[], PetscBool, PetscInt *, PetscInt **);
PetscErrorCode BoltMeshGroupVertices(BoltMesh *, const char[], PetscBool, PetscInt *, PetscInt **);
PetscErrorCode BoltMeshFaceVertices(BoltMesh *, PetscInt, PetscInt *, PetscInt[4], PetscReal[12]);
PetscErrorCode BoltMeshFillVertexField(BoltMesh *, PetscErrorCode (*)(const PetscReal[3], PetscInt, PetscReal[3], void *), void *, Vec);

/* ------------------------------------------------------------------ assembly.c */
typedef struct _n_BoltAssembler BoltAssembler;

PetscErrorCode BoltAssemblerCreate(BoltMesh *, BoltAssembler **);
PetscErrorCode BoltAssemblerSetFromOptions(BoltAssembler *);
PetscErrorCode BoltAssemblerSetUp(BoltAssembler *);
PetscErrorCode BoltAssemblerDamping(BoltAssembler *, Mat *);
PetscErrorCode BoltAssemblerPartStiffness(BoltAssembler *, PetscInt, Mat *);
PetscErrorCode BoltAssemblerView(BoltAssembler *, PetscViewer);
PetscErrorCode BoltAssemblerGetMatrices(BoltAssembler *, Mat *, Mat *);
PetscErrorCode BoltAssemblerGetRayleigh(BoltAssembler *, PetscReal *, PetscReal *);
PetscErrorCode BoltAssemblerGetMesh(BoltAssembler *, BoltMesh **);
PetscErrorCode BoltAssemblerGetPart(BoltAssembler *, PetscInt, PetscReal *, PetscReal *, PetscInt *);
PetscErrorCode BoltAssemblerDestroy(BoltAssembler **);

/* ------------------------------------------------------------------ loads.c */
typedef struct _n_BoltLoadSet BoltLoadSet;
Vec              BoltLoadSetLoad(const BoltLoadSet *);
Vec              BoltLoadSetLoadUnit(const BoltLoadSet *);
Vec              BoltLoadSetPreload(const BoltLoadSet *);
PetscBool        BoltLoadSetHasPreload(const BoltLoadSet *);
PetscReal        BoltLoadSetPreloadForce(const BoltLoadSet *);
const char      *BoltLoadSetPreloadGroup(const BoltLoadSet *, PetscInt);
const char      *BoltLoadSetLoadGroup(const BoltLoadSet *);
PetscReal        BoltLoadSetLoadForce(const BoltLoadSet *);
const PetscReal *BoltLoadSetLoadDirection(const BoltLoadSet *);
const char      *BoltLoadSetProbeGroup(const BoltLoadSet *);
PetscInt         BoltLoadSetProbeComponent(const BoltLoadSet *);
PetscInt         BoltLoadSetProbeDof(const BoltLoadSet *);
const PetscReal *BoltLoadSetProbeCoordinates(const BoltLoadSet *);

PetscErrorCode BoltLoadSetCreate(BoltMesh *, BoltLoadSet **);
PetscErrorCode BoltLoadSetSetFromOptions(BoltLoadSet *);
PetscErrorCode BoltLoadSetSetUp(BoltLoadSet *, Vec);
PetscErrorCode BoltLoadSetProbe(BoltLoadSet *, Vec, PetscReal *);
PetscErrorCode BoltLoadSetView(BoltLoadSet *, PetscViewer);
PetscErrorCode BoltLoadSetDestroy(BoltLoadSet **);

/* ------------------------------------------------------------------ analysis.c */
PetscErrorCode BoltStaticSolve(Mat, Vec, Vec, const char[]);
PetscErrorCode BoltModalSolve(Mat, Mat, PetscInt, const char[], PetscInt *, PetscReal[]);

#endif
