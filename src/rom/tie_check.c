/* The check of a trained ROM's tied pairs. A tie holds its node pair inside the basis, so the
   pair's gap stays what the preloaded state made it and cannot say whether the pair would open
   or slip. Its force can: the pair carries what the full model's residual lacks at its DOFs,
   r = f - M a - C v - K u (with nodal quadrature no other pair's traction reaches those DOFs),
   side b taking W t and side a -W t for the pair's traction t over its nodal area W. The rows of
   K V and M V at the tied DOFs, made once at set-up, give r for the cost of those rows. */
#include "private/rom.h"

struct BoltROMTieCheck_s {
  PetscInt   nrows;      /* tied DOFs this rank owns */
  PetscInt  *dof;        /* their global indices */
  PetscReal *KV, *MV;    /* nrows x n, row-major: their rows of K V and M V */
  PetscReal *load, *pre; /* their entries of the load and of the preload */
  Vec        r;          /* the residual at the owned tied DOFs, 0 elsewhere (the full layout) */
  BoltContactWork *work; /* r at the local contact DOFs (its own: the state's holds V_c q) */
  PetscReal *y;          /* 2n: q + beta v, a + alpha v */
  PetscBool *point;      /* per local contact point: its pair is tied */
  PetscReal *t;          /* 3 per local contact point: a tied point's traction */
};

/* rows[i * n + j] = (A V)[dof_i, j] for the owned tied DOFs (a submatrix of A's rows, times each
   column of V). */
static PetscErrorCode ROMTieRows(Mat A, BV V, PetscInt n, IS rows, IS cols, PetscReal out[])
{
  Mat                As;
  Vec                w;
  const PetscScalar *x;
  PetscInt           m;

  PetscFunctionBeginUser;
  PetscCall(MatCreateSubMatrix(A, rows, cols, MAT_INITIAL_MATRIX, &As));
  PetscCall(MatCreateVecs(As, NULL, &w));
  PetscCall(VecGetLocalSize(w, &m));
  for (PetscInt j = 0; j < n; j++) {
    Vec v;
    PetscCall(BVGetColumn(V, j, &v));
    PetscCall(MatMult(As, v, w));
    PetscCall(BVRestoreColumn(V, j, &v));
    PetscCall(VecGetArrayRead(w, &x));
    for (PetscInt i = 0; i < m; i++) out[i * n + j] = PetscRealPart(x[i]);
    PetscCall(VecRestoreArrayRead(w, &x));
  }
  PetscCall(VecDestroy(&w));
  PetscCall(MatDestroy(&As));
  PetscFunctionReturn(0);
}

/* The tied pairs' rows, with the whole basis (built, or read from the ROM file; none: no check
   of the ties). The preload's entries are those of the preload as built: its layer forces act
   inside the bolts, away from the contact pairs. */
PetscErrorCode ROMTieCheckSetUp(BoltROM *rom, BoltAssembler *asmb, BoltLoadSet *loads)
{
  BoltContactSet          *c  = rom->contact;
  const PetscInt           np = 4 * BoltContactSetElementCount(c), n = rom->n;
  struct BoltROMTieCheck_s *tc;
  PetscInt                 ntie, *hp, *tiedB, rstart, rend, nloc;
  Mat                      K, M;
  IS                       rows, cols;
  Vec                      layout = BoltLoadSetLoad(loads);
  const PetscScalar       *f, *p;
  BoltMesh                *mesh;
  BV                       V;
  PetscBool                whole;

  PetscFunctionBeginUser;
  PetscCall(ROMTieCheckDestroy(rom));
  PetscCall(BoltAssemblerGetMesh(asmb, &mesh));
  PetscCall(BoltROMBasisEnsure(rom, mesh, layout, &whole));
  PetscCall(ROMGetBasis(rom, &V));
  if (!V) PetscFunctionReturn(0);
  PetscCall(PetscNew(&tc));
  rom->tie = tc;
  PetscCall(ROMTiedPairs(rom, c, &ntie, &hp, NULL));
  PetscCall(VecGetOwnershipRange(layout, &rstart, &rend));
  PetscCall(PetscMalloc1(6 * ntie + 1, &tc->dof));
  PetscCall(PetscMalloc1(ntie + 1, &tiedB));
  for (PetscInt i = 0; i < ntie; i++) {
    tiedB[i] = hp[2 * i + 1];
    for (PetscInt s = 0; s < 2; s++)
      for (PetscInt d = 0; d < 3 && hp[2 * i + s] >= 0; d++)
        if (hp[2 * i + s] + d >= rstart && hp[2 * i + s] + d < rend) tc->dof[tc->nrows++] = hp[2 * i + s] + d;
  }
  PetscCall(PetscFree(hp));
  PetscCall(PetscSortRemoveDupsInt(&tc->nrows, tc->dof));
  PetscCall(PetscSortInt(ntie, tiedB));
  /* which local points are at a tied pair (with nodal quadrature, a point is at its own node) */
  PetscCall(PetscMalloc2(np + 1, &tc->point, 3 * np + 1, &tc->t));
  for (PetscInt gp = 0; gp < np; gp++) {
    const PetscInt lb = BoltContactSetElementLocal(c)[24 * (gp / 4) + 12 + 3 * (gp % 4)];
    PetscInt       at = -1;
    if (lb >= 0) PetscCall(PetscFindInt(BoltContactSetLocalGlobal(c)[lb], ntie, tiedB, &at));
    tc->point[gp] = (PetscBool)(at >= 0);
  }
  PetscCall(PetscFree(tiedB));
  PetscCall(PetscMalloc4(tc->nrows * n + 1, &tc->KV, tc->nrows * n + 1, &tc->MV, tc->nrows + 1, &tc->load, tc->nrows + 1, &tc->pre));
  PetscCall(PetscMalloc1(2 * n + 1, &tc->y));
  PetscCall(BoltAssemblerGetMatrices(asmb, &K, &M));
  PetscCall(VecGetLocalSize(layout, &nloc));
  PetscCall(ISCreateGeneral(rom->comm, tc->nrows, tc->dof, PETSC_USE_POINTER, &rows));
  PetscCall(ISCreateStride(rom->comm, nloc, rstart, 1, &cols));
  PetscCall(ROMTieRows(K, V, n, rows, cols, tc->KV));
  PetscCall(ROMTieRows(M, V, n, rows, cols, tc->MV));
  PetscCall(ISDestroy(&rows));
  PetscCall(ISDestroy(&cols));
  PetscCall(VecGetArrayRead(layout, &f));
  PetscCall(VecGetArrayRead(BoltLoadSetPreload(loads), &p));
  for (PetscInt i = 0; i < tc->nrows; i++) {
    tc->load[i] = PetscRealPart(f[tc->dof[i] - rstart]);
    tc->pre[i]  = PetscRealPart(p[tc->dof[i] - rstart]);
  }
  PetscCall(VecRestoreArrayRead(layout, &f));
  PetscCall(VecRestoreArrayRead(BoltLoadSetPreload(loads), &p));
  PetscCall(VecDuplicate(layout, &tc->r));
  PetscCall(BoltContactWorkCreate(c, &tc->work));
  PetscFunctionReturn(0);
}

PetscErrorCode ROMTieCheckDestroy(BoltROM *rom)
{
  struct BoltROMTieCheck_s *tc = rom->tie;

  PetscFunctionBeginUser;
  if (!tc) PetscFunctionReturn(0);
  PetscCall(PetscFree(tc->dof));
  PetscCall(PetscFree4(tc->KV, tc->MV, tc->load, tc->pre));
  PetscCall(PetscFree(tc->y));
  PetscCall(PetscFree2(tc->point, tc->t));
  PetscCall(VecDestroy(&tc->r));
  PetscCall(BoltContactWorkDestroy(&tc->work));
  PetscCall(PetscFree(rom->tie));
  PetscFunctionReturn(0);
}

/* The operator's BOLT_OP_HELD_TRACTIONS: the traction of every point at a tied pair, from the
   residual at its DOFs (q, v, a the ROM's, amp the load's amplitude). Collective. */
PetscErrorCode ROMHeldTractions(BoltOperator *op, Vec q, Vec v, Vec a, PetscReal amp, const PetscBool **tied, const PetscReal **t)
{
  BoltROM                  *rom = (BoltROM *)BoltOperatorContext(op);
  struct BoltROMTieCheck_s *tc  = rom->tie;
  BoltContactSet           *c   = rom->contact;
  BoltContactWork          *w;
  const PetscInt            n   = rom->n, np = 4 * BoltContactSetElementCount(c);
  const PetscScalar        *xq, *xv, *xa, *u;
  PetscScalar              *r;
  PetscInt                  rstart;

  PetscFunctionBeginUser;
  *tied = NULL;
  *t    = NULL;
  if (!tc) PetscFunctionReturn(0);
  w = tc->work;
  PetscCall(VecGetArrayRead(q, &xq));
  PetscCall(VecGetArrayRead(v, &xv));
  PetscCall(VecGetArrayRead(a, &xa));
  for (PetscInt j = 0; j < n; j++) {
    tc->y[j]     = PetscRealPart(xq[j] + rom->rayleigh[1] * xv[j]);
    tc->y[n + j] = PetscRealPart(xa[j] + rom->rayleigh[0] * xv[j]);
  }
  PetscCall(VecRestoreArrayRead(q, &xq));
  PetscCall(VecRestoreArrayRead(v, &xv));
  PetscCall(VecRestoreArrayRead(a, &xa));
  PetscCall(VecZeroEntries(tc->r));
  PetscCall(VecGetOwnershipRange(tc->r, &rstart, NULL));
  PetscCall(VecGetArray(tc->r, &r));
  for (PetscInt i = 0; i < tc->nrows; i++) {
    PetscReal ri = amp * tc->load[i] + tc->pre[i];
    for (PetscInt j = 0; j < n; j++) ri -= tc->KV[i * n + j] * tc->y[j] + tc->MV[i * n + j] * tc->y[n + j];
    r[tc->dof[i] - rstart] = ri;
  }
  PetscCall(VecRestoreArray(tc->r, &r));
  PetscCall(BoltContactSetScatter(c, w, tc->r));
  {
    Vec uc;
    PetscCall(BoltContactWorkGetDisplacements(w, &uc));
    PetscCall(VecGetArrayRead(uc, &u));
    for (PetscInt gp = 0; gp < np; gp++) {
      const PetscInt *loc = &BoltContactSetElementLocal(c)[24 * (gp / 4) + 3 * (gp % 4)];
      PetscReal       A2 = 0;
      if (!tc->point[gp]) continue;
      for (PetscInt k = 0; k < 3; k++) A2 += PetscSqr(BoltContactSetNodalArea(c)[loc[12 + k]]);
      for (PetscInt k = 0; k < 3; k++) {
        const PetscReal rb = PetscRealPart(u[loc[12 + k]]), ra = loc[k] >= 0 ? PetscRealPart(u[loc[k]]) : -rb;
        tc->t[3 * gp + k] = 0.5 * (rb - ra) / PetscSqrtReal(A2);
      }
    }
    PetscCall(VecRestoreArrayRead(uc, &u));
  }
  *tied = tc->point;
  *t    = tc->t;
  PetscFunctionReturn(0);
}
