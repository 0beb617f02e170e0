/* The reduced-order operator: small dense matrices on every rank, solved redundantly with
   LAPACK (cheaper than broadcasting the solution), and the contact DOFs reached through the
   rows of the basis: u_c = V_c q_r, F_r = sum_p D_p' F_p over the node pairs (each summed by
   one owner rank) and K_cr = sum_e V_e' K_e V_e (as D_e' M_e D_e, updated only for elements
   whose active points changed), with D = V_b - V_a at the node pairs. Both sums have the same
   bits on any partition (exact sums over ranks; K_cr under the nodal quadrature by one product
   every rank makes on the same gathered node pairs), and so has the ROM's history. Under the
   penalty law a time step needs neither u_c nor the sums while the contact state holds: the gaps
   come from node-pair rows (normal ones on flat surfaces), and the forces, K_cr and the opening
   test's coefficients are kept with the state's version. */
#include "private/rom.h"

static PetscErrorCode ROMProbe(BoltOperator *op, Vec q, PetscReal *value)
{
  BoltROM           *rom = (BoltROM *)BoltOperatorContext(op);
  const PetscScalar *x;
  PetscReal          v = 0;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(q, &x));
  for (PetscInt j = 0; j < rom->n; j++) v += rom->Vprobe[j] * PetscRealPart(x[j]);
  PetscCall(VecRestoreArrayRead(q, &x));
  *value = v;
  PetscFunctionReturn(0);
}

/* Checkpoints: the reduced vectors as they are (the same on every rank), written by rank 0. */
static PetscErrorCode ROMVectorsSave(BoltOperator *op, PetscViewer v, PetscInt n, const char *const names[], Vec x[])
{
  PetscFunctionBeginUser;
  PetscCall(BoltHDF5WriteVecs(v, BoltOperatorComm(op), n, names, x, PETSC_TRUE));
  PetscFunctionReturn(0);
}

static PetscErrorCode ROMVectorsLoad(BoltOperator *op, PetscViewer v, PetscInt nvec, const char *const names[], Vec y[], PetscInt *missing)
{
  PetscFunctionBeginUser;
  for (PetscInt f = 0; f < nvec; f++) {
    PetscScalar *a;
    PetscReal   *x;
    PetscInt     n, nloc;
    PetscCall(VecGetLocalSize(y[f], &nloc));
    PetscCall(BoltReadAll(v, BoltOperatorComm(op), names[f], &n, &x));
    PetscCheck(n == nloc, BoltOperatorComm(op), PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint holds %" PetscInt_FMT " reduced coordinates, this ROM has %" PetscInt_FMT, n, nloc);
    PetscCall(VecGetArray(y[f], &a));
    for (PetscInt i = 0; i < nloc; i++) a[i] = x[i];
    PetscCall(VecRestoreArray(y[f], &a));
    PetscCall(PetscFree(x));
  }
  PetscFunctionReturn(0);
}

/* The reduced contact stiffness is a sum updated element by element: its round-off depends on
   the path, so a checkpoint keeps it as it is rather than rebuilding it. */
static PetscErrorCode ROMStateSave(BoltOperator *op, PetscViewer v)
{
  BoltROM           *rom = (BoltROM *)BoltOperatorContext(op);
  Mat                Kc;
  const PetscScalar *a;
  PetscInt           nr;

  PetscFunctionBeginUser;
  PetscCall(BoltROMUpdateSettle(op)); /* K_cr of the current state, factorised */
  PetscCall(ROMContactStiffness(op, &Kc));
  PetscCall(MatGetSize(Kc, &nr, NULL));
  PetscCall(MatDenseGetArrayRead(Kc, &a));
  PetscCall(BoltHDF5WriteValues(v, BoltOperatorComm(op), "reduced_contact_stiffness", nr * nr, 1, a, PETSC_TRUE));
  PetscCall(MatDenseRestoreArrayRead(Kc, &a));
  if (rom->update) { /* the grid of the reduced forces' sums: the continued run sums on it too */
    const PetscScalar grid[2] = {rom->fGridBound, rom->fGridValid ? 1.0 : 0.0};
    PetscCall(BoltHDF5WriteValues(v, BoltOperatorComm(op), "reduced_forces_grid", 2, 1, grid, PETSC_TRUE));
  }
  PetscFunctionReturn(0);
}

/* After the contact state was restored: K_cr brought up to date, then replaced by the saved sum. */
static PetscErrorCode ROMStateLoad(BoltOperator *op, PetscViewer v)
{
  BoltROM     *rom = (BoltROM *)BoltOperatorContext(op);
  Mat          Kc;
  PetscScalar *a;
  PetscReal   *x;
  PetscInt     n, nr;

  PetscFunctionBeginUser;
  PetscCall(ROMContactStiffness(op, &Kc));
  PetscCall(MatGetSize(Kc, &nr, NULL));
  PetscCall(BoltReadAll(v, BoltOperatorComm(op), "reduced_contact_stiffness", &n, &x));
  PetscCheck(n == nr * nr, BoltOperatorComm(op), PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint is damaged (reduced contact stiffness of %" PetscInt_FMT " values)", n);
  PetscCall(MatDenseGetArray(Kc, &a));
  for (PetscInt i = 0; i < n; i++) a[i] = x[i];
  PetscCall(MatDenseRestoreArray(Kc, &a));
  PetscCall(MatAssemblyBegin(Kc, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Kc, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscFree(x));
  if (rom->update) {
    PetscCall(BoltReadAll(v, BoltOperatorComm(op), "reduced_forces_grid", &n, &x));
    PetscCheck(n == 2, BoltOperatorComm(op), PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint is damaged (reduced forces' grid of %" PetscInt_FMT " values)", n);
    rom->fGridBound  = x[0];
    rom->fGridValid  = (PetscBool)(x[1] != 0);
    rom->fPartsValid = PETSC_FALSE;
    PetscCall(PetscFree(x));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode ROMView(BoltOperator *op, PetscViewer viewer)
{
  BoltROM *rom = (BoltROM *)BoltOperatorContext(op);

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "  reduced dimension %" PetscInt_FMT ", penalties %g x the FOM's, opening band %g x\n", rom->n, (double)rom->penaltyScale, (double)rom->bandScale));
  PetscCall(BoltROMUpdateView(rom->update, viewer));
  PetscFunctionReturn(0);
}

/* Frees the online caches the operator made in the ROM (idempotent: the ROM may make another). */
PetscErrorCode ROMOnlineDestroy(BoltROM *rom)
{
  PetscFunctionBeginUser;
  PetscCall(MatDestroy(&rom->Kcr));
  PetscCall(PetscFree(rom->Ke));
  PetscCall(PetscFree5(rom->work, rom->work2, rom->dK, rom->packed, rom->Fr));
  PetscCall(PetscFree5(rom->De, rom->DeMax, rom->felem, rom->dMe, rom->dirtyElems));
  /* grown one by one (BoltGrowReal), so freed one by one: PetscFree3 frees a coalesced block */
  PetscCall(PetscFree(rom->kcrSend));
  PetscCall(PetscFree(rom->kcrRecv));
  PetscCall(PetscFree(rom->kcrDT));
  rom->kcrSendAlloc = rom->kcrRecvAlloc = rom->kcrDTAlloc = 0; /* a later operator grows them afresh */
  PetscCall(PetscFree4(rom->gpRows, rom->tnC, rom->tnK, rom->wholeGapBound));
  PetscCall(PetscFree2(rom->Rn, rom->gnRow));
  PetscCall(PetscFree3(rom->keptLo, rom->keptHi, rom->keptCoef));
  PetscCall(PetscFree(rom->tnTau)); /* grown one by one, freed alone */
  rom->tnTauAlloc = 0;
  PetscCall(PetscFree3(rom->pfLocal, rom->pfTerm, rom->pfIn));
  rom->pfValid = PETSC_FALSE;
  PetscCall(BoltExactSumDestroy(&rom->sum));
  PetscCall(BoltROMUpdateDestroy(&rom->update));
  PetscCall(PetscFree2(rom->fAcc, rom->fParts));
  PetscCall(PetscFree6(rom->npSlotStart, rom->npGlobalOf, rom->npDMax, rom->npSlotF, rom->npF, rom->npFSum));
  PetscCall(PetscFree2(rom->npRowsAll, rom->npOfPoint));
  PetscCall(PetscSFDestroy(&rom->npSF));
  PetscCall(PetscFree3(rom->npRowOf, rom->npRows, rom->npGap));
  PetscFunctionReturn(0);
}

static PetscErrorCode ROMOperatorDestroy(BoltOperator *op)
{
  PetscFunctionBeginUser;
  PetscCall(ROMOnlineDestroy((BoltROM *)BoltOperatorContext(op)));
  PetscFunctionReturn(0);
}

/* A free model's ROM: K_r + K_cr is singular along its rigid motions, which its static solve (the
   preload) would leave undetermined. With X = V' R, the rigid motions in its coordinates
   (M_r-orthonormal: V spans them), P = k (M_r X)(M_r X)', k the free model's shift
   (2 pi 10 Hz)^2, holds them in the static solves alone. A self-balanced right-hand side does
   not move them (X' f = 0), so the solution is the one with X' M_r q = 0, as the FOM's preloaded
   state is. (The lowest eigenvectors of (K_r, M_r) would not do: the joint's bolt, washers and
   nut float freely without contact stiffness.) Every rank makes the same operations on the same
   data: the same bits. */
static PetscErrorCode ROMRigidStiffness(BoltROM *rom, Mat *P)
{
  const PetscInt     n = rom->n;
  const PetscReal    k = BoltRigidShift();
  const PetscScalar *mm, *x = rom->rigidr;
  PetscScalar       *y, *p;
  PetscReal          off = 0;

  PetscFunctionBeginUser;
  PetscCheck(x, rom->comm, PETSC_ERR_ARG_WRONGSTATE, "The ROM of a free model has no rigid motions: build it afresh (-rom_rebuild FILE)");
  PetscCall(PetscMalloc1(6 * n, &y));
  PetscCall(MatDenseGetArrayRead(rom->Mr, &mm));
  for (PetscInt c = 0; c < 6; c++) /* y = M_r x_c */
    for (PetscInt i = 0; i < n; i++) {
      PetscScalar sum = 0;
      for (PetscInt j = 0; j < n; j++) sum += mm[i + n * j] * x[j + n * c];
      y[i + n * c] = sum;
    }
  PetscCall(MatDenseRestoreArrayRead(rom->Mr, &mm));
  for (PetscInt c = 0; c < 6; c++) /* X' M_r X = I: how well V holds R */
    for (PetscInt d = 0; d < 6; d++) {
      PetscScalar sum = 0;
      for (PetscInt i = 0; i < n; i++) sum += x[i + n * c] * y[i + n * d];
      off = PetscMax(off, PetscAbsScalar(sum - (c == d ? 1.0 : 0.0)));
    }
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, n, NULL, P));
  PetscCall(MatDenseGetArrayWrite(*P, &p));
  for (PetscInt j = 0; j < n; j++)
    for (PetscInt i = 0; i < n; i++) {
      PetscScalar sum = 0;
      for (PetscInt c = 0; c < 6; c++) sum += y[i + n * c] * y[j + n * c];
      p[i + n * j] = k * sum;
    }
  PetscCall(MatDenseRestoreArrayWrite(*P, &p));
  PetscCall(PetscPrintf(rom->comm, "ROM: free-free: its 6 rigid motions held in its static solves alone (max |X' M_r X - I| %.1e)\n", (double)off));
  PetscCall(PetscFree(y));
  PetscFunctionReturn(0);
}

/* Whether A is diagonal up to rounding: its largest entry off the diagonal at most 1e-8 of its
   largest one (a modal basis: measured 1e-15 and below). */
static PetscErrorCode ROMModal(Mat A, PetscReal *offRel)
{
  const PetscScalar *a;
  PetscInt           n;
  PetscReal          dmax = 0, off = 0;

  PetscFunctionBeginUser;
  PetscCall(MatGetSize(A, &n, NULL));
  PetscCall(MatDenseGetArrayRead(A, &a));
  for (PetscInt j = 0; j < n; j++)
    for (PetscInt i = 0; i < n; i++) {
      if (i == j) dmax = PetscMax(dmax, PetscAbsScalar(a[i + n * j]));
      else off = PetscMax(off, PetscAbsScalar(a[i + n * j]));
    }
  PetscCall(MatDenseRestoreArrayRead(A, &a));
  *offRel = dmax > 0 ? off / dmax : 0;
  PetscFunctionReturn(0);
}

/* The ROM's operator: its matrices, and its own contact state with the ROM's law, penalties and
   opening band. */
PetscErrorCode BoltROMOperatorCreate(BoltROM *rom, BoltOperator **opp)
{
  BoltOperator *op;
  PetscInt      n = rom->n;

  PetscFunctionBeginUser;
  PetscCall(BoltOperatorCreate(rom->comm, "ROM", rom->contact, &op));
  /* n^2 values: a factorisation adds K_cr to a kept copy of the structural sum */
  PetscCall(BoltOperatorSetSolver(op, "rom_", MATSOLVERPETSC, (rom->nCCM + rom->nJIM) ? PETSC_FALSE : PETSC_TRUE, PETSC_TRUE));
  PetscCall(BoltContactStateSetAugment(BoltOperatorState(op), rom->augment)); /* augmented without interface reduction (rom_settings.c) */
  PetscCall(BoltOperatorSetSystem(op, rom->Mr, NULL, rom->Kr, rom->loadr, rom->preloadr));
  PetscCall(BoltOperatorSetDamping(op, rom->Cr, rom->rayleigh[0], rom->rayleigh[1]));
  { /* the basis is modal (reduction.c): the integrator's products are pointwise */
    PetscReal offM, offK;
    PetscCall(ROMModal(rom->Mr, &offM));
    PetscCall(ROMModal(rom->Kr, &offK));
    PetscCheck(offM <= 1e-8 && offK <= 1e-8, rom->comm, PETSC_ERR_PLIB, "ROM: its basis is not modal: M_r and K_r are off their diagonals by %g and %g of their largest entries", (double)offM, (double)offK);
    PetscCall(BoltOperatorSetDiagonalProducts(op));
  }
  if (BoltMeshIsFree(BoltContactSetMesh(rom->contact))) {
    Mat P;
    PetscCall(ROMRigidStiffness(rom, &P));
    PetscCall(BoltOperatorSetRigidStiffness(op, P));
    PetscCall(MatDestroy(&P));
  }
  PetscCall(BoltOperatorSetContext(op, rom));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_CONTACT_DISPLACEMENTS, (void (*)(void))ROMContactDisplacements));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_CONTACT_FORCES, (void (*)(void))ROMContactForces));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_CONTACT_STIFFNESS, (void (*)(void))ROMContactStiffness));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_PROBE, (void (*)(void))ROMProbe));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_PAIR_FORCES, (void (*)(void))ROMPairResultants));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_VECTORS_SAVE, (void (*)(void))ROMVectorsSave));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_VECTORS_LOAD, (void (*)(void))ROMVectorsLoad));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_STATE_SAVE, (void (*)(void))ROMStateSave));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_STATE_LOAD, (void (*)(void))ROMStateLoad));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_VIEW, (void (*)(void))ROMView));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_DESTROY, (void (*)(void))ROMOperatorDestroy));
  PetscCall(BoltContactStateSetPenaltyScale(BoltOperatorState(op), rom->penaltyScale, rom->bandScale));
/* K_cr starts empty; every element is due for an update (marked with the penalties) */
  if (!rom->Kcr) PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, n, NULL, &rom->Kcr));
  if (!rom->sum) PetscCall(BoltExactSumCreate(&rom->sum));
  PetscCall(MatZeroEntries(rom->Kcr));
  rom->KcrValid = rom->FrValid = rom->tnValid = rom->keptValid = PETSC_FALSE; /* a new state: its versions start afresh */
  PetscCall(PetscFree(rom->Ke));
  PetscCall(PetscCalloc1(144 * BoltContactSetElementCount(rom->contact) + 1, &rom->Ke));
  PetscCall(PetscFree5(rom->work, rom->work2, rom->dK, rom->packed, rom->Fr));
  PetscCall(PetscMalloc5(12 * n + 1, &rom->work, 12 * n + 1, &rom->work2, n * n + 1, &rom->dK, n * (n + 1) / 2 + 1, &rom->packed, n + 1, &rom->Fr));
  /* D_e = V_b - V_a of every local contact element, kept for the forces and K_cr */
  {
    BoltContactSet *c = rom->contact;
    const PetscInt  m = BoltContactSetLocalSize(c);
    PetscCall(PetscFree5(rom->De, rom->DeMax, rom->felem, rom->dMe, rom->dirtyElems));
    PetscCall(PetscMalloc5(12 * n * BoltContactSetElementCount(c) + 1, &rom->De, BoltContactSetElementCount(c) + 1, &rom->DeMax, 12 * BoltContactSetElementCount(c) + 1, &rom->felem, 144 * BoltContactSetElementCount(c) + 1, &rom->dMe, BoltContactSetElementCount(c) + 1, &rom->dirtyElems));
    for (PetscInt e = 0; e < BoltContactSetElementCount(c); e++) {
      PetscReal *D = &rom->De[12 * n * e], mx = 0;
      for (PetscInt k = 0; k < 12; k++) {
        PetscInt la = BoltContactSetElementLocal(c)[24 * e + k], lb = BoltContactSetElementLocal(c)[24 * e + 12 + k];
        for (PetscInt j = 0; j < n; j++) {
          D[k + 12 * j] = (lb >= 0 ? PetscRealPart(rom->Vc[lb + m * j]) : 0.0) - (la >= 0 ? PetscRealPart(rom->Vc[la + m * j]) : 0.0);
          mx            = PetscMax(mx, PetscAbsReal(D[k + 12 * j]));
        }
      }
      rom->DeMax[e] = mx;
    }
  }
  /* with opening shapes, only the points the opening solves changed may change state: the basis
     has no shapes to open the others, and freed they chattered at the washers' rims (the
     augmented ROM, without interface reduction, can open any pair); a trained ROM holds every
     point its FOM did not change, even when that FOM changed none */
  PetscCall(BoltContactStateSetMayChange(BoltOperatorState(op), ((rom->opt.trained && rom->marked) || (rom->holdUnmarked && rom->marked && rom->nOpeningPairs > 0 && !rom->augment)) ? rom->marked : NULL));
  PetscCall(ROMSetUpGapRows(rom, BoltContactStateMayChange(BoltOperatorState(op))));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_CONTACT_GAPS, (void (*)(void))ROMContactGaps));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_CHECK_GAPS, rom->augment ? NULL : (void (*)(void))ROMCheckGaps));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_OPEN_TRACTION, (void (*)(void))ROMOpenTraction));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_CHECK_TRACTION, ROMOpenTractionAffine(rom, BoltOperatorState(op)) ? (void (*)(void))ROMCheckTraction : NULL));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_SET_KEPT, ROMSetKeptApplies(rom, BoltOperatorState(op)) ? (void (*)(void))ROMSetKept : NULL));
  if (rom->tie) PetscCall(BoltOperatorSetOperation(op, BOLT_OP_HELD_TRACTIONS, (void (*)(void))ROMHeldTractions));
  PetscCall(ROMSetUpPairForces(rom, BoltContactStateMayChange(BoltOperatorState(op)))); /* the node pairs, before the updates that count them */
  PetscCall(BoltROMUpdateCreate(rom, op, rom->updateRankUsed));
  PetscCall(PetscFree2(rom->fAcc, rom->fParts));
  if (rom->update) PetscCall(PetscMalloc2(2 * n + 1, &rom->fAcc, 2 * n * rom->npOwned + 1, &rom->fParts));
  rom->fGridValid = rom->fPartsValid = PETSC_FALSE;
  *opp = op;
  PetscFunctionReturn(0);
}

/* Start the reduced dual loop from the FOM's preloaded state: its multipliers (scaled to this
   preload: with a fixed active set the static contact problem is linear in it) and its active
   set (under friction its active set only). They stay frozen (penalty law), so the preload
   vector is used as built, uncalibrated. nm runs the ROM's operator, whose state has the ROM's
   penalties. */
PetscErrorCode BoltROMSetPreloadState(BoltROM *rom, BoltNewmark *nm, PetscReal preloadForce)
{
  BoltContactSet   *c = rom->contact;
  BoltContactState *s;
  BoltOperator     *op;

  PetscFunctionBeginUser;
  if (!rom->preloadState) PetscFunctionReturn(0);
  PetscCall(BoltNewmarkGetModel(nm, &op, NULL, NULL));
  s = BoltOperatorState(op);
  /* The FOM's traction at its preloaded state is lambda0 + P g0 (its penalty P on the residual
     gaps g0 its loop leaves), or lambda0 itself after the strict law's loop (its multipliers are
     already the trial tractions of its last solve); the ROM's penalty is s P, so the frozen
     multipliers take lambda0 - (s - 1) P g0, or lambda0 - s P g0: the ROM's traction there is
     the FOM's, its penalty acts on increments */
  const PetscReal g0Share = BoltContactStateIsComplementarity(s) ? 1.0 : 1 - 1 / rom->penaltyScale;

  PetscCall(BoltContactStateSetActive(s, rom->active0, rom->released0)); /* sliding points first: their traction is normal */
  BoltContactStateSetAnchors(s, NULL); /* the FOM's anchors are in the frozen multipliers (raw gaps g0) */
  for (PetscInt e = 0; e < BoltContactSetElementCount(c); e++) {
    for (PetscInt q = 0; q < 4; q++) {
      PetscInt   gp     = 4 * e + q;
      PetscReal  lam[3], g[3], *lambda = &BoltContactStateLambda(s)[3 * gp];
      /* open in the preload: no traction, and none frozen here. Under friction none anywhere: the
         normal is the penalty's alone, and the ROM solves its own preloaded state on the FOM's set
         (its pairs stick or slip there as the FOM's did) */
      if (!rom->active0[gp] || BoltContactStateHasFriction(s)) {
        lambda[0] = lambda[1] = lambda[2] = 0;
        continue;
      }
      for (PetscInt k = 0; k < 3; k++) {
        lam[k] = rom->lambda0[3 * gp + k] * preloadForce;
        g[k]   = -g0Share * rom->gap0[3 * gp + k] * preloadForce;
      }
      BoltContactStateTrialOf(s, gp, lam, g, lambda);
    }
  }
  BoltContactStateChanged(s);
  /* the static state is the FOM's by construction: its active set is not judged again there
     (under the ROM's stiffer penalty, points at the rim whose traction is within the band of
     zero would open on gap differences of a fraction of a nanometre) */
  PetscCall(BoltNewmarkKeepGivenPreload(nm));
  PetscFunctionReturn(0);
}

/* The tied joint in the Laplace domain at s = s0: (s0^2 M + s0 C + K + K_c) q = f with every
   contact point active, by the FOM (MUMPS) and the ROM (LAPACK). Returns the relative error of
   the ROM at the contact DOFs and the probe: the paper's central claim in its exact form. */
PetscErrorCode BoltROMCheckAtS0(BoltROM *rom, BoltOperator *op, BoltAssembler *asmb, BoltContactSet *c, BoltLoadSet *loads, PetscReal *err)
{
  Mat       A, Ar, Kc, Kcr, C, K, M;
  Vec       q, f, qr;
  KSP       ksp, kspr;
  PetscReal s0 = rom->s0, num[2] = {0, 0}, den[2] = {0, 0}, pf, pr;
  Vec       ucFull, ucRed; /* the FOM's (its state's) and the ROM's contact displacements */
  BoltContactState *sFull;

  PetscFunctionBeginUser;
  /* ROM first: its contact stiffness takes the (all active, all dirty) state */
  PetscCall(BoltOperatorContactStiffness(op, &Kcr));
  PetscCall(MatDuplicate(rom->Kr, MAT_COPY_VALUES, &Ar));
  PetscCall(MatAXPY(Ar, s0, rom->Cr, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(Ar, s0 * s0, rom->Mr, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(Ar, 1.0, Kcr, SAME_NONZERO_PATTERN));
  PetscCall(VecDuplicate(rom->loadr, &qr));
  PetscCall(BoltDirectSolverCreate(PETSC_COMM_SELF, NULL, Ar, PETSC_FALSE, NULL, &kspr)); /* LAPACK: PETSc's default for dense */
  PetscCall(KSPSolve(kspr, rom->loadr, qr));
  /* FOM, with the ROM's penalties: a state of its own, every point active */
  PetscCall(BoltContactStateCreate(c, &sFull));
  PetscCall(BoltContactStateSetPenaltyScale(sFull, rom->penaltyScale, rom->bandScale));
  PetscCall(BoltContactStateStiffness(sFull, &Kc));
  PetscCall(BoltAssemblerDamping(asmb, &C));
  PetscCall(BoltAssemblerGetMatrices(asmb, &K, &M));
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &A));
  PetscCall(MatAXPY(A, s0, C, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(A, s0 * s0, M, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(A, 1.0, Kc, DIFFERENT_NONZERO_PATTERN));
  PetscCall(VecDuplicate(BoltLoadSetLoad(loads), &q));
  f = BoltLoadSetLoad(loads);
  PetscCall(BoltDirectSolverCreate(rom->comm, NULL, A, PETSC_FALSE, MATSOLVERMUMPS, &ksp));
  PetscCall(BoltDirectSolverFactor(ksp, NULL));
  PetscCall(KSPSolve(ksp, f, q));
  /* compare at the contact DOFs and the probe */
  PetscCall(BoltContactSetScatter(c, BoltContactStateWork(sFull), q));
  PetscCall(BoltContactWorkGetDisplacements(BoltContactStateWork(sFull), &ucFull));
  PetscCall(BoltOperatorContactDisplacements(op, qr));
  PetscCall(BoltContactWorkGetDisplacements(BoltContactStateWork(BoltOperatorState(op)), &ucRed));
  {
    const PetscScalar *a, *b;
    PetscCall(VecGetArrayRead(ucFull, &a));
    PetscCall(VecGetArrayRead(ucRed, &b));
    for (PetscInt i = 0; i < BoltContactSetLocalSize(c); i++) {
      num[0] += PetscSqr(PetscRealPart(a[i] - b[i]));
      den[0] += PetscSqr(PetscRealPart(a[i]));
    }
    PetscCall(VecRestoreArrayRead(ucFull, &a));
    PetscCall(VecRestoreArrayRead(ucRed, &b));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, num, 1, MPIU_REAL, MPI_SUM, rom->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, den, 1, MPIU_REAL, MPI_SUM, rom->comm));
  PetscCall(BoltLoadSetProbe(loads, q, &pf));
  PetscCall(BoltOperatorProbe(op, qr, &pr));
  *err = PetscMax(PetscSqrtReal(num[0] / den[0]), PetscAbsReal(pr - pf) / PetscAbsReal(pf));
  PetscCall(PetscPrintf(rom->comm, "ROM check at s0 = %g rad/s, tied joint: relative error %.3e at the contact DOFs, %.3e at the probe\n", (double)s0, (double)PetscSqrtReal(num[0] / den[0]), (double)(PetscAbsReal(pr - pf) / PetscAbsReal(pf))));
  PetscCall(VecDestroy(&q));
  PetscCall(VecDestroy(&qr));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(KSPDestroy(&kspr));
  PetscCall(MatDestroy(&A));
  PetscCall(MatDestroy(&Ar));
  PetscCall(MatDestroy(&C));
  PetscCall(BoltContactStateDestroy(&sFull));
  PetscFunctionReturn(0);
}
