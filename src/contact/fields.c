/* Fields on the contact DOFs of the geometry: the scatter from the global displacement, gaps and
   forces of a field at the Gauss points, nodal sums across ranks, the element stiffness of the
   penalty, and the nodal states written for ParaView. No state of a solve: the caller's. */
#include "private/contact.h"

static PetscErrorCode BoltContactForcesInto(BoltContactSet *, const PetscReal[], Vec);

/* out = the nodal forces sum w N t of a field t (3 per Gauss point) at the local contact DOFs,
   summed over the elements of every rank (a node on a partition boundary gets both sides). */
static PetscErrorCode BoltContactSetNodalSum(BoltContactSet *c, BoltContactWork *w, const PetscReal t[], PetscReal out[])
{
  const PetscScalar *f;

  PetscFunctionBeginUser;
  PetscCall(BoltContactForcesInto(c, t, w->fcWork));
  PetscCall(VecZeroEntries(w->fGlobal));
  PetscCall(VecScatterBegin(c->scatter, w->fcWork, w->fGlobal, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(c->scatter, w->fcWork, w->fGlobal, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterBegin(c->scatter, w->fGlobal, w->fcWork, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(c->scatter, w->fGlobal, w->fcWork, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(w->fcWork, &f));
  for (PetscInt i = 0; i < c->nlocal; i++) out[i] = PetscRealPart(f[i]);
  PetscCall(VecRestoreArrayRead(w->fcWork, &f));
  PetscFunctionReturn(0);
}

/* The normal traction of the field t (3 per Gauss point) smoothed through the nodes: at each node
   its normal force over its area (both sums w N over the elements around it), interpolated back
   to the Gauss point. The multipliers outnumber the nodes four to one, and the part of them that
   exerts no nodal force is not determined by the discrete problem: near the edge of the contact
   zone it shows as Gauss-point multipliers of tens of MPa of either sign over a compressed node.
   The smoothed traction depends only on the forces the multipliers exert. */
PetscErrorCode BoltContactSetSmoothedNormalTraction(BoltContactSet *c, BoltContactWork *w, const PetscReal t[], PetscReal tn[])
{
  PetscFunctionBeginUser;
  PetscCall(BoltContactSetNodalSum(c, w, t, w->nodalForce));
  for (PetscInt e = 0; e < c->nelem; e++) {
    const PetscInt *loc = &c->elemLocal[24 * e];
    for (PetscInt q = 0; q < 4; q++) {
      PetscInt         gp = 4 * e + q;
      const PetscReal *n = &c->gpNormal[3 * gp], *N = &c->gpN[16 * e + 4 * q];
      PetscReal        sum = 0, wsum = 0;
      for (PetscInt a = 0; a < 4; a++) {
        const PetscInt *ii = loc[12 + 3 * a] >= 0 ? &loc[12 + 3 * a] : &loc[3 * a]; /* side b, or a if b is clamped */
        PetscReal       fn = 0, an = 0;
        if (ii[0] < 0) continue;                                              /* both sides clamped */
        for (PetscInt k = 0; k < 3; k++) {
          fn += w->nodalForce[ii[k]] * n[k];
          an += c->nodalArea[ii[k]] * n[k];
        }
        if (an == 0) continue;
        sum += N[a] * fn / an;
        wsum += N[a];
      }
      tn[gp] = wsum > 0 ? sum / wsum : 0;
    }
  }
  PetscFunctionReturn(0);
}

/* Gauss-point data, the local contact vector and its scatter. layout: a global displacement
   vector. */
PetscErrorCode BoltContactSetSetUpQuadrature(BoltContactSet *c, Vec layout)
{
  PetscInt ne = c->nelem, n = 0, *glob, *perm;
  IS       isGlobal;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc3(16 * ne + 1, &c->gpN, 4 * ne + 1, &c->gpW, 12 * ne + 1, &c->gpNormal));
  PetscCall(PetscMalloc1(24 * ne + 1, &c->elemLocal));
  for (PetscInt e = 0; e < ne; e++) {
    if (c->quadrature == BOLT_QUADRATURE_NODAL) PetscCall(QuadNodalPoints(c->elem[e].Xa, &c->gpN[16 * e], &c->gpW[4 * e], &c->gpNormal[12 * e]));
    else PetscCall(QuadGaussPoints(c->elem[e].Xa, &c->gpN[16 * e], &c->gpW[4 * e], &c->gpNormal[12 * e]));
  }
  /* local contact vector: the distinct global DOFs the local elements touch */
  PetscCall(PetscMalloc2(24 * ne + 1, &glob, 24 * ne + 1, &perm));
  for (PetscInt e = 0; e < ne; e++)
    for (PetscInt k = 0; k < 24; k++)
      if (c->elem[e].dofs[k] >= 0) glob[n++] = c->elem[e].dofs[k];
  PetscCall(PetscSortRemoveDupsInt(&n, glob));
  c->nlocal = n;
  PetscCall(PetscMalloc1(n + 1, &c->localGlobal));
  PetscCall(PetscArraycpy(c->localGlobal, glob, n));
  for (PetscInt e = 0; e < ne; e++)
    for (PetscInt k = 0; k < 24; k++) {
      PetscInt d = c->elem[e].dofs[k], loc = -1;
      if (d >= 0) PetscCall(PetscFindInt(d, n, c->localGlobal, &loc));
      c->elemLocal[24 * e + k] = loc;
    }
  PetscCall(PetscFree2(glob, perm));
  {
    Vec             uc;
    BoltContactWork *w;
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &uc));
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, n, c->localGlobal, PETSC_COPY_VALUES, &isGlobal));
    PetscCall(VecScatterCreate(layout, isGlobal, uc, NULL, &c->scatter));
    PetscCall(ISDestroy(&isGlobal));
    PetscCall(VecDestroy(&uc));
    PetscCall(VecDuplicate(layout, &c->layout));
    PetscCall(PetscMalloc1(n + 1, &c->nodalArea));
    PetscCall(BoltContactWorkCreate(c, &w));
    PetscCall(BoltContactSetNodalSum(c, w, c->gpNormal, c->nodalArea));
    PetscCall(BoltContactWorkDestroy(&w));
  }
  {
    PetscInt ngp = 4 * ne;
    PetscCall(MPIU_Allreduce(&ngp, &c->ngpGlobal, 1, MPIU_INT, MPI_SUM, BoltMeshComm(c->mesh)));
  }
  PetscFunctionReturn(0);
}

/* An empty K_c in the global layout with the fixed pattern of all contact elements: one COO
   entry per element matrix entry, so a state's element matrices are inserted as they are. */
PetscErrorCode BoltContactSetStiffnessMatrix(BoltContactSet *c, Mat *Kc)
{
  PetscInt ne = c->nelem, *ci, *cj, ncoo = 576 * ne, m, M;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(c->layout, &m));
  PetscCall(VecGetSize(c->layout, &M));
  PetscCall(MatCreate(BoltMeshComm(c->mesh), Kc));
  PetscCall(MatSetSizes(*Kc, m, m, M, M));
  PetscCall(MatSetType(*Kc, MATAIJ));
  PetscCall(PetscObjectSetName((PetscObject)*Kc, "Kc"));
  PetscCall(PetscMalloc2(ncoo + 1, &ci, ncoo + 1, &cj));
  for (PetscInt e = 0; e < ne; e++)
    for (PetscInt i = 0; i < 24; i++)
      for (PetscInt j = 0; j < 24; j++) {
        ci[576 * e + 24 * i + j] = c->elem[e].dofs[i];
        cj[576 * e + 24 * i + j] = c->elem[e].dofs[j];
      }
  PetscCall(MatSetPreallocationCOO(*Kc, ncoo, ci, cj));
  PetscCall(PetscFree2(ci, cj));
  PetscFunctionReturn(0);
}

/* Element e's 24x24 penalty matrix over its active points, in the set's quadrature, without the
   tangential penalty at released points (but, where friction makes them slip, a stiffness across
   their slip directions: slipDir, 4 values a point, the direction and the stiffness) (the Gauss points' is computed as it always was, so
   that the stick law's results keep their bits). */
PetscErrorCode BoltContactSetElementStiffness(BoltContactSet *c, PetscInt e, PetscReal epsN, PetscReal epsT, const PetscBool active[], const PetscBool released[], const PetscReal slipDir[], PetscReal Ke[576])
{
  PetscBool anyReleased = PETSC_FALSE;

  PetscFunctionBeginUser;
  for (PetscInt q = 0; q < 4; q++) anyReleased = (PetscBool)(anyReleased || released[q]);
  if (c->quadrature == BOLT_QUADRATURE_GAUSS && !anyReleased) PetscCall(QuadPairPenaltyStiffnessActive(c->elem[e].Xa, epsN, epsT, active, Ke));
  else PetscCall(QuadPairPenaltyStiffnessPoints(&c->gpN[16 * e], &c->gpW[4 * e], &c->gpNormal[12 * e], epsN, epsT, active, released, slipDir, Ke));
  PetscFunctionReturn(0);
}

/* The work space's uc <- the contact DOFs of a global displacement vector (the FOM's way). */
PetscErrorCode BoltContactSetScatter(BoltContactSet *c, BoltContactWork *w, Vec u)
{
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(c->scatter, u, w->uc, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(c->scatter, u, w->uc, INSERT_VALUES, SCATTER_FORWARD));
  PetscFunctionReturn(0);
}

/* The gaps at every point of the work space's contact displacements uc. */
PetscErrorCode BoltContactSetGapsOf(BoltContactSet *c, BoltContactWork *w, PetscReal gap[])
{
  const PetscScalar *u;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(w->uc, &u));
  for (PetscInt e = 0; e < c->nelem; e++) {
    const PetscInt *loc = &c->elemLocal[24 * e];
    for (PetscInt q = 0; q < 4; q++) {
      const PetscReal *N = &c->gpN[16 * e + 4 * q];
      PetscReal       *g = &gap[12 * e + 3 * q];
      for (PetscInt k = 0; k < 3; k++) {
        PetscReal v = 0;
        for (PetscInt a = 0; a < 4; a++) {
          PetscInt ia = loc[3 * a + k], ib = loc[12 + 3 * a + k];
          v += N[a] * ((ib >= 0 ? PetscRealPart(u[ib]) : 0) - (ia >= 0 ? PetscRealPart(u[ia]) : 0));
        }
        g[k] = v;
      }
    }
  }
  PetscCall(VecRestoreArrayRead(w->uc, &u));
  PetscFunctionReturn(0);
}

/* F = B' lambda: the nodal forces of the tractions lambda (3 per point) in the global layout of
   F, both sides of every pair. */
PetscErrorCode BoltContactSetForcesOf(BoltContactSet *c, BoltContactWork *w, const PetscReal lambda[], Vec F)
{
  PetscFunctionBeginUser;
  PetscCall(BoltContactForcesInto(c, lambda, w->fc));
  PetscCall(VecZeroEntries(F));
  PetscCall(VecScatterBegin(c->scatter, w->fc, F, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(c->scatter, w->fc, F, ADD_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

/* The contact state at the nodes, for the output: in F (global layout, 3 per node) the weights
   sum N_a of the node's open, sticking and slipping points (x, y and z: one per point with nodal
   quadrature), on both sides of each pair. codes: each local point's (BoltContactStatePointCodes). */
PetscErrorCode BoltContactSetNodalStates(BoltContactSet *c, BoltContactWork *w, const unsigned char codes[], Vec F)
{
  PetscScalar *f;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(w->fc));
  PetscCall(VecGetArray(w->fc, &f));
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
    const PetscInt  *loc = &c->elemLocal[24 * (gp / 4)];
    const PetscReal *N   = &c->gpN[4 * gp];
    for (PetscInt a = 0; a < 4; a++) {
      const PetscInt ia = loc[3 * a + codes[gp]], ib = loc[12 + 3 * a + codes[gp]];
      if (ia >= 0) f[ia] += N[a];
      if (ib >= 0) f[ib] += N[a];
    }
  }
  PetscCall(VecRestoreArray(w->fc, &f));
  PetscCall(VecZeroEntries(F));
  PetscCall(VecScatterBegin(c->scatter, w->fc, F, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(c->scatter, w->fc, F, ADD_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

/* The nodal forces sum_q w N_a lambda_q of element e's Gauss-point tractions on its side-b nodes
   (3 per node, 12); side a takes their opposite. */
void BoltContactElementForces(BoltContactSet *c, PetscInt e, const PetscReal lambda[], PetscReal fb[12])
{
  for (PetscInt k = 0; k < 12; k++) fb[k] = 0;
  for (PetscInt q = 0; q < 4; q++) {
    const PetscInt   gp = 4 * e + q;
    const PetscReal *N = &c->gpN[16 * e + 4 * q], *lam = &lambda[3 * gp], w = c->gpW[gp];
    if (lam[0] == 0 && lam[1] == 0 && lam[2] == 0) continue;
    for (PetscInt a = 0; a < 4; a++)
      for (PetscInt k = 0; k < 3; k++) fb[3 * a + k] += w * N[a] * lam[k];
  }
}

static PetscErrorCode BoltContactForcesInto(BoltContactSet *c, const PetscReal lambda[], Vec fc)
{
  PetscScalar *f;
  PetscReal    fb[12];

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(fc));
  PetscCall(VecGetArray(fc, &f));
  for (PetscInt e = 0; e < c->nelem; e++) {
    const PetscInt *loc = &c->elemLocal[24 * e];
    BoltContactElementForces(c, e, lambda, fb);
    for (PetscInt k = 0; k < 12; k++) {
      PetscInt ia = loc[k], ib = loc[12 + k];
      if (ia >= 0) f[ia] -= fb[k];
      if (ib >= 0) f[ib] += fb[k];
    }
  }
  PetscCall(VecRestoreArray(fc, &f));
  PetscFunctionReturn(0);
}

/* With a clamp, every part must be held: clamped itself, or joined to a held part by shared
   nodes or a contact pair. A part that is not floats, and every solve with it is singular. */
PetscErrorCode BoltContactSetCheckSupport(BoltContactSet *c)
{
  BoltMesh    *m  = c->mesh;
  PetscInt     np = BoltMeshPartCount(m), nv, *verts, held[BOLTROM_MAX_PARTS], adj[BOLTROM_MAX_PARTS][BOLTROM_MAX_PARTS];
  DM           dmv;
  PetscSection s;
  Vec          loc, ind[BOLTROM_MAX_PARTS + 1];
  PetscInt     pStart, pEnd, vStart, vEnd, cStart, cEnd;
  const char  *clampGroup = BoltMeshClampGroup(m);

  PetscFunctionBeginUser;
  if (!clampGroup) PetscFunctionReturn(0);
  PetscCall(DMPlexGetChart(BoltMeshDM(m), &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(BoltMeshDM(m), 0, &vStart, &vEnd));
  PetscCall(DMPlexGetHeightStratum(BoltMeshDM(m), 0, &cStart, &cEnd));
  /* one indicator per part (and one for the clamp) on the vertices, summed over the ranks */
  PetscCall(DMClone(BoltMeshDM(m), &dmv));
  PetscCall(PetscSectionCreate(BoltMeshComm(m), &s));
  PetscCall(PetscSectionSetChart(s, pStart, pEnd));
  for (PetscInt v = vStart; v < vEnd; v++) PetscCall(PetscSectionSetDof(s, v, 1));
  PetscCall(PetscSectionSetUp(s));
  PetscCall(DMSetLocalSection(dmv, s));
  PetscCall(DMCreateLocalVector(dmv, &loc));
  for (PetscInt p = 0; p <= np; p++) {
    PetscScalar *a;
    PetscCall(VecZeroEntries(loc));
    PetscCall(VecGetArray(loc, &a));
    if (p < np) {
      for (PetscInt cell = cStart; cell < cEnd; cell++) {
        PetscInt cv[8], off;
        if (BoltMeshCellPart(m, cell) != p) continue;
        PetscCall(BoltMeshCellVertices(m, cell, cv));
        for (PetscInt k = 0; k < 8; k++) {
          PetscCall(PetscSectionGetOffset(s, cv[k], &off));
          a[off] = 1;
        }
      }
    } else {
      PetscCall(BoltMeshGroupVertices(m, clampGroup, PETSC_FALSE, &nv, &verts));
      for (PetscInt k = 0; k < nv; k++) {
        PetscInt off;
        PetscCall(PetscSectionGetOffset(s, verts[k], &off));
        a[off] = 1;
      }
      PetscCall(PetscFree(verts));
    }
    PetscCall(VecRestoreArray(loc, &a));
    PetscCall(DMCreateGlobalVector(dmv, &ind[p]));
    PetscCall(VecZeroEntries(ind[p]));
    PetscCall(DMLocalToGlobal(dmv, loc, ADD_VALUES, ind[p]));
  }
  for (PetscInt p = 0; p < np; p++) {
    PetscScalar d;
    PetscCall(VecDot(ind[p], ind[np], &d));
    held[p] = PetscRealPart(d) > 0;
    for (PetscInt q = 0; q < np; q++) {
      PetscCall(VecDot(ind[p], ind[q], &d));
      adj[p][q] = p != q && PetscRealPart(d) > 0;
    }
  }
  for (PetscInt k = 0; k < c->npairs; k++) adj[c->pairPart[k][0]][c->pairPart[k][1]] = adj[c->pairPart[k][1]][c->pairPart[k][0]] = 1;
  for (PetscBool grew = PETSC_TRUE; grew;) { /* spread the support along the joins */
    grew = PETSC_FALSE;
    for (PetscInt p = 0; p < np; p++)
      for (PetscInt q = 0; q < np && !held[p]; q++)
        if (held[q] && adj[p][q]) held[p] = grew = PETSC_TRUE;
  }
  for (PetscInt p = 0; p <= np; p++) PetscCall(VecDestroy(&ind[p]));
  PetscCall(VecDestroy(&loc));
  PetscCall(PetscSectionDestroy(&s));
  PetscCall(DMDestroy(&dmv));
  for (PetscInt p = 0; p < np; p++)
    PetscCheck(held[p], BoltMeshComm(m), PETSC_ERR_USER_INPUT, "Part %s is held by neither the clamp group '%s' nor, through shared nodes or contact pairs (contact_<pair>_a/_b), by a part that is: it would float free; extend the clamp group, add a contact pair, or run free-free with -clamp false", BoltMeshPartName(m, p), clampGroup);
  PetscFunctionReturn(0);
}

/* A work space over the set (after its quadrature is set up). */
PetscErrorCode BoltContactWorkCreate(BoltContactSet *c, BoltContactWork **wp)
{
  BoltContactWork *w;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&w));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, c->nlocal, &w->uc));
  PetscCall(VecDuplicate(w->uc, &w->fc));
  PetscCall(VecDuplicate(w->uc, &w->fcWork));
  PetscCall(VecDuplicate(c->layout, &w->fGlobal));
  PetscCall(PetscMalloc2(c->nlocal + 1, &w->nodalForce, 12 * c->nelem + 1, &w->tau));
  *wp = w;
  PetscFunctionReturn(0);
}

/* The local contact displacements (the work space's: an operator fills them). */
PetscErrorCode BoltContactWorkGetDisplacements(BoltContactWork *w, Vec *uc)
{
  PetscFunctionBeginUser;
  *uc = w->uc;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltContactWorkDestroy(BoltContactWork **wp)
{
  PetscFunctionBeginUser;
  if (!*wp) PetscFunctionReturn(0);
  PetscCall(VecDestroy(&(*wp)->uc));
  PetscCall(VecDestroy(&(*wp)->fc));
  PetscCall(VecDestroy(&(*wp)->fcWork));
  PetscCall(VecDestroy(&(*wp)->fGlobal));
  PetscCall(PetscFree2((*wp)->nodalForce, (*wp)->tau));
  PetscCall(PetscFree(*wp));
  PetscFunctionReturn(0);
}
