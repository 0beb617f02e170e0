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
typedef struct _n_BoltMesh BoltMesh;

PetscErrorCode BoltMeshCreate(MPI_Comm, BoltMesh **);
PetscErrorCode BoltMeshSetFromOptions(BoltMesh *);
PetscErrorCode BoltMeshSetUp(BoltMesh *);
PetscErrorCode BoltMeshView(BoltMesh *, PetscViewer);
PetscErrorCode BoltMeshDestroy(BoltMesh **);
/* mesh_info.c: what the mesh tells other modules (cells and vertices are DMPlex points: take
   their ranges from BoltMeshDM's strata) */
MPI_Comm        BoltMeshComm(const BoltMesh *);
DM              BoltMeshDM(const BoltMesh *);
const char     *BoltMeshFileName(const BoltMesh *);
Hex8Formulation BoltMeshFormulation(const BoltMesh *);
PetscInt        BoltMeshVertexCountGlobal(const BoltMesh *);
PetscInt        BoltMeshCellCountGlobal(const BoltMesh *);
PetscInt        BoltMeshPartCount(const BoltMesh *);
const char     *BoltMeshPartName(const BoltMesh *, PetscInt);
PetscInt        BoltMeshCellPart(const BoltMesh *, PetscInt);
PetscInt        BoltMeshPointOriginal(const BoltMesh *, PetscInt);
const char     *BoltMeshClampGroup(const BoltMesh *);
const char     *BoltMeshSupportGroup(const BoltMesh *);
PetscInt        BoltMeshSupportComponents(const BoltMesh *, const PetscInt **);
PetscErrorCode  BoltMeshPartValuesWrite(const BoltMesh *, BoltJSON *, const char[], const PetscInt[], const PetscReal[]);
PetscErrorCode  BoltMeshSummaryWrite(const BoltMesh *, BoltJSON *);
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
const PetscReal *BoltLoadSetPreloadAxis(const BoltLoadSet *);
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
PetscErrorCode BoltModalSolve(Mat, Mat, BV, PetscBool, PetscInt, const char[], PetscInt *, PetscReal[]);
/* rigid.c: a free model (no clamp, no support): its rigid motions, inertia relief, the shift */
PetscBool      BoltMeshIsFree(const BoltMesh *);
PetscErrorCode BoltMeshRigidMotion(BoltMesh *, PetscInt, const PetscReal[3], Vec);
PetscErrorCode BoltAssemblerRigidModes(BoltAssembler *, BV *);
PetscErrorCode BoltRigidProject(BV, Vec);
PetscErrorCode BoltRigidRelieve(BV, Mat, Vec);
PetscErrorCode BoltRigidFrequencies(BV, Mat, PetscReal[6]);
PetscReal      BoltRigidShift(void);
PetscErrorCode BoltStaticSolveFree(Mat, Mat, BV, Vec, Vec, const char[], PetscInt *);
/* bolt_tension.c: the clamp force read from the stud beyond the preload layers */
PetscErrorCode BoltLoadSetStudTension(BoltLoadSet *, PetscInt, Mat, Vec, Vec, PetscReal *, PetscBool *);
PetscInt       BoltLoadSetBoltCount(const BoltLoadSet *);
const char    *BoltLoadSetBoltName(const BoltLoadSet *, PetscInt);
PetscReal      BoltLoadSetBoltForce(const BoltLoadSet *, PetscInt);
Vec            BoltLoadSetBoltUnit(const BoltLoadSet *, PetscInt);

#endif
