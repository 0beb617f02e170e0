#ifndef BOLTROM_PRIVATE_APP_H
#define BOLTROM_PRIVATE_APP_H
#include "boltrom.h"

struct _n_BoltOutput {
  MPI_Comm comm;
  char     dir[PETSC_MAX_PATH_LEN];
  char     name[BOLTROM_NAME_LEN];
  char     h5tmp[PETSC_MAX_PATH_LEN], h5final[PETSC_MAX_PATH_LEN];
  PetscViewer viewer;
  PetscInt nfields;
  char     field[16][BOLTROM_NAME_LEN];
  PetscInt fieldComponents[16];
  PetscBool fieldOnCells[16];
  PetscInt  nseries;            /* temporal XDMF series of displacement snapshots: the FOM's, the ROM's */
  struct {
    char       prefix[8];       /* of the series' fields: <prefix>snapshot_<i>, <prefix>contact_state_<i> */
    PetscInt   n;
    PetscReal *time;
    PetscBool  states;          /* with the contact state at each snapshot */
  } series[2];
};

struct _n_BoltRunOptions {
  char      outputDir[PETSC_MAX_PATH_LEN];
  char      outputName[BOLTROM_NAME_LEN];
  char      summary[PETSC_MAX_PATH_LEN];
  PetscBool staticSolve, verifyFields, checkRigid, writeOutput, fom, rom;
  char      exportDir[PETSC_MAX_PATH_LEN]; /* tied K and M, full and reduced, for petsc4py */
  PetscInt  verifyField;                   /* 0 smooth, 1 linear */
  PetscInt  nev;
  PetscInt  fomUpdateRank; /* -fom_update_rank */
  PetscInt  modalContact; /* BOLT_MODAL_TIED or _PRELOAD: the contact state the modes are about */
};

enum { BOLT_MODAL_TIED, BOLT_MODAL_PRELOAD };

struct _n_BoltSummary {
  BoltMesh       *mesh;
  BoltAssembler  *asmb;
  BoltContactSet *contact;
  BoltLoadSet    *loads;
  PetscReal       tSetUp;
  PetscBool       staticSolve;                   /* "static": the tied joint under the load */
  Vec             u;                             /* its displacement */
  PetscReal       probe, tStatic;
  PetscInt        staticPasses; /* a free model: shifted solves of its static solve */
  PetscBool       freeFree;     /* the tied analyses took the rigid-body motions apart */
  PetscReal       rigidFreq[6]; /* a free model: the rigid motions' frequencies under K [Hz] */
  Vec             x, Kx, Mx;                     /* -verify_fields, or NULL */
  PetscInt        nev, nconv;                    /* "modal" if nev > 0 */
  PetscReal       freq[100], tModal;
  PetscInt        modalContact;                  /* BOLT_MODAL_*, and with _PRELOAD */
  PetscInt        modalPoints[3];                /* the closed, the stuck and all contact points */
  PetscBool       checkRigid;                    /* "rigid_residual_per_part" */
  PetscReal       rigid[BOLTROM_MAX_PARTS];
  BoltNewmark    *preloadRun;                    /* "preload": the FOM's preload (-fom, -modal_contact preload) */
  BoltNewmark    *fomRun;                        /* "fom": the FOM's run */
  PetscReal       preloadForce[BOLTROM_MAX_PAIRS]; /* the FOM's preloaded state, before its transient */
  PetscReal       studTension; /* the FOM's preloaded stud tension [N] (BoltLoadSetStudTension) */
  PetscBool       hasStud;     /* an element layer lies between the preload layers */
  PetscReal       tractionStats[3], preloadPenetration, preloadChange;
  PetscInt        preloadActive, preloadSliding;
  BoltROM        *rom;                           /* "rom": the reduced model and its run */
  BoltNewmark    *romRun;
  PetscBool       romCheckS0;
  PetscReal       romCheckError;
  PetscInt        romBolts;                      /* "rom.bolt_stud_tension": several bolts, read in the ROM's preloaded state */
  PetscReal       romStudTension[BOLTROM_MAX_BOLTS];
  PetscReal       errL2, errMean;                /* "speedup" and "errors": with both runs */
};

struct _n_BoltRun {
  MPI_Comm          comm;
  BoltRunOptions    opt;
  BoltMesh         *mesh;
  BoltAssembler    *asmb;
  BoltContactSet   *contact;
  BoltLoadSet      *loads;
  Vec               u;
  Mat               Ktied;
  BV                rigid; /* a free model's rigid motions (BoltRunRigidModes), made once for every analysis */
  BoltOperator     *fomOp, *romOp;
  BoltNewmark      *fomNm, *romNm;
  BoltPreloadState *fomPreload;
  BoltROM          *rom;
  BoltSummary       sum;
};

#endif
