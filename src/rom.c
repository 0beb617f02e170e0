/* The reduced-order operator: small dense matrices on every rank, solved redundantly with
   LAPACK (cheaper than broadcasting the solution), and the contact DOFs reached through the
   rows of the basis: u_c = V_c q_r, F_r = V_c' f_c summed over ranks, and
   K_cr = sum_e V_e' K_e V_e (as D_e' M_e D_e) updated only for elements whose active points changed. */
#include "boltrom.h"
#include <petscblaslapack.h>

static PetscErrorCode ROMContactDisplacements(BoltOperator *op, Vec q)
{
  BoltROM           *rom = (BoltROM *)op->ctx;
  BoltContactSet    *c   = rom->contact;
  const PetscScalar *x;
  PetscScalar       *u, one = 1.0, zero = 0.0;
  PetscBLASInt       m, n, inc = 1;

  PetscFunctionBeginUser;
  if (!c->nlocal) PetscFunctionReturn(0);
  PetscCall(PetscBLASIntCast(c->nlocal, &m));
  PetscCall(PetscBLASIntCast(rom->n, &n));
  PetscCall(VecGetArrayRead(q, &x));
  PetscCall(VecGetArray(c->uc, &u));
  PetscCallBLAS("BLASgemv", BLASgemv_("N", &m, &n, &one, rom->Vc, &m, x, &inc, &zero, u, &inc));
  PetscCall(VecRestoreArray(c->uc, &u));
  PetscCall(VecRestoreArrayRead(q, &x));
  PetscFunctionReturn(0);
}

static PetscErrorCode ROMContactForces(BoltOperator *op, Vec F)
{
  BoltROM           *rom = (BoltROM *)op->ctx;
  BoltContactSet    *c   = rom->contact;
  const PetscScalar *f;
  PetscScalar       *y, one = 1.0, zero = 0.0;
  PetscBLASInt       m, n, inc = 1;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(F, &y));
  if (c->nlocal) {
    PetscCall(PetscBLASIntCast(c->nlocal, &m));
    PetscCall(PetscBLASIntCast(rom->n, &n));
    PetscCall(VecGetArrayRead(c->fc, &f));
    PetscCallBLAS("BLASgemv", BLASgemv_("T", &m, &n, &one, rom->Vc, &m, f, &inc, &zero, y, &inc));
    PetscCall(VecRestoreArrayRead(c->fc, &f));
  } else
    for (PetscInt j = 0; j < rom->n; j++) y[j] = 0;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, y, (PetscMPIInt)rom->n, MPIU_SCALAR, MPIU_SUM, rom->comm));
  PetscCall(VecRestoreArray(F, &y));
  PetscFunctionReturn(0);
}

static PetscErrorCode ROMContactStiffness(BoltOperator *op, Mat *Kc)
{
  BoltROM        *rom = (BoltROM *)op->ctx;
  BoltContactSet *c   = rom->contact;
  PetscInt        n = rom->n, changed = 0, any;
  PetscBLASInt    bn, b12 = 12;
  PetscScalar     one = 1.0, zero = 0.0, *De = rom->work, *T = rom->work2, *dK = rom->dK, *K;
  PetscReal       Knew[576];

  PetscFunctionBeginUser;
  PetscCall(PetscBLASIntCast(n, &bn));
  for (PetscInt e = 0; e < c->nelem; e++) {
    PetscScalar delta[144];
    if (!c->dirty[e]) continue;
    /* K_e = [M -M; -M M] (B = [-N, N]), so V_e' K_e V_e = D_e' M D_e with D_e = V_b - V_a, the
       relative displacements of the node pairs. Forming D_e first spares the directions that open
       no gap the penalty's round-off (through K_e it would be about eps_N |V|^2 u, large under a
       near-hard penalty against the joint's soft stiffness) */
    PetscCall(QuadPairPenaltyStiffnessActive(c->elem[e].Xa, c->epsN[c->elem[e].pair], c->epsT[c->elem[e].pair], &c->active[4 * e], Knew));
    for (PetscInt a = 0; a < 12; a++)
      for (PetscInt b = 0; b < 12; b++) {
        delta[12 * a + b]          = Knew[24 * a + b] - rom->Ke[144 * e + 12 * a + b];
        rom->Ke[144 * e + 12 * a + b] = Knew[24 * a + b];
      }
    c->dirty[e] = PETSC_FALSE;
    for (PetscInt k = 0; k < 12; k++) {
      PetscInt la = c->elemLocal[24 * e + k], lb = c->elemLocal[24 * e + 12 + k];
      for (PetscInt j = 0; j < n; j++) De[k + 12 * j] = (lb >= 0 ? rom->Vc[lb + c->nlocal * j] : 0.0) - (la >= 0 ? rom->Vc[la + c->nlocal * j] : 0.0);
    }
    if (!changed) PetscCall(PetscArrayzero(dK, n * n));
    PetscCallBLAS("BLASgemm", BLASgemm_("N", "N", &b12, &bn, &b12, &one, delta, &b12, De, &b12, &zero, T, &b12));
    PetscCallBLAS("BLASgemm", BLASgemm_("T", "N", &bn, &bn, &b12, &one, De, &b12, T, &b12, &one, dK, &bn));
    changed++;
  }
  PetscCall(MPIU_Allreduce(&changed, &any, 1, MPIU_INT, MPI_SUM, rom->comm));
  if (any) {
    if (!changed) PetscCall(PetscArrayzero(dK, n * n));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, dK, (PetscMPIInt)(n * n), MPIU_SCALAR, MPIU_SUM, rom->comm));
    PetscCall(MatDenseGetArray(rom->Kcr, &K));
    for (PetscInt k = 0; k < n * n; k++) K[k] += dK[k];
    PetscCall(MatDenseRestoreArray(rom->Kcr, &K));
    PetscCall(MatAssemblyBegin(rom->Kcr, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(rom->Kcr, MAT_FINAL_ASSEMBLY));
  }
  *Kc = rom->Kcr;
  PetscFunctionReturn(0);
}

static PetscErrorCode ROMProbe(BoltOperator *op, Vec q, PetscReal *value)
{
  BoltROM           *rom = (BoltROM *)op->ctx;
  const PetscScalar *x;
  PetscReal          v = 0;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(q, &x));
  for (PetscInt j = 0; j < rom->n; j++) v += rom->Vprobe[j] * PetscRealPart(x[j]);
  PetscCall(VecRestoreArrayRead(q, &x));
  *value = v;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltROMOperatorCreate(BoltROM *rom, BoltOperator **opp)
{
  BoltOperator *op;
  PetscInt      n = rom->n;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&op));
  op->name       = "ROM";
  op->comm       = rom->comm;
  op->solverType = MATSOLVERPETSC;
  op->exactConstraints = (rom->nCCM + rom->nJIM) ? PETSC_FALSE : PETSC_TRUE;
  op->augment = rom->augment; /* -rom_contact_augment */
  PetscCall(PetscStrncpy(op->prefix, "rom_", sizeof(op->prefix)));
  op->M       = rom->Mr;
  op->C       = rom->Cr;
  op->K       = rom->Kr;
  op->load    = rom->loadr;
  op->preload = rom->preloadr;
  PetscCall(PetscObjectReference((PetscObject)op->M));
  PetscCall(PetscObjectReference((PetscObject)op->C));
  PetscCall(PetscObjectReference((PetscObject)op->K));
  PetscCall(PetscObjectReference((PetscObject)op->load));
  PetscCall(PetscObjectReference((PetscObject)op->preload));
  op->contact              = rom->contact;
  op->ctx                  = rom;
  op->contactDisplacements = ROMContactDisplacements;
  op->contactForces        = ROMContactForces;
  op->contactStiffness     = ROMContactStiffness;
  op->probe                = ROMProbe;
  /* the ROM's own penalties and activation band, restored when the operator goes */
  for (PetscInt p = 0; p < rom->contact->npairs; p++) {
    rom->epsSaved[2 * p]     = rom->contact->epsN[p];
    rom->epsSaved[2 * p + 1] = rom->contact->epsT[p];
    rom->epsSaved[2 * BOLTROM_MAX_PAIRS + p] = rom->contact->bandTraction[p];
    rom->contact->epsN[p] *= rom->penaltyScale;
    rom->contact->epsT[p] *= rom->penaltyScale;
    rom->contact->bandTraction[p] *= rom->bandScale;
  }
  /* K_cr starts empty with every element due for an update */
  if (!rom->Kcr) PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, n, NULL, &rom->Kcr));
  PetscCall(MatZeroEntries(rom->Kcr));
  PetscCall(PetscFree(rom->Ke));
  PetscCall(PetscCalloc1(144 * rom->contact->nelem + 1, &rom->Ke));
  PetscCall(PetscFree3(rom->work, rom->work2, rom->dK));
  PetscCall(PetscMalloc3(12 * n + 1, &rom->work, 12 * n + 1, &rom->work2, n * n + 1, &rom->dK));
  for (PetscInt e = 0; e < rom->contact->nelem; e++) rom->contact->dirty[e] = PETSC_TRUE;
  *opp = op;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltROMOperatorDestroy(BoltOperator **opp)
{
  BoltOperator *op = *opp;

  PetscFunctionBeginUser;
  if (!op) PetscFunctionReturn(0);
  {
    BoltROM *rom = (BoltROM *)op->ctx;
    for (PetscInt p = 0; p < rom->contact->npairs; p++) {
      rom->contact->epsN[p] = rom->epsSaved[2 * p];
      rom->contact->epsT[p] = rom->epsSaved[2 * p + 1];
      rom->contact->bandTraction[p] = rom->epsSaved[2 * BOLTROM_MAX_PAIRS + p];
    }
  }
  PetscCall(MatDestroy(&op->M));
  PetscCall(MatDestroy(&op->C));
  PetscCall(MatDestroy(&op->K));
  PetscCall(VecDestroy(&op->load));
  PetscCall(VecDestroy(&op->preload));
  PetscCall(PetscFree(*opp));
  PetscFunctionReturn(0);
}

/* Start the reduced dual loop from the FOM's preloaded state: its multipliers (scaled to this
   preload: with a fixed active set the static contact problem is linear in it) and its active
   set. They stay frozen (penalty law), so the preload vector is used as built, uncalibrated.
   Call after BoltROMOperatorCreate, which sets the ROM's penalties. */
PetscErrorCode BoltROMSetPreloadState(BoltROM *rom, BoltNewmark *nm, PetscReal preloadForce)
{
  BoltContactSet *c = rom->contact;

  PetscFunctionBeginUser;
  if (!rom->preloadState) PetscFunctionReturn(0);
  /* The FOM's traction at its preloaded state is lambda0 + P g0 (its penalty P on the residual
     gaps g0 its loop leaves); the ROM's penalty is s P, so the frozen multipliers take
     lambda0 - (s - 1) P g0: the ROM's traction there is the FOM's, its penalty acts on increments */
  for (PetscInt e = 0; e < c->nelem; e++) {
    const PetscInt pair = c->elem[e].pair;
    for (PetscInt q = 0; q < 4; q++) {
      PetscInt  gp = 4 * e + q;
      PetscReal lam[3], g[3];
      if (!rom->active0[gp]) { /* open in the preload: no traction, and none frozen here */
        c->lambda[3 * gp] = c->lambda[3 * gp + 1] = c->lambda[3 * gp + 2] = 0;
        continue;
      }
      for (PetscInt k = 0; k < 3; k++) {
        lam[k] = rom->lambda0[3 * gp + k] * preloadForce;
        g[k]   = -(1 - 1 / rom->penaltyScale) * rom->gap0[3 * gp + k] * preloadForce;
      }
      BoltContactTrialTraction(lam, g, &c->gpNormal[3 * gp], c->epsN[pair], c->epsT[pair], &c->lambda[3 * gp]);
    }
  }
  PetscCall(BoltContactSetSetActive(c, rom->active0));
  nm->calibratePreload = PETSC_FALSE;
  /* the static state is the FOM's by construction: its active set is not judged again there
     (under the ROM's stiffer penalty, points at the rim whose traction is within the band of
     zero would open on gap differences of a fraction of a nanometre) */
  nm->keepStaticActiveSet = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The tied joint in the Laplace domain at s = s0: (s0^2 M + s0 C + K + K_c) q = f with every
   contact point active, by the FOM (MUMPS) and the ROM (LAPACK). Returns the relative error of
   the ROM at the contact DOFs and the probe: the paper's central claim in its exact form. */
PetscErrorCode BoltROMCheckAtS0(BoltROM *rom, BoltOperator *op, BoltAssembler *asmb, BoltContactSet *c, BoltLoadSet *loads, PetscReal *err)
{
  Mat       A, Ar, Kc, Kcr, C;
  Vec       q, f, qr;
  KSP       ksp, kspr;
  PC        pc;
  PetscReal s0 = rom->s0, num[2] = {0, 0}, den[2] = {0, 0}, pf, pr;
  Vec       ucFull;

  PetscFunctionBeginUser;
  /* ROM first: its contact stiffness takes the (all active, all dirty) state */
  PetscCall(op->contactStiffness(op, &Kcr));
  PetscCall(MatDuplicate(rom->Kr, MAT_COPY_VALUES, &Ar));
  PetscCall(MatAXPY(Ar, s0, rom->Cr, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(Ar, s0 * s0, rom->Mr, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(Ar, 1.0, Kcr, SAME_NONZERO_PATTERN));
  PetscCall(VecDuplicate(rom->loadr, &qr));
  PetscCall(KSPCreate(PETSC_COMM_SELF, &kspr));
  PetscCall(KSPSetOperators(kspr, Ar, Ar));
  PetscCall(KSPSetType(kspr, KSPPREONLY));
  PetscCall(KSPGetPC(kspr, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(KSPSolve(kspr, rom->loadr, qr));
  /* FOM */
  for (PetscInt e = 0; e < c->nelem; e++) c->dirty[e] = PETSC_TRUE;
  PetscCall(BoltContactSetStiffness(c, &Kc));
  PetscCall(BoltAssemblerDamping(asmb, &C));
  PetscCall(MatDuplicate(asmb->K, MAT_COPY_VALUES, &A));
  PetscCall(MatAXPY(A, s0, C, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(A, s0 * s0, asmb->M, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(A, 1.0, Kc, DIFFERENT_NONZERO_PATTERN));
  PetscCall(VecDuplicate(loads->load, &q));
  f = loads->load;
  PetscCall(KSPCreate(rom->comm, &ksp));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSolve(ksp, f, q));
  /* compare at the contact DOFs and the probe */
  PetscCall(BoltContactSetScatter(c, q));
  PetscCall(VecDuplicate(c->uc, &ucFull));
  PetscCall(VecCopy(c->uc, ucFull));
  PetscCall(op->contactDisplacements(op, qr));
  {
    const PetscScalar *a, *b;
    PetscCall(VecGetArrayRead(ucFull, &a));
    PetscCall(VecGetArrayRead(c->uc, &b));
    for (PetscInt i = 0; i < c->nlocal; i++) {
      num[0] += PetscSqr(PetscRealPart(a[i] - b[i]));
      den[0] += PetscSqr(PetscRealPart(a[i]));
    }
    PetscCall(VecRestoreArrayRead(ucFull, &a));
    PetscCall(VecRestoreArrayRead(c->uc, &b));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, num, 1, MPIU_REAL, MPI_SUM, rom->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, den, 1, MPIU_REAL, MPI_SUM, rom->comm));
  PetscCall(BoltLoadSetProbe(loads, q, &pf));
  PetscCall(op->probe(op, qr, &pr));
  *err = PetscMax(PetscSqrtReal(num[0] / den[0]), PetscAbsReal(pr - pf) / PetscAbsReal(pf));
  PetscCall(PetscPrintf(rom->comm, "ROM check at s0 = %g rad/s, tied joint: relative error %.3e at the contact DOFs, %.3e at the probe\n", (double)s0, (double)PetscSqrtReal(num[0] / den[0]), (double)(PetscAbsReal(pr - pf) / PetscAbsReal(pf))));
  PetscCall(VecDestroy(&ucFull));
  PetscCall(VecDestroy(&q));
  PetscCall(VecDestroy(&qr));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(KSPDestroy(&kspr));
  PetscCall(MatDestroy(&A));
  PetscCall(MatDestroy(&Ar));
  PetscCall(MatDestroy(&C));
  PetscFunctionReturn(0);
}
