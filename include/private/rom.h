#ifndef BOLTROM_PRIVATE_ROM_H
#define BOLTROM_PRIVATE_ROM_H
/* Inside the reduced operator (src/rom/rom*.c): what its files share and no other module sees. */
#include "boltrom.h"
#include "private/boltrom_krylov.h" /* BoltKrylov: the basis's options */

/* A point at a node pair (a changed point of the nodal quadrature, or an element's corner): its
   node pair (global DOFs of the x components on sides b and a, -1 where clamped), its name
   (4 x element key + corner) and where its record is. */
typedef struct {
  PetscInt dofB, dofA, name, pos;
} ROMPointRecord;

void ROMRowsTimes(PetscInt m, PetscInt n, const PetscScalar *A, PetscInt lda, const PetscScalar *x, PetscScalar *u);
PetscInt ROMNodePairs(PetscInt nrec, ROMPointRecord rec[], ROMPointRecord first[]);
PetscErrorCode ROMContactDisplacements(BoltOperator *op, Vec q);
PetscErrorCode ROMSetUpPairForces(BoltROM *rom, const PetscBool mayChange[]);
PetscErrorCode ROMContactStiffness(BoltOperator *op, Mat *Kc);
PetscErrorCode ROMSetUpGapRows(BoltROM *rom, const PetscBool mayChange[]);
PetscErrorCode ROMContactForces(BoltOperator *op, const PetscReal lambda[], Vec F);
PetscErrorCode ROMContactGaps(BoltOperator *op, Vec q, PetscReal gap[]);
PetscErrorCode ROMCheckGaps(BoltOperator *op, Vec q, PetscReal gap[]);
PetscErrorCode ROMOpenTraction(BoltOperator *op, PetscReal tn[]);
PetscErrorCode ROMSetKept(BoltOperator *op, PetscBool *kept);
PetscBool      ROMSetKeptApplies(BoltROM *rom, BoltContactState *s);
PetscBool      ROMOpenTractionAffine(BoltROM *rom, BoltContactState *s);
PetscErrorCode ROMCheckTraction(BoltOperator *op, const PetscReal gap[], PetscReal tn[]);
PetscErrorCode ROMPairResultants(BoltOperator *op, Vec q, PetscReal force[]);
PetscErrorCode BoltNodePairsDirected(BoltContactSet *c, const PetscBool mask[], PetscInt nd, const PetscReal pointDir[], PetscInt *npairsOut, PetscInt **pairsOut, PetscReal **dirOut);
PetscErrorCode BoltNodePairs(BoltContactSet *c, const PetscBool mask[], PetscInt *npairsOut, PetscInt **pairsOut);
PetscErrorCode BoltNodePairsCombination(PetscInt npair, const PetscInt pairs[], const PetscReal dirs[], PetscInt stride, const PetscReal coef[], Vec v);
PetscErrorCode BoltNodePairVectorAlong(PetscInt a, PetscInt b, const PetscReal dir[3], Vec v);
PetscErrorCode BoltNodePairVector(PetscInt a, PetscInt b, PetscInt d, Vec v);
PetscErrorCode BoltNodePairPatterns(MPI_Comm comm, PetscInt npair, const PetscInt pairs[], const PetscReal dirs[], PetscInt stride, PetscInt nsnap, Vec snap[], PetscInt kmax, PetscInt *kout, PetscReal **patterns);
PetscErrorCode BoltROMPreloadSolve(BoltAssembler *asmb, BoltContactSet *c, BoltLoadSet *loads, BoltROM *rom, PetscInt nClosed, PetscReal staticPenaltyScale, PetscReal openingScale, PetscInt nOpenKrylov, const BoltPreloadState *shared, PetscInt nsnap, Vec snap[], PetscInt *nextra, Vec **extrap, Vec *preload);
PetscErrorCode ROMResolveSettings(BoltROM *rom, BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads);
PetscErrorCode ROMResolveOnline(BoltROM *rom, BoltContactSet *contact);
PetscErrorCode ROMReuseFile(BoltROM *rom, BoltContactSet *contact, BoltLoadSet *loads, PetscLogDouble t0, PetscBool *reused);
PetscErrorCode ROMBuild(BoltROM *rom, BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads, PetscLogDouble t0);
PetscInt       ROMPreloadInputs(BoltLoadSet *loads);
PetscErrorCode ROMInputMatrix(BoltContactSet *c, BoltLoadSet *loads, Vec layout, const PetscBool select[], BV *B, PetscInt *ncols, PetscInt *npairsOut);
PetscErrorCode ROMInsertPreloadInputs(BV B, PetscInt col, BoltLoadSet *loads);
PetscErrorCode ROMTieHeld(BoltROM *rom, BoltContactSet *contact, BV V);
PetscErrorCode ROMTiedPairs(BoltROM *rom, BoltContactSet *contact, PetscInt *ntie, PetscInt **pairs, PetscReal **normals);
PetscErrorCode ROMTieCheckSetUp(BoltROM *rom, BoltAssembler *asmb, BoltLoadSet *loads);
PetscErrorCode ROMTieCheckDestroy(BoltROM *rom);
PetscErrorCode ROMHeldTractions(BoltOperator *op, Vec q, Vec v, Vec a, PetscReal amp, const PetscBool **tied, const PetscReal **t);
PetscErrorCode ROMGetBasis(BoltROM *rom, BV *V);
PetscErrorCode ROMTrainedSettings(BoltROM *rom, BoltLoadSet *loads);
PetscErrorCode BoltROMStaticChanges(BoltAssembler *asmb, BoltContactSet *c, BoltLoadSet *loads, BoltROM *rom, const BoltPreloadState *shared, PetscBool **changed, BoltPreloadState **solved);
PetscErrorCode ROMAutoChoose(BoltROM *, BoltAssembler *, BoltContactSet *, BoltLoadSet *);
PetscErrorCode ROMSwitchTied(BoltROM *, BoltAssembler *, BoltContactSet *, BoltLoadSet *);
PetscErrorCode ROMAutoRelease(BoltROM *);
PetscErrorCode ROMAutoTake(BoltROM *, PetscBool **, BoltPreloadState **);
PetscErrorCode ROMTrainedInputs(BoltROM *rom, BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads, BV *B, Mat *Kheld);
PetscErrorCode ROMOnlineDestroy(BoltROM *rom);
PetscErrorCode BoltROMSave(BoltROM *rom, BV V, BoltAssembler *asmb, BoltLoadSet *loads, const char file[]);
PetscErrorCode BoltROMLoad(const char file[], BoltROM *rom, BoltContactSet *c, BoltLoadSet *loads, PetscBool *matched, char why[], size_t whylen);
PetscErrorCode BoltROMFingerprintInt(BoltROMFingerprint *, const char[], PetscInt);
PetscErrorCode BoltROMFingerprintReal(BoltROMFingerprint *, const char[], PetscReal);
PetscErrorCode BoltROMFingerprintString(BoltROMFingerprint *, const char[], const char[]);
PetscErrorCode BoltROMFingerprintScene(BoltAssembler *, BoltContactSet *, BoltLoadSet *, PetscInt, PetscReal, PetscReal, PetscInt, PetscInt, BoltROMFingerprint *);
PetscErrorCode BoltROMFingerprintWrite(const BoltROMFingerprint *, PetscViewer);
PetscErrorCode BoltROMFingerprintMatch(const BoltROMFingerprint *, PetscViewer, PetscBool *, char[], size_t);
PetscErrorCode BoltROMFingerprintMatchLoad(PetscViewer, BoltLoadSet *, PetscBool, PetscBool *, PetscBool *, char[], size_t);


struct _n_BoltROMFingerprintField {
  char          key[BOLTROM_NAME_LEN + 32];
  PetscDataType type; /* PETSC_INT, PETSC_REAL or PETSC_STRING */
  PetscInt      i;
  PetscReal     r;
  char          s[BOLTROM_NAME_LEN];
};

struct _n_BoltReductionOptions {
  MPI_Comm   comm;
  PetscInt   nCCM, nJIM;
  BoltKrylov *krylov;       /* the Krylov basis's options (-krylov_*), owned by the ROM */
  char       file[PETSC_MAX_PATH_LEN];
  char       rebuildFile[PETSC_MAX_PATH_LEN]; /* -rom_rebuild: where a ROM built in place of a -rom_file that does not match (or is damaged) goes; empty: refuse */
  PetscBool  extraInputs;   /* allow a load that is not an input of the ROM */
  PetscBool  verify;        /* -rom_verify: orthogonality and s0 checked, online every gap and a refactorisation at every change */
  /* the construction's fixed settings (rom_object.c), resolved by SetUp */
  PetscInt   nClosed;            /* closed-contact Krylov vectors */
  PetscReal  openingScale;       /* the load's scale whose changed pairs get opening shapes */
  PetscReal  slipScale;          /* friction: the load's scale whose pairs beyond the cone get shapes */
  PetscReal  slipScalePeriodic;  /* ... under a periodic load (a sine can build up near a mode) */
  PetscBool  periodicLoad;       /* the scene's load is a sine or a stepped sine (BoltROMSetPeriodicLoad) */
  PetscReal  coneShapes;         /* -rom_cone_shapes: friction, the pairs at this fraction of the cone in the preloaded state get shapes, 0 none */
  PetscBool  coneTraction;       /* -rom_cone_traction */
  PetscInt   coneModes;          /* -rom_cone_modes: the cone shapes compressed to this many per direction, 0 a shape per pair */
  PetscInt   nOpenKrylov;        /* opened-joint Krylov vectors */
  PetscInt   nSnapshotModes;                /* -rom_snapshot_modes: POD modes of the FOM's snapshots of this run, 0 none */
  PetscReal  snapshotTol;                   /* the snapshot modes' smallest singular value, relative */
  const BoltPreloadState *fomPreload;       /* the FOM's preloaded state of this run, or NULL */
  PetscInt   nFomSnapshots;                 /* the FOM's displacement snapshots of this run (-snapshot_every) */
  Vec       *fomSnapshots;
  PetscBool  trained;                       /* -rom_train: inputs where the contact changes, the other closed pairs tied (trained.c) */
  PetscBool  trainStatic;                   /* -rom_train static: where it changes from static solves of the preloaded joint, not the FOM's run */
  const PetscBool *fomChanged;              /* the FOM's run: per local contact point, its state left the preloaded one */
  PetscBool  trainAuto;                     /* -rom_train auto (the default): tied if static solves change no pair, else as none */
};

struct _n_BoltROMFingerprint {
  PetscInt                n;
  BoltROMFingerprintField field[BOLTROM_FINGERPRINT_FIELDS];
};

struct _n_BoltROM {
  MPI_Comm        comm;
  BoltReductionOptions opt;          /* the options as given (BoltROMSetFromOptions) */
  PetscBool       view;              /* -rom_view: print the settings used once set up */
  PetscBool       staticShapes;      /* resolved: static shapes in the basis */
  PetscReal       staticPenaltyScale; /* resolved: the offline static solves' penalty, x the FOM's */
  PetscInt        n;                 /* reduced dimension */
  Mat             Mr, Cr, Kr, Kcr;   /* MATSEQDENSE n x n on every rank */
  PetscReal       rayleigh[2];       /* C_r = rayleigh[0] M_r + rayleigh[1] K_r */
  Vec             loadr, preloadr;   /* MATSEQ n */
  Vec             loadUnitr;         /* V' (1 N load pattern), kept in the ROM file */
  PetscScalar    *Vc;                /* nlocal x n, column-major: rows of V at contact->localGlobal */
  PetscReal      *Vprobe;            /* n: the probe row of V */
  PetscReal      *Ke;                /* 144 per local contact element: M_e of K_e = [M_e -M_e; -M_e M_e] inside Kcr */
  PetscReal      *De;                /* 12 x n per local contact element: V_b - V_a at its node pairs (0 where clamped) */
  PetscReal      *DeMax;             /* per local contact element: max |De| */
  PetscReal      *felem;             /* 12 per local contact element: the side-b forces of the tractions */
  PetscScalar    *work, *work2, *dK, *packed; /* scratch (packed: an upper triangle) */
  PetscReal      *dMe;               /* 144 per local contact element: scratch of the K_cr update */
  PetscInt       *dirtyElems;        /* per local contact element: scratch of the K_cr update */
  PetscReal      *kcrSend, *kcrRecv, *kcrDT; /* scratch of the node-pair K_cr update, kept between updates */
  PetscInt        kcrSendAlloc, kcrRecvAlloc, kcrDTAlloc; /* (a fresh megabyte-sized buffer per update spent its time in page faults) */
  BoltExactSum   *sum;               /* the reductions over ranks, partition-independent */
  /* what the online phase keeps while the contact state's version holds (BoltContactState) */
  PetscScalar    *Fr;                /* n: the reduced forces of the state's multipliers */
  PetscObjectState FrVersion, KcrVersion, tnVersion;
  PetscBool       FrValid, KcrValid, tnValid;
  /* the gaps from node-pair differences D = V_b - V_a: on flat surfaces the normal gaps n' D q
     (a sixth of the rows of V_c), all that the penalty law's decisions need (the tangential gaps
     act only through the penalty, which is inside K_cr); under friction the whole gaps, three
     rows per node pair (half the rows of V_c, and no cancellation in u_b - u_a) */
  PetscBool       flat;              /* the normals of all points at each node agree (global) */
  PetscBool       wholeRows;         /* three rows of D per node pair (curved surfaces, or friction), else one normal row */
  PetscInt        nGapRows, nLiveRows; /* all rows; the first nLiveRows are those of points that may change */
  PetscBool       heldRowsDone;      /* the held points' rows were taken once */
  PetscScalar    *Rn;                /* nGapRows x n, column-major */
  PetscInt       *gpRows;            /* 4 per local point: the row of each node it interpolates (-1: none) */
  PetscScalar    *gnRow;             /* nGapRows: scratch */
  PetscReal      *tnC, *tnK;         /* per local point: the opening test's traction is tnC + tnK g.n */
  PetscReal      *tnTau;             /* 3 per local point: scratch of tnC and tnK's tractions (grow-only) */
  PetscInt        tnTauAlloc;
  /* the pair resultants b + A q of a penalty law (rom_pair_forces.c), made again when the version moves */
  PetscReal      *pfLocal;           /* this rank's part of A (BOLT_PAIR_FORCE rows per pair x n, row-major), then of b */
  PetscReal      *pfTerm;            /* 16 per local point: the multipliers, P (3 x 3) and penalties (normal, tangential) of its term in pfLocal */
  PetscBool      *pfIn;              /* per local point: its term is in pfLocal */
  PetscObjectState pfVersion;
  PetscBool       pfValid;
  /* the whole gap of an open point is needed only where it closes (it sticks there): it is taken
     from the point's rows of D_e when its normal gap is within wholeGapBound x |q|_max of closing,
     a bound on the rounding between the normal row and the whole gap's normal part */
  PetscReal      *wholeGapBound;     /* per local point */
  PetscReal       gapsXmax;          /* |q|_max of the last gaps that needed it (whole gaps near closing) */
  /* the proof that no point changes (ROMSetKept): while every live normal row's gap lies in its
     interval keptLo + keptCoef |q|_max < g < keptHi, every point keeps its state */
  PetscReal      *keptLo, *keptHi, *keptCoef; /* per gap row */
  PetscBool       keptNever;         /* some local point's state would change whatever its gap */
  PetscObjectState keptVersion;
  PetscBool       keptValid;
  BoltContactSet *contact;
  BV              rigid;         /* offline: a free model's rigid motions (mass-orthonormal, the FOM's layout), NULL if held */
  PetscInt        nRigid;        /* rigid motions appended to the basis (6 free-free, else 0) */
  PetscScalar    *rigidr;        /* 6 n, column-major: V' R, a free model's rigid motions in the ROM's coordinates (kept in the ROM file), NULL if held */
  /* offline figures */
  PetscInt        order, ninputs, nCCM, nJIM, rankPerOrder[8];
  PetscReal       s0, tOffline, tInputs, tBasis, tProject, tFactor, tSolve, tOrth, tInterface;
  PetscBool       fromFile;
  PetscBool       augment;       /* contact law of the reduced dual loop */
  PetscReal       orthogonality; /* max |V'V - I|, or -1 if not measured */
  BoltROMFingerprint fingerprint; /* what the basis depends on (src/rom/fingerprint.c) */
  /* the FOM's preloaded state (offline): multipliers per newton of preload and the active set,
     per local contact element; the reduced dual loop starts from them and keeps them frozen */
  PetscBool       preloadState;
  PetscReal      *lambda0;       /* 12 per local contact element, per N of preload */
  PetscReal      *gap0;          /* the gaps of that state, likewise */
  PetscBool      *active0;       /* 4 per local contact element */
  PetscBool      *released0;     /* 4 per local contact element: closed but sliding (strict law) */
  PetscReal       penaltyScale;  /* the ROM's penalties: this times the FOM's */
  PetscReal       bandScale;     /* the ROM's activation band (traction): this times the FOM's */
  PetscInt        nClosed;       /* closed-contact Krylov vectors in the basis */
  PetscReal       openingScale;  /* opening shapes of the pairs this multiple of the load changes (0: none) */
  PetscReal       slipScale;     /* friction: also of the pairs beyond the cone, sticking, under this multiple */
  PetscReal       coneShapes;    /* friction: also of the pairs whose preloaded traction is this fraction of the cone or more (0: none) */
  PetscBool       coneTraction;  /* with them: a shape along the pair's tangential traction too (else along its normal only) */
  PetscInt        coneModes;     /* with them and training snapshots: this many shapes per direction, of the snapshots' patterns at the pairs (0: one per pair) */
  PetscInt        nOpenKrylov;   /* opened-joint Krylov vectors with them */
  PetscInt        nOpeningPairs; /* node pairs with opening shapes in the basis */
  PetscInt        nSnapshotModes; /* POD modes of the FOM's snapshots in the basis */
  PetscInt        nConePairs;    /* friction: node pairs with cone shapes in the basis */
  PetscInt        nConeModes;    /* friction: the cone shapes in the basis when compressed (-rom_cone_modes), else 0 */
  PetscBool      *marked;        /* 4 per local contact element: the point's state changed in those static solves (NULL: not made) */
  PetscBool       holdUnmarked;  /* online, the other points keep their preloaded state */
  PetscBool       gapsEverywhere; /* -rom_verify: every point's gaps at every solve */
  PetscReal       epsSaved[3 * BOLTROM_MAX_PAIRS]; /* the FOM's penalties (N, T) and bands per pair, while the ROM's are set */
  PetscInt        updateRankUsed; /* as resolved when the operator was made (0: refactorise) */
  struct BoltROMUpdate_s *update; /* low-rank updates of the online factorisation (rom_update.c), or NULL */
  /* F_r = sum_p D_p' F_p over node pairs p (D_p: the pair's three rows of D = V_b - V_a, F_p the
     side-b force of its points). Each node pair has one owner rank, in turn over the pairs in the
     order of their first point's name; its points' nodal forces reach the owner, which sums them
     in the order of their names: a node pair's term has the same bits on any partition, costs a
     quarter of the four element terms it replaces, and the ranks share the pairs evenly. */
  PetscInt        npOwned, npGlobal; /* node pairs this rank owns, and all of them */
  PetscInt       *npSlotStart;   /* npOwned + 1: the owned pairs' points in npSlotF */
  PetscInt       *npGlobalOf;    /* per owned pair: its index among all pairs (its rows in npRowsAll) */
  PetscReal      *npDMax;        /* per owned pair: max |D_p| */
  PetscReal      *npSlotF;       /* 3 per point of an owned pair: its nodal force, from its element's rank */
  PetscReal      *npF, *npFSum;  /* 3 per owned pair: F_p, and the F_p whose term fAcc holds */
  PetscSF         npSF;          /* leaves: felem of the local elements (and, alike, their points' gaps); roots: npSlotF */
  /* every node pair's rows of D on every rank: the owners' force terms read their pairs' rows
     there, and the online K_cr and low-rank updates gather a changed point's 3 x 3 block and its
     pair's index, not its 3n values of D */
  PetscReal      *npRowsAll;     /* 3n per node pair (all ranks'), n x 3 column-major, in the pairs' order */
  PetscInt       *npOfPoint;     /* 4 per local contact element: its node pair's index (-1: both nodes clamped) */
  /* under friction with the nodal quadrature (pairGaps) the owners make the gaps too, D_p q, and
     send them to the pairs' points: the rows of pairs with a point that may change first */
  PetscBool       pairGaps;
  PetscInt        npLive;        /* owned pairs with a point that may change */
  PetscInt       *npRowOf;       /* per owned pair: its first row in npRows */
  PetscScalar    *npRows;        /* 3 npOwned x n, column-major: the owned pairs' rows of npRowsAll again, as one block for the gaps' product (npRowsAll keeps a pair's rows together for its force term) */
  PetscScalar    *npGap;         /* 3 npOwned: scratch */
  /* with low-rank updates, F_r of the state's multipliers is updated for the pairs whose forces changed */
  PetscReal      *fAcc;          /* 2n: this rank's exact partial sums */
  PetscReal      *fParts;        /* 2n per owned pair: its term's parts in fAcc */
  PetscReal       fGridBound;    /* the bound the sums' grid was set for (kept by checkpoints) */
  PetscBool       fGridValid, fPartsValid;
  /* a trained ROM's check of its tied pairs (tie_check.c): the rows of K V and M V, of the load
     and of the preload at the tied pairs' DOFs this rank owns, for the ties' forces */
  struct BoltROMTieCheck_s *tie;
  const BoltPreloadState   *solvedPreload; /* -rom_train static without a FOM run: the preloaded state solved offline, while the build uses it */
  /* -rom_train auto: whether the static solves made it the tied ROM; their marks and the state
     they solved (no FOM in the run), handed to the build */
  PetscBool         autoTied;
  PetscBool        *autoChanged;
  BoltPreloadState *autoSolved;
};

#endif
