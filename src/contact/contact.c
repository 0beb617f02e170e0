/* Contact set: the pairs of matching quad faces named contact_<pair>_a / contact_<pair>_b,
   found in parallel by node coordinates, with their penalties and element matrices. Each
   element is kept by the rank that owns its face a; the DOFs of side b are global indices,
   so the element's matrix is assembled straight into the distributed system. */
#include "boltrom.h"

PetscErrorCode BoltContactSetCreate(BoltMesh *mesh, BoltContactSet **cs)
{
  BoltContactSet *c;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  c->mesh           = mesh;
  c->augment        = PETSC_TRUE;
  PetscCall(PetscStrncpy(c->lawType, "strict", sizeof(c->lawType)));
  c->activationGap  = -1; /* the law's default: SetFromOptions and SetUp fill it in */
  c->matchTolerance = 1e-6;
  c->reanchor       = PETSC_TRUE; /* the strict law's re-closing pairs stick where they close */
  c->frictionDefault = 0.3;
  c->slipAngleTolerance = 1e-2;
  c->slipStiffnessRatio = 1.1;
  c->stickFactor        = 200;
  *cs               = c;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltContactSetSetFromOptions(BoltContactSet *c)
{
  BoltContactLaw *law = &c->law;
  const char     *quad[] = {"gauss", "nodal"};
  PetscBool      set;

  PetscFunctionBeginUser;
  PetscCall(BoltContactLawRegisterAll());
  PetscOptionsBegin(c->mesh->comm, NULL, "Contact", "boltrom");
  PetscCall(PetscOptionsFList("-contact_law", "Contact law: strict (one-sided contact at every node pair, closed pairs stick; active-set loop), coulomb (strict, with Coulomb friction: closed pairs stick inside the cone and slip on it; -contact_friction) or stick (the paper's: Gauss points, opening band, penalty 200 E/m)", "BoltContactLaw", BoltContactLawList, c->lawType, c->lawType, sizeof(c->lawType), NULL));
  PetscCall(BoltContactLawSetType(c->mesh->comm, c->lawType, law)); /* an unknown law fails here, before any solve */
  c->penaltyFactor = law->penaltyFactor;
  c->quadrature    = law->strict ? BOLT_QUADRATURE_NODAL : BOLT_QUADRATURE_GAUSS;
  PetscCall(PetscOptionsReal("-contact_penalty_factor", "Normal and tangential penalty as a multiple of the softer part's E, per metre [1/m] (default: the law's, strict 3e7, coulomb 1e6, stick 200)", NULL, c->penaltyFactor, &c->penaltyFactor, NULL));
  {
    const char *const reclose[] = {"slide", "stick"};
    PetscInt          rule      = c->reanchor ? 1 : 0;
    PetscCall(PetscOptionsEList("-contact_reclose", "Strict law: a pair that opened and closes again sticks where it closes (stick) or slides from then on (slide)", NULL, reclose, 2, reclose[rule], &rule, NULL));
    c->reanchor = rule == 1 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(PetscOptionsEList("-contact_quadrature", "Contact points: nodal (one per node pair and face, the strict law's default) or gauss (2x2 per face pair, the stick law's)", NULL, quad, 2, quad[c->quadrature], &c->quadrature, NULL));
  PetscCall(PetscOptionsBool("-contact_augment", "Augmented Lagrangian (false: pure penalty, no multipliers)", NULL, c->augment, &c->augment, NULL));
  {
    const char *open[] = {"nodal", "gauss"};
    PetscCall(PetscOptionsEList("-contact_open_test", "Stick law: when a closed point opens: nodal (its normal traction smoothed through the nodes, nodal force / nodal area, is tensile beyond the band) or gauss (its own multiplier is)", NULL, open, 2, open[c->openTest], &c->openTest, NULL));
  }
  if (c->activationGap < 0 && !law->strict) c->activationGap = 1e-7; /* strict: -1 until SetUp knows the mesh */
  PetscCall(PetscOptionsReal("-contact_activation_gap", "An open point closes when it penetrates by more than this [m] (default: strict 1e-9 x the shortest contact-face edge, stick 1e-7)", NULL, c->activationGap, &c->activationGap, &set));
  PetscCall(PetscOptionsReal("-contact_match_tolerance", "Node matching tolerance, relative to the face's shortest edge", NULL, c->matchTolerance, &c->matchTolerance, NULL));
  PetscCall(PetscOptionsReal("-contact_friction", "Coulomb friction coefficient of every pair (-contact_law coulomb; -contact_<pair>_friction sets one pair)", NULL, c->frictionDefault, &c->frictionDefault, &c->frictionSet));
  PetscCall(PetscOptionsReal("-contact_slip_angle_tolerance", "Coulomb friction: K_c keeps a slipping pair's slip direction until its slip turns by more than this [rad] (a quasi-Newton step: the converged traction is on the cone along the slip whatever it is)", NULL, c->slipAngleTolerance, &c->slipAngleTolerance, NULL));
  PetscCall(PetscOptionsReal("-contact_slip_stiffness_ratio", "Coulomb friction: K_c takes a slipping pair's new stiffness across its slip (mu |t_N| / |slip|) once the one it has is off by more than this factor", NULL, c->slipStiffnessRatio, &c->slipStiffnessRatio, NULL));
  PetscCall(PetscOptionsReal("-contact_stick_stiffness_factor", "Coulomb friction: tangential stiffness of a sticking pair (elastic stick, as the stick law's penalty and CalculiX's stick slope), x E of the softer part per metre [1/m]", NULL, c->stickFactor, &c->stickFactor, NULL));
  PetscOptionsEnd();
  PetscCheck(c->stickFactor > 0, c->mesh->comm, PETSC_ERR_USER_INPUT, "-contact_stick_stiffness_factor must be > 0 (got %g)", (double)c->stickFactor);
  PetscCheck(c->slipStiffnessRatio > 1, c->mesh->comm, PETSC_ERR_USER_INPUT, "-contact_slip_stiffness_ratio must be > 1 (got %g)", (double)c->slipStiffnessRatio);
  PetscCheck(c->slipAngleTolerance > 0, c->mesh->comm, PETSC_ERR_USER_INPUT, "-contact_slip_angle_tolerance must be > 0 (got %g)", (double)c->slipAngleTolerance);
  PetscCheck(!c->frictionSet || law->friction, c->mesh->comm, PETSC_ERR_USER_INPUT, "-contact_friction needs a frictional law: add -contact_law coulomb (the %s law has no Coulomb limit)", c->lawType);
  PetscCheck(!law->friction || c->reanchor, c->mesh->comm, PETSC_ERR_USER_INPUT, "-contact_reclose slide is frictionless sliding: drop it with -contact_law coulomb (a pair that closes again sticks, then slips by friction)");
  PetscCheck(c->frictionDefault >= 0, c->mesh->comm, PETSC_ERR_USER_INPUT, "-contact_friction must be >= 0 (got %g)", (double)c->frictionDefault);
  PetscCheck(c->penaltyFactor > 0, c->mesh->comm, PETSC_ERR_USER_INPUT, "-contact_penalty_factor must be > 0 (got %g)", (double)c->penaltyFactor);
  PetscCheck(!set || c->activationGap >= 0, c->mesh->comm, PETSC_ERR_USER_INPUT, "-contact_activation_gap must be >= 0 (got %g)", (double)c->activationGap);
  PetscCheck(!law->strict || c->augment, c->mesh->comm, PETSC_ERR_USER_INPUT, "The strict contact law closes gaps by its multipliers: drop -contact_augment false, or use -contact_law stick for the penalty law");
  PetscFunctionReturn(0);
}

/* Pair names from the labels contact_<pair>_a on rank 0, broadcast so all ranks agree. */
static PetscErrorCode BoltContactFindPairs(BoltContactSet *c)
{
  BoltMesh   *m = c->mesh;
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(m->comm, &rank));
  c->npairs = 0;
  if (rank == 0) {
    PetscInt nlabels;
    PetscCall(DMGetNumLabels(m->dm, &nlabels));
    for (PetscInt l = 0; l < nlabels; l++) {
      const char *name;
      size_t      len;
      PetscBool   pre;

      PetscCall(DMGetLabelName(m->dm, l, &name));
      PetscCall(PetscStrlen(name, &len));
      PetscCall(PetscStrncmp(name, "contact_", 8, &pre));
      if (!pre || len < 11 || name[len - 2] != '_' || name[len - 1] != 'a') continue;
      PetscCheck(c->npairs < BOLTROM_MAX_PAIRS, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "More than %d contact pairs", BOLTROM_MAX_PAIRS);
      PetscCall(PetscStrncpy(c->pairName[c->npairs], name + 8, len - 9));
      c->npairs++;
    }
  }
  PetscCallMPI(MPI_Bcast(&c->npairs, 1, MPIU_INT, 0, m->comm));
  PetscCallMPI(MPI_Bcast(c->pairName, BOLTROM_MAX_PAIRS * BOLTROM_NAME_LEN, MPI_CHAR, 0, m->comm));
  for (PetscInt p = 0; p < c->npairs; p++) {
    char      nb[BOLTROM_NAME_LEN + 16];
    PetscBool has;

    PetscCall(PetscSNPrintf(nb, sizeof(nb), "contact_%s_b", c->pairName[p]));
    PetscCall(BoltMeshHasGroup(m, nb, &has));
    PetscCheck(has, m->comm, PETSC_ERR_USER_INPUT, "Contact pair %s has side a (contact_%s_a) but no side b: add the physical surface group %s", c->pairName[p], c->pairName[p], nb);
  }
  PetscFunctionReturn(0);
}

typedef struct {
  PetscReal x[3];
  PetscInt  dofs[3];
} BoltNode;

static int BoltNodeCompareX(const void *a, const void *b)
{
  PetscReal xa = ((const BoltNode *)a)->x[0], xb = ((const BoltNode *)b)->x[0];
  return (xa > xb) - (xa < xb);
}

/* All owned vertices of a group, from every rank, sorted by x. */
static PetscErrorCode BoltContactGatherNodes(BoltContactSet *c, const char group[], PetscInt *nnodes, BoltNode **nodes)
{
  BoltMesh          *m = c->mesh;
  PetscInt           nv, *verts, ntot = 0;
  BoltNode          *mine, *all;
  Vec                coords;
  PetscSection       cs;
  const PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(BoltMeshGroupVertices(m, group, PETSC_TRUE, &nv, &verts));
  PetscCall(PetscMalloc1(nv + 1, &mine));
  PetscCall(DMGetCoordinatesLocal(m->dm, &coords));
  PetscCall(DMGetCoordinateSection(m->dm, &cs));
  PetscCall(VecGetArrayRead(coords, &x));
  for (PetscInt i = 0; i < nv; i++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(cs, verts[i], &off));
    for (PetscInt d = 0; d < 3; d++) mine[i].x[d] = PetscRealPart(x[off + d]);
    PetscCall(BoltMeshVertexDofs(m, verts[i], mine[i].dofs));
  }
  PetscCall(VecRestoreArrayRead(coords, &x));
  PetscCall(PetscFree(verts));
  PetscCall(BoltGatherAll(m->comm, MPI_BYTE, mine, nv * (PetscInt)sizeof(BoltNode), &all, NULL, &ntot, NULL));
  ntot /= (PetscInt)sizeof(BoltNode);
  qsort(all, (size_t)ntot, sizeof(BoltNode), BoltNodeCompareX);
  PetscCall(PetscFree(mine));
  *nnodes = ntot;
  *nodes  = all;
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltContactFindNode(PetscInt n, const BoltNode *nodes, const PetscReal x[3], PetscReal tol, const BoltNode **found)
{
  PetscInt lo = 0, hi = n;

  PetscFunctionBeginUser;
  *found = NULL;
  while (lo < hi) { /* first node with x >= x0 - tol */
    PetscInt mid = (lo + hi) / 2;
    if (nodes[mid].x[0] < x[0] - tol) lo = mid + 1;
    else hi = mid;
  }
  for (PetscInt i = lo; i < n && nodes[i].x[0] <= x[0] + tol; i++) {
    PetscReal d2 = 0;
    for (PetscInt d = 0; d < 3; d++) d2 += PetscSqr(nodes[i].x[d] - x[d]);
    if (d2 <= tol * tol) {
      *found = &nodes[i];
      break;
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode BoltContactSetSetUp(BoltContactSet *c)
{
  BoltMesh *m   = c->mesh;
  PetscInt  cap = 256;

  PetscReal hContact = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(boltLog.contactSetUp, 0, 0, 0, 0));
  PetscCall(BoltContactFindPairs(c));
  PetscCall(PetscMalloc1(cap, &c->elem));
  c->nelem       = 0;
  c->contactDofs = 0;
  for (PetscInt p = 0; p < c->npairs; p++) {
    char            na[BOLTROM_NAME_LEN + 16], nb[BOLTROM_NAME_LEN + 16];
    PetscInt        nb_nodes, nunmatched = 0, npartial = 0, partA = -1, partB = -1, nelemLocal = 0, counts[2], nvA, nvB, *vA, *vB;
    BoltNode       *bnodes = NULL;
    PetscReal       area = 0, bad[3] = {0, 0, 0};

    PetscCall(PetscSNPrintf(na, sizeof(na), "contact_%s_a", c->pairName[p]));
    PetscCall(PetscSNPrintf(nb, sizeof(nb), "contact_%s_b", c->pairName[p]));
    PetscCall(BoltContactGatherNodes(c, nb, &nb_nodes, &bnodes));
    {
      PetscInt nf, *faces;
      PetscCall(BoltMeshGroupPoints(m, na, PETSC_TRUE, &nf, &faces));
      for (PetscInt k = 0; k < nf; k++) {
        PetscInt            face = faces[k], nvert, verts[4], nsupp, cell;
        const PetscInt     *supp;
        BoltContactElement *e;
        PetscReal           X[12], cc[3] = {0, 0, 0}, fc[3] = {0, 0, 0}, nrm[3], hmin = PETSC_MAX_REAL, faceArea;

        PetscCall(BoltMeshFaceVertices(m, face, &nvert, verts, X));
        PetscCheck(nvert == 4, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "Contact side %s: face with %" PetscInt_FMT " vertices; contact sides must be quadrilateral faces of hexahedra", na, nvert);
        /* orient the face so its normal points out of part a */
        PetscCall(DMPlexGetSupportSize(m->dm, face, &nsupp));
        PetscCall(DMPlexGetSupport(m->dm, face, &supp));
        PetscCheck(nsupp == 1, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "Contact side %s contains an interior face: contact surfaces must be on the boundary of their part, with distinct nodes on each side", na);
        cell = supp[0];
        if (partA < 0) partA = m->cellPart[cell - m->cStart];
        {
          PetscReal CX[24];
          PetscCall(BoltMeshCellCoordinates(m, cell, CX));
          for (PetscInt a = 0; a < 8; a++)
            for (PetscInt d = 0; d < 3; d++) cc[d] += CX[3 * a + d] / 8;
        }
        for (PetscInt a = 0; a < 4; a++)
          for (PetscInt d = 0; d < 3; d++) fc[d] += X[3 * a + d] / 4;
        {
          PetscReal d1[3], d2[3], dot = 0;
          for (PetscInt d = 0; d < 3; d++) {
            d1[d] = X[6 + d] - X[d];
            d2[d] = X[9 + d] - X[3 + d];
          }
          nrm[0] = d1[1] * d2[2] - d1[2] * d2[1];
          nrm[1] = d1[2] * d2[0] - d1[0] * d2[2];
          nrm[2] = d1[0] * d2[1] - d1[1] * d2[0];
          for (PetscInt d = 0; d < 3; d++) dot += nrm[d] * (fc[d] - cc[d]);
          if (dot < 0) { /* reverse the cycle: 0 3 2 1 */
            PetscInt  tv = verts[1];
            PetscReal tx;
            verts[1] = verts[3];
            verts[3] = tv;
            for (PetscInt d = 0; d < 3; d++) {
              tx        = X[3 + d];
              X[3 + d]  = X[9 + d];
              X[9 + d]  = tx;
            }
          }
        }
        for (PetscInt a = 0; a < 4; a++) {
          PetscReal h = 0;
          for (PetscInt d = 0; d < 3; d++) h += PetscSqr(X[3 * ((a + 1) % 4) + d] - X[3 * a + d]);
          hmin = PetscMin(hmin, PetscSqrtReal(h));
        }
        hContact = PetscMin(hContact, hmin);
        if (c->nelem == cap) {
          cap *= 2;
          PetscCall(PetscRealloc(sizeof(BoltContactElement) * cap, &c->elem));
        }
        e       = &c->elem[c->nelem];
        e->pair = p;
        e->key  = m->pointOriginal[face - m->pStart];
        PetscCall(PetscArraycpy(e->Xa, X, 12));
        for (PetscInt a = 0; a < 4; a++) {
          const BoltNode *bn;
          PetscCall(BoltMeshVertexDofs(m, verts[a], &e->dofs[3 * a]));
          PetscCall(BoltContactFindNode(nb_nodes, bnodes, &X[3 * a], c->matchTolerance * hmin, &bn));
          if (!bn) {
            if (!nunmatched)
              for (PetscInt d = 0; d < 3; d++) bad[d] = X[3 * a + d];
            nunmatched++;
            for (PetscInt d = 0; d < 3; d++) e->dofs[12 + 3 * a + d] = -1;
          } else
            for (PetscInt d = 0; d < 3; d++) e->dofs[12 + 3 * a + d] = bn->dofs[d];
        }
        for (PetscInt k = 0; k < 8; k++) { /* a node held in some components only (-support_group) */
          const PetscInt *d3 = &e->dofs[3 * k];
          if ((d3[0] < 0 || d3[1] < 0 || d3[2] < 0) && (d3[0] >= 0 || d3[1] >= 0 || d3[2] >= 0)) npartial++;
        }
        PetscCall(QuadArea(X, &faceArea));
        area += faceArea;
        c->nelem++;
        nelemLocal++;
      }
      PetscCall(PetscFree(faces));
    }
    PetscCall(PetscFree(bnodes));
    {
      PetscInt  g;
      PetscReal gbad[3];
      PetscMPIInt rank, worst;
      PetscCall(MPIU_Allreduce(&nunmatched, &g, 1, MPIU_INT, MPI_SUM, m->comm));
      if (g) { /* report one unmatched node, from the lowest rank that has one */
        PetscCallMPI(MPI_Comm_rank(m->comm, &rank));
        {
          PetscMPIInt mine = nunmatched ? rank : PETSC_MPI_INT_MAX;
          PetscCall(MPIU_Allreduce(&mine, &worst, 1, MPI_INT, MPI_MIN, m->comm));
        }
        PetscCall(PetscArraycpy(gbad, bad, 3));
        PetscCallMPI(MPI_Bcast(gbad, 3, MPIU_REAL, worst, m->comm));
      }
      PetscCheck(!g, m->comm, PETSC_ERR_USER_INPUT, "Contact pair %s: %" PetscInt_FMT " node(s) of side a have no partner on side b, e.g. (%g, %g, %g): the two surfaces must be meshed node to node", c->pairName[p], g, (double)(g ? gbad[0] : 0), (double)(g ? gbad[1] : 0), (double)(g ? gbad[2] : 0));
      PetscCall(MPIU_Allreduce(&npartial, &g, 1, MPIU_INT, MPI_SUM, m->comm));
      PetscCheck(!g, m->comm, PETSC_ERR_USER_INPUT, "Contact pair %s: the support group '%s' holds %" PetscInt_FMT " of its nodes in some components only, which contact does not take: choose a -support_group off the contact surfaces", c->pairName[p], m->supportGroup, g);
    }
    PetscCall(BoltMeshGroupVertices(m, na, PETSC_TRUE, &nvA, &vA));
    PetscCall(BoltMeshGroupVertices(m, nb, PETSC_TRUE, &nvB, &vB));
    /* part of side b: from any local cell touching a side-b face */
    {
      PetscInt nf, *faces;
      PetscCall(BoltMeshGroupPoints(m, nb, PETSC_FALSE, &nf, &faces));
      for (PetscInt k = 0; k < nf && partB < 0; k++) {
        PetscInt        nsupp;
        const PetscInt *supp;
        PetscCall(DMPlexGetSupportSize(m->dm, faces[k], &nsupp));
        PetscCall(DMPlexGetSupport(m->dm, faces[k], &supp));
        if (nsupp >= 1 && supp[0] >= m->cStart && supp[0] < m->cEnd) partB = m->cellPart[supp[0] - m->cStart];
      }
      PetscCall(PetscFree(faces));
    }
    counts[0] = nvA;
    counts[1] = nvB;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 2, MPIU_INT, MPI_SUM, m->comm));
    PetscCall(PetscFree(vA));
    PetscCall(PetscFree(vB));
    PetscCheck(counts[0] == counts[1], m->comm, PETSC_ERR_USER_INPUT, "Contact pair %s: side a has %" PetscInt_FMT " nodes but side b has %" PetscInt_FMT ": the two surfaces must cover the same footprint, node to node", c->pairName[p], counts[0], counts[1]);
    c->contactDofsPerPair[p] = 3 * (counts[0] + counts[1]);
    c->contactDofs += c->contactDofsPerPair[p];
    PetscCall(MPIU_Allreduce(&nelemLocal, &c->elementsPerPair[p], 1, MPIU_INT, MPI_SUM, m->comm));
    PetscCall(MPIU_Allreduce(&area, &c->areaPerPair[p], 1, MPIU_REAL, MPI_SUM, m->comm));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &partA, 1, MPIU_INT, MPI_MAX, m->comm));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &partB, 1, MPIU_INT, MPI_MAX, m->comm));
    PetscCheck(partA >= 0 && partB >= 0, m->comm, PETSC_ERR_USER_INPUT, "Contact pair %s: a side has no faces on the mesh's hexahedra", c->pairName[p]);
    c->pairPart[p][0] = partA;
    c->pairPart[p][1] = partB;
    {
      PetscReal Ea = m->materials.mat[m->partMaterial[partA]].E, Eb = m->materials.mat[m->partMaterial[partB]].E, factor = c->penaltyFactor;
      PetscBool set;
      char      opt[BOLTROM_NAME_LEN + 48];
      PetscCall(PetscSNPrintf(opt, sizeof(opt), "-contact_%s_penalty_factor", c->pairName[p]));
      PetscOptionsBegin(m->comm, NULL, "Contact pair", "boltrom");
      PetscCall(PetscOptionsReal(opt, "Penalty of this pair, x E of its softer part, per metre", NULL, factor, &factor, NULL));
      PetscOptionsEnd();
      PetscCheck(factor > 0, m->comm, PETSC_ERR_USER_INPUT, "%s must be > 0 (got %g)", opt, (double)factor);
      c->epsN[p] = c->epsT[p] = factor * PetscMin(Ea, Eb);
      c->stickStiffness[p] = c->stickFactor * PetscMin(Ea, Eb);
      c->friction[p] = c->frictionDefault;
      PetscCall(PetscSNPrintf(opt, sizeof(opt), "-contact_%s_friction", c->pairName[p]));
      PetscOptionsBegin(m->comm, NULL, "Contact pair", "boltrom");
      PetscCall(PetscOptionsReal(opt, "Coulomb friction coefficient of this pair (-contact_law coulomb)", NULL, c->friction[p], &c->friction[p], &set));
      PetscOptionsEnd();
      PetscCheck(!set || c->law.friction, m->comm, PETSC_ERR_USER_INPUT, "%s needs a frictional law: add -contact_law coulomb", opt);
      PetscCheck(c->friction[p] >= 0, m->comm, PETSC_ERR_USER_INPUT, "%s must be >= 0 (got %g)", opt, (double)c->friction[p]);
      /* stick law: the opening band in traction is that of the default penalty (200 E/m) at the
         activation gap, whatever the penalty: scaled with eps_N, a stiff penalty kept every point
         closed. The strict law has none. */
      c->bandTraction[p] = c->law.strict ? 1e-10 * PetscMin(Ea, Eb) : 200.0 * PetscMin(Ea, Eb) * c->activationGap;
    }
  }
  PetscCall(MPIU_Allreduce(&hContact, &c->hMin, 1, MPIU_REAL, MPI_MIN, m->comm));
  /* the strict law's tolerance on a gap: 1e-9 of the shortest contact-face edge, so of every
     element's size; far above the round-off of the displacements, and its traction error
     (the gap times the structure's stiffness per area) is pascals */
  c->gapTolerance = 1e-9 * (c->npairs ? c->hMin : 1.0);
  if (c->activationGap < 0) c->activationGap = c->gapTolerance;
  PetscCall(PetscLogEventEnd(boltLog.contactSetUp, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* K + Kc with every contact element active (the tied joint), from a state of its own. */
PetscErrorCode BoltContactSetAssembleTied(BoltContactSet *c, Mat K, Mat *Ktied)
{
  BoltContactState *s;
  Mat               Kc;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(boltLog.contactAssembly, 0, 0, 0, 0));
  PetscCall(BoltContactStateCreate(c, &s)); /* every point active */
  PetscCall(BoltContactStateStiffness(s, &Kc));
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, Ktied));
  PetscCall(MatAXPY(*Ktied, 1.0, Kc, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatSetOption(*Ktied, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(PetscObjectSetName((PetscObject)*Ktied, "K_tied"));
  PetscCall(BoltContactStateDestroy(&s));
  PetscCall(PetscLogEventEnd(boltLog.contactAssembly, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltContactSetView(BoltContactSet *c, PetscViewer viewer)
{
  BoltMesh *m = c->mesh;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "Contact: %" PetscInt_FMT " pairs, %" PetscInt_FMT " contact DOFs, penalty %g x E(softer) per metre\n", c->npairs, c->contactDofs, (double)c->penaltyFactor));
  for (PetscInt p = 0; p < c->npairs; p++)
    PetscCall(PetscViewerASCIIPrintf(viewer, "  pair %-14s %-12s / %-12s %5" PetscInt_FMT " elements, %6" PetscInt_FMT " DOFs, area %.4e m^2, eps %.3e Pa/m\n", c->pairName[p], m->partName[c->pairPart[p][0]], m->partName[c->pairPart[p][1]], c->elementsPerPair[p], c->contactDofsPerPair[p], (double)c->areaPerPair[p], (double)c->epsN[p]));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltContactSetDestroy(BoltContactSet **cs)
{
  PetscFunctionBeginUser;
  if (!*cs) PetscFunctionReturn(0);
  PetscCall(PetscFree((*cs)->elem));
  PetscCall(PetscFree3((*cs)->gpN, (*cs)->gpW, (*cs)->gpNormal));
  PetscCall(PetscFree((*cs)->elemLocal));
  PetscCall(PetscFree((*cs)->localGlobal));
  PetscCall(VecDestroy(&(*cs)->uc));
  PetscCall(VecDestroy(&(*cs)->fc));
  PetscCall(VecDestroy(&(*cs)->fcWork));
  PetscCall(VecDestroy(&(*cs)->fGlobal));
  PetscCall(PetscFree3((*cs)->nodalArea, (*cs)->nodalForce, (*cs)->tau));
  PetscCall(VecScatterDestroy(&(*cs)->scatter));
  PetscCall(PetscFree(*cs));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------ fields on the contact DOFs */

static PetscErrorCode BoltContactForcesInto(BoltContactSet *, const PetscReal[], Vec);

/* out = the nodal forces sum w N t of a field t (3 per Gauss point) at the local contact DOFs,
   summed over the elements of every rank (a node on a partition boundary gets both sides). */
static PetscErrorCode BoltContactSetNodalSum(BoltContactSet *c, const PetscReal t[], PetscReal out[])
{
  const PetscScalar *f;

  PetscFunctionBeginUser;
  PetscCall(BoltContactForcesInto(c, t, c->fcWork));
  PetscCall(VecZeroEntries(c->fGlobal));
  PetscCall(VecScatterBegin(c->scatter, c->fcWork, c->fGlobal, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(c->scatter, c->fcWork, c->fGlobal, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterBegin(c->scatter, c->fGlobal, c->fcWork, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(c->scatter, c->fGlobal, c->fcWork, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(c->fcWork, &f));
  for (PetscInt i = 0; i < c->nlocal; i++) out[i] = PetscRealPart(f[i]);
  PetscCall(VecRestoreArrayRead(c->fcWork, &f));
  PetscFunctionReturn(0);
}

/* The normal traction of the field t (3 per Gauss point) smoothed through the nodes: at each node
   its normal force over its area (both sums w N over the elements around it), interpolated back
   to the Gauss point. The multipliers outnumber the nodes four to one, and the part of them that
   exerts no nodal force is not determined by the discrete problem: near the edge of the contact
   zone it shows as Gauss-point multipliers of tens of MPa of either sign over a compressed node.
   The smoothed traction depends only on the forces the multipliers exert. */
PetscErrorCode BoltContactSetSmoothedNormalTraction(BoltContactSet *c, const PetscReal t[], PetscReal tn[])
{
  PetscFunctionBeginUser;
  PetscCall(BoltContactSetNodalSum(c, t, c->nodalForce));
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
          fn += c->nodalForce[ii[k]] * n[k];
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
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &c->uc));
  PetscCall(VecDuplicate(c->uc, &c->fc));
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, n, c->localGlobal, PETSC_COPY_VALUES, &isGlobal));
  PetscCall(VecScatterCreate(layout, isGlobal, c->uc, NULL, &c->scatter));
  PetscCall(ISDestroy(&isGlobal));
  PetscCall(VecDuplicate(c->uc, &c->fcWork));
  PetscCall(VecDuplicate(layout, &c->fGlobal));
  PetscCall(PetscMalloc3(n + 1, &c->nodalArea, n + 1, &c->nodalForce, 12 * ne + 1, &c->tau));
  PetscCall(BoltContactSetNodalSum(c, c->gpNormal, c->nodalArea));
  {
    PetscInt ngp = 4 * ne;
    PetscCall(MPIU_Allreduce(&ngp, &c->ngpGlobal, 1, MPIU_INT, MPI_SUM, c->mesh->comm));
  }
  PetscFunctionReturn(0);
}

/* An empty K_c in the global layout with the fixed pattern of all contact elements: one COO
   entry per element matrix entry, so a state's element matrices are inserted as they are. */
PetscErrorCode BoltContactSetStiffnessMatrix(BoltContactSet *c, Mat *Kc)
{
  PetscInt ne = c->nelem, *ci, *cj, ncoo = 576 * ne, m, M;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(c->fGlobal, &m)); /* a vector of the global layout */
  PetscCall(VecGetSize(c->fGlobal, &M));
  PetscCall(MatCreate(c->mesh->comm, Kc));
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

/* uc <- the contact DOFs of a global displacement vector (the FOM's way). */
PetscErrorCode BoltContactSetScatter(BoltContactSet *c, Vec u)
{
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(c->scatter, u, c->uc, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(c->scatter, u, c->uc, INSERT_VALUES, SCATTER_FORWARD));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltContactSetGapsOf(BoltContactSet *c, PetscReal gap[])
{
  const PetscScalar *u;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(c->uc, &u));
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
  PetscCall(VecRestoreArrayRead(c->uc, &u));
  PetscFunctionReturn(0);
}

/* F = B' lambda: the nodal forces of the tractions lambda (3 per point) in the global layout of
   F, both sides of every pair. */
PetscErrorCode BoltContactSetForcesOf(BoltContactSet *c, const PetscReal lambda[], Vec F)
{
  PetscFunctionBeginUser;
  PetscCall(BoltContactForcesInto(c, lambda, c->fc));
  PetscCall(VecZeroEntries(F));
  PetscCall(VecScatterBegin(c->scatter, c->fc, F, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(c->scatter, c->fc, F, ADD_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

/* The contact state at the nodes, for the output: in F (global layout, 3 per node) the weights
   sum N_a of the node's open, sticking and slipping points (x, y and z: one per point with nodal
   quadrature), on both sides of each pair. codes: each local point's (BoltContactStatePointCodes). */
PetscErrorCode BoltContactSetNodalStates(BoltContactSet *c, const unsigned char codes[], Vec F)
{
  PetscScalar *f;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(c->fc));
  PetscCall(VecGetArray(c->fc, &f));
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
    const PetscInt  *loc = &c->elemLocal[24 * (gp / 4)];
    const PetscReal *N   = &c->gpN[4 * gp];
    for (PetscInt a = 0; a < 4; a++) {
      const PetscInt ia = loc[3 * a + codes[gp]], ib = loc[12 + 3 * a + codes[gp]];
      if (ia >= 0) f[ia] += N[a];
      if (ib >= 0) f[ib] += N[a];
    }
  }
  PetscCall(VecRestoreArray(c->fc, &f));
  PetscCall(VecZeroEntries(F));
  PetscCall(VecScatterBegin(c->scatter, c->fc, F, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(c->scatter, c->fc, F, ADD_VALUES, SCATTER_REVERSE));
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
  PetscInt     np = m->nparts, nv, *verts, held[BOLTROM_MAX_PARTS], adj[BOLTROM_MAX_PARTS][BOLTROM_MAX_PARTS];
  DM           dmv;
  PetscSection s;
  Vec          loc, ind[BOLTROM_MAX_PARTS + 1];

  PetscFunctionBeginUser;
  if (!m->clamp) PetscFunctionReturn(0);
  /* one indicator per part (and one for the clamp) on the vertices, summed over the ranks */
  PetscCall(DMClone(m->dm, &dmv));
  PetscCall(PetscSectionCreate(m->comm, &s));
  PetscCall(PetscSectionSetChart(s, m->pStart, m->pEnd));
  for (PetscInt v = m->vStart; v < m->vEnd; v++) PetscCall(PetscSectionSetDof(s, v, 1));
  PetscCall(PetscSectionSetUp(s));
  PetscCall(DMSetLocalSection(dmv, s));
  PetscCall(DMCreateLocalVector(dmv, &loc));
  for (PetscInt p = 0; p <= np; p++) {
    PetscScalar *a;
    PetscCall(VecZeroEntries(loc));
    PetscCall(VecGetArray(loc, &a));
    if (p < np) {
      for (PetscInt cell = m->cStart; cell < m->cEnd; cell++) {
        PetscInt cv[8], off;
        if (m->cellPart[cell - m->cStart] != p) continue;
        PetscCall(BoltMeshCellVertices(m, cell, cv));
        for (PetscInt k = 0; k < 8; k++) {
          PetscCall(PetscSectionGetOffset(s, cv[k], &off));
          a[off] = 1;
        }
      }
    } else {
      PetscCall(BoltMeshGroupVertices(m, m->clampGroup, PETSC_FALSE, &nv, &verts));
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
    PetscCheck(held[p], m->comm, PETSC_ERR_USER_INPUT, "Part %s is held by neither the clamp group '%s' nor, through shared nodes or contact pairs (contact_<pair>_a/_b), by a part that is: it would float free; extend the clamp group, add a contact pair, or run free-free with -clamp false", m->partName[p], m->clampGroup);
  PetscFunctionReturn(0);
}
