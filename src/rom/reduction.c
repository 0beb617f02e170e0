/* Offline reduction: the input matrix B (contact node pairs, load, preload), the second-order
   Krylov basis of boltrom_krylov.h, and the projection onto it (BoltROM). */
#include "private/rom.h"
#include <petscblaslapack.h>
#include "private/boltrom_krylov.h"
#include "private/boltrom_interface.h"

/* Rows of V at this rank's contact DOFs (through the contact scatter) and at the probe. */
static PetscErrorCode BoltROMExtractRows(BoltROM *rom, BV V, BoltLoadSet *loads)
{
  BoltContactWork *w;
  Vec              uc;
  BoltContactSet *c = rom->contact;
  const PetscInt  nloc = BoltContactSetLocalSize(c);
  Vec             e;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(nloc * rom->n + 1, &rom->Vc));
  PetscCall(BoltContactWorkCreate(c, &w));
  PetscCall(BoltContactWorkGetDisplacements(w, &uc));
  for (PetscInt j = 0; j < rom->n; j++) {
    Vec                v;
    const PetscScalar *u;
    PetscCall(BVGetColumn(V, j, &v));
    PetscCall(BoltContactSetScatter(c, w, v));
    PetscCall(BVRestoreColumn(V, j, &v));
    PetscCall(VecGetArrayRead(uc, &u));
    for (PetscInt i = 0; i < nloc; i++) rom->Vc[i + nloc * j] = u[i];
    PetscCall(VecRestoreArrayRead(uc, &u));
  }
  PetscCall(BoltContactWorkDestroy(&w));
  PetscCall(VecDuplicate(BoltLoadSetLoad(loads), &e));
  PetscCall(VecZeroEntries(e));
  if (BoltLoadSetProbeDof(loads) >= 0) PetscCall(VecSetValue(e, BoltLoadSetProbeDof(loads), 1.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(e));
  PetscCall(VecAssemblyEnd(e));
  PetscCall(PetscMalloc1(rom->n + 1, &rom->Vprobe));
  {
    PetscScalar *d;
    PetscCall(PetscMalloc1(rom->n + 1, &d));
    PetscCall(BVDotVec(V, e, d));
    for (PetscInt j = 0; j < rom->n; j++) rom->Vprobe[j] = PetscRealPart(d[j]);
    PetscCall(PetscFree(d));
  }
  PetscCall(VecDestroy(&e));
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltProject(BV V, Mat A, Mat *Ar)
{
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(BVGetSizes(V, NULL, NULL, &n));
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, n, NULL, Ar));
  PetscCall(BVMatProject(V, A, V, *Ar));
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltProjectVec(BV V, Vec f, Vec *fr)
{
  PetscInt     n;
  PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(BVGetSizes(V, NULL, NULL, &n));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, fr));
  PetscCall(VecGetArray(*fr, &a));
  PetscCall(BVDotVec(V, f, a));
  PetscCall(VecRestoreArray(*fr, &a));
  PetscFunctionReturn(0);
}

/* The basis turned into the reduced model's own modes: V <- V Phi with K_r Phi = M_r Phi Lambda and
   Phi' M_r Phi = I (LAPACK's sygv on the projected pair). The same subspace, so the same reduced
   model, in coordinates where M_r = I and K_r = Lambda up to the projection's rounding: the time
   integrator's two products per step with them are pointwise (BoltROMOperator; dense n x n
   products otherwise, a fifth of the paper-step ROM's step). */
static PetscErrorCode ROMModalBasis(BV V, Mat M, Mat K)
{
  Mat          Mr, Kr;
  PetscScalar *a, *b, *work, lw;
  PetscReal   *w;
  PetscBLASInt bn, lwork = -1, info, itype = 1;
  PetscInt     n;

  PetscFunctionBeginUser;
  PetscCall(BVGetSizes(V, NULL, NULL, &n));
  PetscCall(BoltProject(V, M, &Mr));
  PetscCall(BoltProject(V, K, &Kr));
  PetscCall(PetscBLASIntCast(n, &bn));
  PetscCall(MatDenseGetArray(Kr, &a));
  PetscCall(MatDenseGetArray(Mr, &b));
  PetscCall(PetscMalloc1(n + 1, &w));
  PetscCallBLAS("LAPACKsygv", LAPACKsygv_(&itype, "V", "L", &bn, a, &bn, b, &bn, w, &lw, &lwork, &info));
  lwork = (PetscBLASInt)PetscRealPart(lw);
  PetscCall(PetscMalloc1(lwork + 1, &work));
  PetscCallBLAS("LAPACKsygv", LAPACKsygv_(&itype, "V", "L", &bn, a, &bn, b, &bn, w, work, &lwork, &info));
  PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "ROM: the modes of the reduced model failed (LAPACK sygv info %d): its mass matrix is not positive definite", (int)info);
  PetscCall(MatDenseRestoreArray(Mr, &b));
  PetscCall(MatDenseRestoreArray(Kr, &a));
  PetscCall(BVMultInPlace(V, Kr, 0, n)); /* Kr holds Phi */
  PetscCall(PetscFree2(w, work));
  PetscCall(MatDestroy(&Mr));
  PetscCall(MatDestroy(&Kr));
  PetscFunctionReturn(0);
}

/* Appends the static shapes to the basis, orthonormalised against it; dependent ones are
   dropped. The remainders are printed: without interface reduction a shape can lie very close to
   the Krylov vectors' span, and the orthogonalisation then amplifies round-off (separate builds
   on different rank counts differ more than their Krylov vectors do; docs/reduction.md). With
   tol > 0 a shape whose remainder is below tol of its norm is taken for round-off and dropped
   too (the opened-joint Krylov vectors, where the load opens few pairs, lie that close to the
   opening shapes' span). */
static PetscErrorCode BoltBasisAppend(BV V, const char what[], PetscInt nv, Vec v[], PetscReal tol, PetscInt *added)
{
  PetscInt  k, j = 0;
  PetscReal rmin = PETSC_MAX_REAL, rmax = 0;

  PetscFunctionBeginUser;
  PetscCall(BVGetSizes(V, NULL, NULL, &k));
  PetscCall(BVResize(V, k + nv, PETSC_TRUE));
  if (nv == 0) {
    *added = 0;
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < nv; i++) {
    PetscReal nrm, n0;
    PetscBool dep;
    PetscCall(VecNorm(v[i], NORM_2, &n0));
    PetscCall(BVSetActiveColumns(V, 0, k + j + 1));
    PetscCall(BVInsertVec(V, k + j, v[i]));
    PetscCall(BVOrthonormalizeColumn(V, k + j, PETSC_TRUE, &nrm, &dep));
    if (nrm <= tol * n0) dep = PETSC_TRUE;
    rmin = PetscMin(rmin, n0 > 0 ? nrm / n0 : 0);
    rmax = PetscMax(rmax, n0 > 0 ? nrm / n0 : 0);
    if (!dep) j++;
  }
  /* a summary: the remainders of hundreds of shapes would make a line of thousands of characters */
  PetscCall(PetscPrintf(PetscObjectComm((PetscObject)V), "ROM: %s: %" PetscInt_FMT " of %" PetscInt_FMT " kept, remainder after orthogonalisation / norm from %.2e to %.2e\n", what, j, nv, (double)rmin, (double)rmax));
  if (j < nv) PetscCall(BVResize(V, k + j, PETSC_TRUE));
  PetscCall(BVSetActiveColumns(V, 0, k + j));
  *added = j;
  PetscFunctionReturn(0);
}

/* POD modes of the FOM's displacement snapshots of this run: each snapshot's remainder against
   the basis, then the leading left singular vectors of the remainders (by the eigenvectors of
   their Gram matrix, which is small: one column per snapshot), at most nmodes of them and only
   those whose singular value is above tol of the largest. They give the basis what the FOM did
   and the static shapes miss, such as the joint's slip fields under friction. */
static PetscErrorCode BoltSnapshotModes(BV V, PetscInt nsnap, Vec snap[], PetscInt nmodes, PetscReal tol, PetscInt *nout, Vec **modes)
{
  BV            X;
  Mat           G;
  PetscScalar  *g, *w, *work, *coef;
  PetscBLASInt  bn, lwork, info;
  PetscInt      ns = nsnap - 1, k = 0;
  Vec           x;

  PetscFunctionBeginUser;
  *nout  = 0;
  *modes = NULL;
  if (ns <= 0 || nmodes <= 0) PetscFunctionReturn(0);
  PetscCall(BVCreate(PetscObjectComm((PetscObject)V), &X));
  PetscCall(BVSetSizesFromVec(X, snap[0], ns));
  PetscCall(BVSetFromOptions(X));
  PetscCall(BoltBVTolerateCancellation(X));
  for (PetscInt j = 0; j < ns; j++) { /* the motion from the preloaded state, less what V spans */
    PetscCall(BVGetColumn(X, j, &x));
    PetscCall(VecWAXPY(x, -1.0, snap[0], snap[j + 1]));
    PetscCall(BVOrthogonalizeVec(V, x, NULL, NULL, NULL));
    PetscCall(BVOrthogonalizeVec(V, x, NULL, NULL, NULL)); /* twice: the remainders are small */
    PetscCall(BVRestoreColumn(X, j, &x));
  }
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, ns, ns, NULL, &G));
  PetscCall(BVDot(X, X, G));
  PetscCall(MatDenseGetArray(G, &g));
  PetscCall(PetscBLASIntCast(ns, &bn));
  lwork = 8 * bn;
  PetscCall(PetscMalloc3(ns, &w, (size_t)lwork, &work, ns, &coef));
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &bn, g, &bn, w, work, &lwork, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed on the snapshots' Gram matrix (info %d)", (int)info);
  PetscCall(PetscMalloc1(nmodes, modes));
  PetscCall(BVSetActiveColumns(X, 0, ns));
  for (PetscInt i = ns - 1; i >= 0 && k < nmodes; i--) { /* eigenvalues ascend */
    if (!(w[i] > tol * tol * w[ns - 1]) || w[i] <= 0) break;
    for (PetscInt j = 0; j < ns; j++) coef[j] = g[j + (size_t)ns * i] / PetscSqrtReal(w[i]);
    PetscCall(BVCreateVec(X, &(*modes)[k]));
    PetscCall(BVMultVec(X, 1.0, 0.0, (*modes)[k], coef));
    k++;
  }
  PetscCall(PetscPrintf(PetscObjectComm((PetscObject)V), "ROM: %" PetscInt_FMT " snapshots: %" PetscInt_FMT " modes kept, the last at %.1e of the largest singular value, the next at %.1e\n", ns, k, k > 0 ? (double)PetscSqrtReal(PetscMax(w[ns - k], 0) / w[ns - 1]) : 0.0, ns - k - 1 >= 0 ? (double)PetscSqrtReal(PetscMax(w[ns - k - 1], 0) / w[ns - 1]) : 0.0));
  PetscCall(MatDenseRestoreArray(G, &g));
  PetscCall(PetscFree3(w, work, coef));
  PetscCall(MatDestroy(&G));
  PetscCall(BVDestroy(&X));
  *nout = k;
  PetscFunctionReturn(0);
}

/* A free model's six rigid motions, appended to the basis: the Krylov vectors and the static
   shapes (solved under inertia relief) are elastic, and an unbalanced load moves the whole
   structure as a rigid body as well. */
static PetscErrorCode ROMAppendRigid(BoltROM *rom, BV V)
{
  Vec r[6];

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < 6; k++) {
    PetscCall(BVCreateVec(rom->rigid, &r[k]));
    PetscCall(BVCopyVec(rom->rigid, k, r[k]));
  }
  PetscCall(BoltBasisAppend(V, "rigid-body modes", 6, r, 0, &rom->nRigid));
  for (PetscInt k = 0; k < 6; k++) PetscCall(VecDestroy(&r[k]));
  PetscFunctionReturn(0);
}

/* The rigid motions in the ROM's coordinates, M_r^-1 V' M R (exact: V spans them; M_r is diagonal
   in the modal basis), for its static solves (rom.c); once the basis is complete and projected. */
static PetscErrorCode ROMRigidCoordinates(BoltROM *rom, BV V, Mat M)
{
  Vec          r, Mr;
  PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(PetscFree(rom->rigidr));
  PetscCall(PetscMalloc1(6 * rom->n, &rom->rigidr));
  PetscCall(BVCreateVec(rom->rigid, &r));
  PetscCall(VecDuplicate(r, &Mr));
  PetscCall(MatDenseGetArray(rom->Mr, &x));
  for (PetscInt k = 0; k < 6; k++) {
    PetscCall(BVCopyVec(rom->rigid, k, r));
    PetscCall(MatMult(M, r, Mr));
    PetscCall(BVDotVec(V, Mr, &rom->rigidr[rom->n * k]));
    for (PetscInt j = 0; j < rom->n; j++) rom->rigidr[rom->n * k + j] /= x[j + rom->n * j];
  }
  PetscCall(MatDenseRestoreArray(rom->Mr, &x));
  PetscCall(VecDestroy(&Mr));
  PetscCall(VecDestroy(&r));
  PetscCall(BVDestroy(&rom->rigid));
  PetscFunctionReturn(0);
}

/* max |V'V - I| of the basis. */
static PetscErrorCode ROMOrthogonality(BoltROM *rom, BV V)
{
  Mat                G;
  const PetscScalar *g;

  PetscFunctionBeginUser;
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, rom->n, rom->n, NULL, &G));
  PetscCall(BVDot(V, V, G));
  PetscCall(MatDenseGetArrayRead(G, &g));
  rom->orthogonality = 0;
  for (PetscInt i = 0; i < rom->n; i++)
    for (PetscInt j = 0; j < rom->n; j++) rom->orthogonality = PetscMax(rom->orthogonality, PetscAbsScalar(g[i + rom->n * j] - (i == j ? 1.0 : 0.0)));
  PetscCall(MatDenseRestoreArrayRead(G, &g));
  PetscCall(MatDestroy(&G));
  PetscFunctionReturn(0);
}

/* Builds the basis and projects the model onto it, in rom (its settings resolved). */
PetscErrorCode ROMBuild(BoltROM *rom, BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads, PetscLogDouble t0)
{
  BoltReductionOptions *o   = &rom->opt;
  BoltKrylov           *kry = o->krylov;
  BoltInterface        *ir  = NULL;
  BV                    B, V;
  Mat                   C;
  Vec                   preloadCalibrated = NULL; /* the preload layer forces that clamp with -preload_force */
  PetscLogDouble        t1, t2, t3;
  PetscBool             staticShapes       = rom->staticShapes;
  PetscReal             staticPenaltyScale = rom->staticPenaltyScale;
  Vec                   q0keep = NULL;
  Mat                   K, M, Kheld = NULL; /* a trained ROM's Krylov stiffness: K + K_c of the preloaded joint */
  PetscBool            *staticChanged = NULL; /* -rom_train static: the points static solves change */
  BoltPreloadState     *solvedPreload = NULL; /* and the preloaded state, if no FOM ran */

  PetscFunctionBeginUser;
  PetscCall(BoltAssemblerGetMatrices(asmb, &K, &M));
  /* built here: the snapshot modes, and the cone modes in the static solves, read this run's snapshots */
  PetscCheck(!BoltLoadSetBoltCount(loads) || !rom->staticShapes || o->fomPreload, o->comm, PETSC_ERR_SUP, "The ROM of several bolts (-preload_bolts) starts from the FOM's calibrated bolts: add -fom true, or give a -rom_file built for these bolts");
  PetscCheck(o->nSnapshotModes == 0 || o->nFomSnapshots > 1, o->comm, PETSC_ERR_USER_INPUT, "-rom_snapshot_modes needs the FOM's snapshots of the same run: add -fom true -snapshot_every k");
  PetscCall(BoltAssemblerDamping(asmb, &C));
  rom->nCCM = o->nCCM;
  rom->nJIM = o->nJIM;
  if (o->nCCM + o->nJIM > 0) {
    /* the contact inputs collapse onto the reduced interface: inputs E_I V_IR, load, preload */
    PetscCall(PetscLogEventBegin(BOLT_EVENT_INTERFACE_REDUCTION, 0, 0, 0, 0));
    PetscCall(BoltInterfaceBuild(contact, M, C, K, kry->s0, o->nCCM, o->nJIM, kry->deflationTol, &ir));
    PetscCall(PetscLogEventEnd(BOLT_EVENT_INTERFACE_REDUCTION, 0, 0, 0, 0));
    PetscCall(BVCreate(o->comm, &B));
    PetscCall(BVSetSizesFromVec(B, BoltLoadSetLoad(loads), ir->nIR + 1 + ROMPreloadInputs(loads)));
    PetscCall(BVSetFromOptions(B));
    PetscCall(BoltBVTolerateCancellation(B));
    PetscCall(BoltInterfaceInputs(ir, B, 0));
    PetscCall(BVInsertVec(B, ir->nIR, BoltLoadSetLoadUnit(loads)));
    PetscCall(ROMInsertPreloadInputs(B, ir->nIR + 1, loads));
    rom->ninputs  = ir->nIR + 1 + ROMPreloadInputs(loads);
    kry->solve    = BoltInterfaceSolve;
    kry->solveCtx = ir;
    rom->nCCM     = ir->rankCCM;
    rom->nJIM     = ir->rankJIM;
  } else if (o->trained) {
    if (o->trainStatic) { /* where the contact changes from static solves, in place of the FOM run's record */
      if (rom->autoTied) PetscCall(ROMAutoTake(rom, &staticChanged, &solvedPreload)); /* -rom_train auto made them */
      else PetscCall(BoltROMStaticChanges(asmb, contact, loads, rom, o->fomPreload, &staticChanged, &solvedPreload));
      o->fomChanged = staticChanged;
      if (solvedPreload) o->fomPreload = rom->solvedPreload = solvedPreload;
    }
    PetscCall(ROMTrainedInputs(rom, asmb, contact, loads, &B, &Kheld));
  }
  else PetscCall(ROMInputMatrix(contact, loads, BoltLoadSetLoad(loads), NULL, &B, &rom->ninputs, NULL));
  PetscCall(PetscTime(&t1));
  rom->tInterface = t1 - t0;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_BASIS, 0, 0, 0, 0));
  PetscCall(BoltKrylovBuild(kry, M, C, Kheld ? Kheld : K, B, &V));
  PetscCall(MatDestroy(&Kheld));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_BASIS, 0, 0, 0, 0));
  PetscCall(BoltInterfaceDestroy(&ir)); /* its factorisations are not needed from here on */
  kry->solve    = NULL;
  kry->solveCtx = NULL;
  PetscCall(BVDestroy(&B));
  /* the preloaded state's static solves factor the FOM: the damping matrix is rebuilt after them
     rather than held through them (at 562k DOFs the two did not fit in 24 GB together) */
  if (staticShapes) PetscCall(MatDestroy(&C));
  PetscCall(BoltMemoryRelease());
  PetscCall(BoltMemoryPrint(o->comm, "the Krylov basis"));
  rom->nRigid = 0;
  if (BoltMeshIsFree(BoltContactSetMesh(contact)) && !rom->rigid) PetscCall(BoltAssemblerRigidModes(asmb, &rom->rigid)); /* the static solves' inertia relief (static_shapes.c) */
  if (staticShapes) {
    Vec     *extra;
    PetscInt added, nextra;
    PetscCall(PetscLogEventBegin(BOLT_EVENT_BASIS, 0, 0, 0, 0));
    PetscCall(BoltROMPreloadSolve(asmb, contact, loads, rom, o->nClosed, staticPenaltyScale, o->trained ? 0 : rom->openingScale, rom->nOpenKrylov, o->fomPreload, o->nFomSnapshots, o->fomSnapshots, &nextra, &extra, &preloadCalibrated));
    PetscCall(BoltMemoryPrint(o->comm, "the preloaded state's static solves"));
    PetscCall(BoltAssemblerDamping(asmb, &C));
    if (o->trained) { PetscCall(VecDuplicate(extra[0], &q0keep)); PetscCall(VecCopy(extra[0], q0keep)); }
    PetscCall(BoltBasisAppend(V, "static shapes", 2 + o->nClosed, extra, 0, &added));
    PetscCall(BoltBasisAppend(V, "opening shapes", nextra - 2 - o->nClosed, extra + 2 + o->nClosed, kry->deflationTol, &added));
    for (PetscInt k = 0; k < nextra; k++) PetscCall(VecDestroy(&extra[k]));
    PetscCall(PetscFree(extra));
    if (!rom->preloadState) { /* shapes only: the augmented ROM solves its own preload */
      PetscCall(PetscFree4(rom->lambda0, rom->gap0, rom->active0, rom->released0));
      PetscCall(VecDestroy(&preloadCalibrated));
    }
    PetscCall(PetscLogEventEnd(BOLT_EVENT_BASIS, 0, 0, 0, 0));
  }
  if (rom->rigid) PetscCall(ROMAppendRigid(rom, V));
  if (o->nSnapshotModes > 0) {
    Vec     *modes;
    PetscInt nmodes, added;
    PetscCall(BoltSnapshotModes(V, o->nFomSnapshots, o->fomSnapshots, o->nSnapshotModes, o->snapshotTol, &nmodes, &modes));
    PetscCall(BoltBasisAppend(V, "snapshot modes", nmodes, modes, kry->deflationTol, &added));
    rom->nSnapshotModes = added;
    for (PetscInt k = 0; k < nmodes; k++) PetscCall(VecDestroy(&modes[k]));
    PetscCall(PetscFree(modes));
  }
  if (o->trained) { /* the preloaded state itself presses the held pairs: it joins untied */
    PetscInt added;
    PetscCall(ROMTieHeld(rom, contact, V));
    PetscCall(BoltBasisAppend(V, "preloaded state, untied", 1, &q0keep, kry->deflationTol, &added));
  }
  PetscCall(VecDestroy(&q0keep));
  if (o->trainStatic) {
    o->fomChanged = NULL;
    PetscCall(PetscFree(staticChanged));
    if (solvedPreload) o->fomPreload = rom->solvedPreload = NULL;
    PetscCall(BoltPreloadStateDestroy(&solvedPreload));
  }
  PetscCall(PetscTime(&t2));
  PetscCall(BVGetSizes(V, NULL, NULL, &rom->n));
  rom->orthogonality = -1;
  if (o->verify) PetscCall(ROMOrthogonality(rom, V)); /* of the orthogonalised basis */
  PetscCall(PetscLogEventBegin(BOLT_EVENT_PROJECTION, 0, 0, 0, 0));
  PetscCall(ROMModalBasis(V, M, K));
  PetscCall(BoltProject(V, M, &rom->Mr));
  PetscCall(BoltProject(V, C, &rom->Cr));
  PetscCall(BoltProject(V, K, &rom->Kr));
  if (rom->rigid) PetscCall(ROMRigidCoordinates(rom, V, M));
  PetscCall(BoltProjectVec(V, BoltLoadSetLoad(loads), &rom->loadr));
  PetscCall(BoltProjectVec(V, BoltLoadSetLoadUnit(loads), &rom->loadUnitr));
  PetscCall(BoltProjectVec(V, preloadCalibrated ? preloadCalibrated : BoltLoadSetPreload(loads), &rom->preloadr));
  PetscCall(VecDestroy(&preloadCalibrated));
  PetscCall(BoltROMExtractRows(rom, V, loads));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_PROJECTION, 0, 0, 0, 0));
  PetscCall(PetscTime(&t3));
  rom->order = kry->order;
  rom->s0    = kry->s0;
  for (PetscInt k = 0; k < 8; k++) rom->rankPerOrder[k] = kry->rankPerOrder[k];
  rom->tInputs  = ir ? 0 : t1 - t0;
  if (!ir) rom->tInterface = 0;
  rom->tBasis   = t2 - t1;
  rom->tProject = t3 - t2;
  rom->tFactor  = kry->tFactor;
  rom->tSolve   = kry->tSolve;
  rom->tOrth    = kry->tOrth;
  rom->tOffline = t3 - t0;
  PetscCall(PetscPrintf(o->comm, "ROM: rank kept per order:"));
  for (PetscInt k = 0; k < rom->order; k++) PetscCall(PetscPrintf(o->comm, " %" PetscInt_FMT, rom->rankPerOrder[k]));
  PetscCall(PetscPrintf(o->comm, "\n"));
  PetscCall(PetscPrintf(o->comm, "ROM: %" PetscInt_FMT " inputs, order %" PetscInt_FMT ", s0 %g rad/s: dimension %" PetscInt_FMT " (offline %.2f s: inputs %.2f, basis %.2f [factor %.2f, solves %.2f, orthogonalisation %.2f], projection %.2f)\n", rom->ninputs, rom->order, (double)rom->s0, rom->n, (double)rom->tOffline, (double)rom->tInputs, (double)rom->tBasis, (double)rom->tFactor, (double)rom->tSolve, (double)rom->tOrth, (double)rom->tProject));
  if (o->file[0]) PetscCall(BoltROMSave(rom, V, asmb, loads, o->file));
  PetscCall(BoltROMKeepBasis(rom, V)); /* the output's u = V q (rom_field.c) */
  PetscCall(BVDestroy(&V));
  PetscCall(MatDestroy(&C));
  PetscFunctionReturn(0);
}

/* Errors of a ROM history against the FOM's (docs/reduction.md, "Errors and speedup"): relative L2 over all steps, and
   the mean pointwise relative error over the steps where |u_FOM| > 1% of its maximum. */
PetscErrorCode BoltHistoryErrors(PetscInt n, const PetscReal fom[], const PetscReal rom[], PetscReal *eL2, PetscReal *eMean)
{
  PetscReal num = 0, den = 0, umax = 0, sum = 0;
  PetscInt  cnt = 0;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; i++) {
    num += PetscSqr(rom[i] - fom[i]);
    den += PetscSqr(fom[i]);
    umax = PetscMax(umax, PetscAbsReal(fom[i]));
  }
  for (PetscInt i = 0; i < n; i++)
    if (PetscAbsReal(fom[i]) > 0.01 * umax) {
      sum += PetscAbsReal(rom[i] - fom[i]) / PetscAbsReal(fom[i]);
      cnt++;
    }
  *eL2   = den > 0 ? PetscSqrtReal(num / den) : 0;
  *eMean = cnt ? sum / cnt : 0;
  PetscFunctionReturn(0);
}
