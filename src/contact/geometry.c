/* Contact set: the pairs of matching quad faces named contact_<pair>_a / contact_<pair>_b,
   found in parallel by node coordinates, with their penalties and element matrices. Each
   element is kept by the rank that owns its face a; the DOFs of side b are global indices,
   so the element's matrix is assembled straight into the distributed system. */
#include "private/contact.h"

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
  const char *quad[] = {"gauss", "nodal"};
  PetscBool   set;

  PetscFunctionBeginUser;
  PetscCall(BoltContactLawRegisterAll());
  PetscOptionsBegin(BoltMeshComm(c->mesh), NULL, "Contact", "boltrom");
  PetscCall(PetscOptionsFList("-contact_law", "Contact law: strict (one-sided at every node pair, closed pairs stick), coulomb (strict with Coulomb friction) or stick (the paper's)", "BoltContactLaw", BoltContactLawList, c->lawType, c->lawType, sizeof(c->lawType), NULL));
  PetscCall(BoltContactLawCreate(BoltMeshComm(c->mesh), c->lawType, &c->law)); /* an unknown law fails here, before any solve */
  c->penaltyFactor = c->law->penaltyFactor;
  c->quadrature    = BoltContactSetIsComplementarity(c) ? BOLT_QUADRATURE_NODAL : BOLT_QUADRATURE_GAUSS;
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
    PetscCall(PetscOptionsEList("-contact_open_test", "Stick law: a closed point opens when tensile beyond the band: nodal (traction smoothed through the nodes) or gauss (its own multiplier)", NULL, open, 2, open[c->openTest], &c->openTest, NULL));
  }
  if (c->activationGap < 0 && !BoltContactSetIsComplementarity(c)) c->activationGap = 1e-7; /* strict: -1 until SetUp knows the mesh */
  PetscCall(PetscOptionsReal("-contact_activation_gap", "An open point closes when it penetrates by more than this [m] (default: strict 1e-9 x the shortest contact-face edge, stick 1e-7)", NULL, c->activationGap, &c->activationGap, &set));
  PetscCall(PetscOptionsReal("-contact_match_tolerance", "Node matching tolerance, relative to the face's shortest edge", NULL, c->matchTolerance, &c->matchTolerance, NULL));
  PetscCall(PetscOptionsReal("-contact_friction", "Coulomb friction coefficient of every pair (-contact_law coulomb; -contact_<pair>_friction sets one pair)", NULL, c->frictionDefault, &c->frictionDefault, &c->frictionSet));
  PetscCall(PetscOptionsReal("-contact_slip_angle_tolerance", "Coulomb: K_c keeps a slipping pair's slip direction until the slip turns by more than this [rad]", NULL, c->slipAngleTolerance, &c->slipAngleTolerance, NULL));
  PetscCall(PetscOptionsReal("-contact_slip_stiffness_ratio", "Coulomb friction: K_c takes a slipping pair's new stiffness across its slip (mu |t_N| / |slip|) once the one it has is off by more than this factor", NULL, c->slipStiffnessRatio, &c->slipStiffnessRatio, NULL));
  PetscCall(PetscOptionsReal("-contact_stick_stiffness_factor", "Coulomb: tangential stiffness of a sticking pair (elastic stick), x E of the softer part, per metre [1/m]", NULL, c->stickFactor, &c->stickFactor, NULL));
  PetscOptionsEnd();
  PetscCheck(c->stickFactor > 0, BoltMeshComm(c->mesh), PETSC_ERR_USER_INPUT, "-contact_stick_stiffness_factor must be > 0 (got %g)", (double)c->stickFactor);
  PetscCheck(c->slipStiffnessRatio > 1, BoltMeshComm(c->mesh), PETSC_ERR_USER_INPUT, "-contact_slip_stiffness_ratio must be > 1 (got %g)", (double)c->slipStiffnessRatio);
  PetscCheck(c->slipAngleTolerance > 0, BoltMeshComm(c->mesh), PETSC_ERR_USER_INPUT, "-contact_slip_angle_tolerance must be > 0 (got %g)", (double)c->slipAngleTolerance);
  PetscCheck(!c->frictionSet || BoltContactSetHasFriction(c), BoltMeshComm(c->mesh), PETSC_ERR_USER_INPUT, "-contact_friction needs a frictional law: add -contact_law coulomb (the %s law has no Coulomb limit)", c->lawType);
  PetscCheck(!BoltContactSetHasFriction(c) || c->reanchor, BoltMeshComm(c->mesh), PETSC_ERR_USER_INPUT, "-contact_reclose slide is frictionless sliding: drop it with -contact_law coulomb (a pair that closes again sticks, then slips by friction)");
  PetscCheck(c->frictionDefault >= 0, BoltMeshComm(c->mesh), PETSC_ERR_USER_INPUT, "-contact_friction must be >= 0 (got %g)", (double)c->frictionDefault);
  PetscCheck(c->penaltyFactor > 0, BoltMeshComm(c->mesh), PETSC_ERR_USER_INPUT, "-contact_penalty_factor must be > 0 (got %g)", (double)c->penaltyFactor);
  PetscCheck(!set || c->activationGap >= 0, BoltMeshComm(c->mesh), PETSC_ERR_USER_INPUT, "-contact_activation_gap must be >= 0 (got %g)", (double)c->activationGap);
  PetscCheck(!BoltContactSetIsComplementarity(c) || c->augment, BoltMeshComm(c->mesh), PETSC_ERR_USER_INPUT, "The strict contact law closes gaps by its multipliers: drop -contact_augment false, or use -contact_law stick for the penalty law");
  PetscFunctionReturn(0);
}

/* Pair names from the labels contact_<pair>_a on rank 0, broadcast so all ranks agree; a side b
   whose side a is missing is named too (its pair would otherwise be dropped without a word). */
static PetscErrorCode BoltContactFindPairs(BoltContactSet *c)
{
  BoltMesh   *m = c->mesh;
  PetscMPIInt rank;
  char        orphan[BOLTROM_NAME_LEN] = "";

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(BoltMeshComm(m), &rank));
  c->npairs = 0;
  if (rank == 0) {
    PetscInt nlabels;
    PetscCall(DMGetNumLabels(BoltMeshDM(m), &nlabels));
    for (PetscInt l = 0; l < nlabels; l++) {
      const char *name;
      size_t      len;
      PetscBool   pre;

      PetscCall(DMGetLabelName(BoltMeshDM(m), l, &name));
      PetscCall(PetscStrlen(name, &len));
      PetscCall(PetscStrncmp(name, "contact_", 8, &pre));
      if (pre && len >= 11 && name[len - 2] == '_' && name[len - 1] == 'b' && !orphan[0]) {
        char      na[BOLTROM_NAME_LEN + 16];
        PetscBool has;
        PetscCall(PetscStrncpy(na, name, sizeof(na)));
        na[len - 1] = 'a';
        PetscCall(DMHasLabel(BoltMeshDM(m), na, &has));
        if (!has) PetscCall(PetscStrncpy(orphan, name + 8, PetscMin(len - 9, sizeof(orphan))));
      }
      if (!pre || len < 11 || name[len - 2] != '_' || name[len - 1] != 'a') continue;
      PetscCheck(c->npairs < BOLTROM_MAX_PAIRS, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "More than %d contact pairs", BOLTROM_MAX_PAIRS);
      PetscCall(PetscStrncpy(c->pairName[c->npairs], name + 8, len - 9));
      c->npairs++;
    }
  }
  PetscCallMPI(MPI_Bcast(&c->npairs, 1, MPIU_INT, 0, BoltMeshComm(m)));
  PetscCallMPI(MPI_Bcast(c->pairName, BOLTROM_MAX_PAIRS * BOLTROM_NAME_LEN, MPI_CHAR, 0, BoltMeshComm(m)));
  PetscCallMPI(MPI_Bcast(orphan, sizeof(orphan), MPI_CHAR, 0, BoltMeshComm(m)));
  PetscCheck(!orphan[0], BoltMeshComm(m), PETSC_ERR_USER_INPUT, "Contact pair %s has side b (contact_%s_b) but no side a: add the physical surface group contact_%s_a", orphan, orphan, orphan);
  for (PetscInt p = 0; p < c->npairs; p++) {
    char      nb[BOLTROM_NAME_LEN + 16];
    PetscBool has;

    PetscCall(PetscSNPrintf(nb, sizeof(nb), "contact_%s_b", c->pairName[p]));
    PetscCall(BoltMeshHasGroup(m, nb, &has));
    PetscCheck(has, BoltMeshComm(m), PETSC_ERR_USER_INPUT, "Contact pair %s has side a (contact_%s_a) but no side b: add the physical surface group %s", c->pairName[p], c->pairName[p], nb);
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
  PetscCall(DMGetCoordinatesLocal(BoltMeshDM(m), &coords));
  PetscCall(DMGetCoordinateSection(BoltMeshDM(m), &cs));
  PetscCall(VecGetArrayRead(coords, &x));
  for (PetscInt i = 0; i < nv; i++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(cs, verts[i], &off));
    for (PetscInt d = 0; d < 3; d++) mine[i].x[d] = PetscRealPart(x[off + d]);
    PetscCall(BoltMeshVertexDofs(m, verts[i], mine[i].dofs));
  }
  PetscCall(VecRestoreArrayRead(coords, &x));
  PetscCall(PetscFree(verts));
  PetscCall(BoltGatherAll(BoltMeshComm(m), MPI_BYTE, mine, nv * (PetscInt)sizeof(BoltNode), &all, NULL, &ntot, NULL));
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

/* Face a's vertices and coordinates, ordered so that its normal points out of its part; the
   part of its cell. */
static PetscErrorCode ContactOrientedFace(BoltMesh *m, const char na[], PetscInt face, PetscInt *partA, PetscInt verts[4], PetscReal X[12])
{
  PetscInt        nvert, nsupp, cell;
  const PetscInt *supp;
  PetscReal       cc[3] = {0, 0, 0}, fc[3] = {0, 0, 0}, nrm[3];

  PetscFunctionBeginUser;
  PetscCall(BoltMeshFaceVertices(m, face, &nvert, verts, X));
  PetscCheck(nvert == 4, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "Contact side %s: face with %" PetscInt_FMT " vertices; contact sides must be quadrilateral faces of hexahedra", na, nvert);
  /* orient the face so its normal points out of part a */
  PetscCall(DMPlexGetSupportSize(BoltMeshDM(m), face, &nsupp));
  PetscCall(DMPlexGetSupport(BoltMeshDM(m), face, &supp));
  PetscCheck(nsupp == 1, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "Contact side %s contains an interior face: contact surfaces must be on the boundary of their part, with distinct nodes on each side", na);
  cell = supp[0];
  if (*partA < 0) *partA = BoltMeshCellPart(m, cell);
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
  PetscFunctionReturn(0);
}

/* The default penalties, stick stiffness, friction coefficient and opening band of pair p from
   the softer of its parts (options -contact_<pair>_penalty_factor, -contact_<pair>_friction). */
static PetscErrorCode ContactPairParameters(BoltContactSet *c, PetscInt p, PetscInt partA, PetscInt partB)
{
  BoltMesh *m  = c->mesh;
  PetscReal Ea, Eb, factor = c->penaltyFactor;
  PetscBool set;
  char      opt[BOLTROM_NAME_LEN + 48];

  PetscFunctionBeginUser;
  PetscCall(BoltMeshPartMaterial(m, partA, NULL, &Ea, NULL, NULL));
  PetscCall(BoltMeshPartMaterial(m, partB, NULL, &Eb, NULL, NULL));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-contact_%s_penalty_factor", c->pairName[p]));
  PetscOptionsBegin(BoltMeshComm(m), NULL, "Contact pair", "boltrom");
  PetscCall(PetscOptionsReal(opt, "Penalty of this pair, x E of its softer part, per metre", NULL, factor, &factor, NULL));
  PetscOptionsEnd();
  PetscCheck(factor > 0, BoltMeshComm(m), PETSC_ERR_USER_INPUT, "%s must be > 0 (got %g)", opt, (double)factor);
  c->epsN[p] = c->epsT[p] = factor * PetscMin(Ea, Eb);
  c->stickStiffness[p] = c->stickFactor * PetscMin(Ea, Eb);
  c->friction[p] = c->frictionDefault;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-contact_%s_friction", c->pairName[p]));
  PetscOptionsBegin(BoltMeshComm(m), NULL, "Contact pair", "boltrom");
  PetscCall(PetscOptionsReal(opt, "Coulomb friction coefficient of this pair (-contact_law coulomb)", NULL, c->friction[p], &c->friction[p], &set));
  PetscOptionsEnd();
  PetscCheck(!set || BoltContactSetHasFriction(c), BoltMeshComm(m), PETSC_ERR_USER_INPUT, "%s needs a frictional law: add -contact_law coulomb", opt);
  PetscCheck(c->friction[p] >= 0, BoltMeshComm(m), PETSC_ERR_USER_INPUT, "%s must be >= 0 (got %g)", opt, (double)c->friction[p]);
  /* stick law: the opening band in traction is that of the default penalty (200 E/m) at the
     activation gap, whatever the penalty: scaled with eps_N, a stiff penalty kept every point
     closed. The strict law has none. */
  c->bandTraction[p] = BoltContactSetIsComplementarity(c) ? 1e-10 * PetscMin(Ea, Eb) : 200.0 * PetscMin(Ea, Eb) * c->activationGap;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltContactSetSetUp(BoltContactSet *c)
{
  BoltMesh *m   = c->mesh;
  PetscInt  cap = 256;

  PetscReal hContact = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_CONTACT_SET_UP, 0, 0, 0, 0));
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
        PetscInt            face = faces[k], verts[4];
        BoltContactElement *e;
        PetscReal           X[12], hmin = PETSC_MAX_REAL, faceArea;

        PetscCall(ContactOrientedFace(m, na, face, &partA, verts, X));
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
        e->key  = BoltMeshPointOriginal(m, face);
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
      PetscCall(MPIU_Allreduce(&nunmatched, &g, 1, MPIU_INT, MPI_SUM, BoltMeshComm(m)));
      if (g) { /* report one unmatched node, from the lowest rank that has one */
        PetscCallMPI(MPI_Comm_rank(BoltMeshComm(m), &rank));
        {
          PetscMPIInt mine = nunmatched ? rank : PETSC_MPI_INT_MAX;
          PetscCall(MPIU_Allreduce(&mine, &worst, 1, MPI_INT, MPI_MIN, BoltMeshComm(m)));
        }
        PetscCall(PetscArraycpy(gbad, bad, 3));
        PetscCallMPI(MPI_Bcast(gbad, 3, MPIU_REAL, worst, BoltMeshComm(m)));
      }
      PetscCheck(!g, BoltMeshComm(m), PETSC_ERR_USER_INPUT, "Contact pair %s: %" PetscInt_FMT " node(s) of side a have no partner on side b, e.g. (%g, %g, %g): the two surfaces must be meshed node to node", c->pairName[p], g, (double)(g ? gbad[0] : 0), (double)(g ? gbad[1] : 0), (double)(g ? gbad[2] : 0));
      PetscCall(MPIU_Allreduce(&npartial, &g, 1, MPIU_INT, MPI_SUM, BoltMeshComm(m)));
      PetscCheck(!g, BoltMeshComm(m), PETSC_ERR_USER_INPUT, "Contact pair %s: the support group '%s' holds %" PetscInt_FMT " of its nodes in some components only, which contact does not take: choose a -support_group off the contact surfaces", c->pairName[p], BoltMeshSupportGroup(m), g);
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
        PetscCall(DMPlexGetSupportSize(BoltMeshDM(m), faces[k], &nsupp));
        PetscCall(DMPlexGetSupport(BoltMeshDM(m), faces[k], &supp));
        if (nsupp >= 1) partB = BoltMeshCellPart(m, supp[0]);
      }
      PetscCall(PetscFree(faces));
    }
    counts[0] = nvA;
    counts[1] = nvB;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 2, MPIU_INT, MPI_SUM, BoltMeshComm(m)));
    PetscCall(PetscFree(vA));
    PetscCall(PetscFree(vB));
    PetscCheck(counts[0] == counts[1], BoltMeshComm(m), PETSC_ERR_USER_INPUT, "Contact pair %s: side a has %" PetscInt_FMT " nodes but side b has %" PetscInt_FMT ": the two surfaces must cover the same footprint, node to node", c->pairName[p], counts[0], counts[1]);
    c->contactDofsPerPair[p] = 3 * (counts[0] + counts[1]);
    c->contactDofs += c->contactDofsPerPair[p];
    PetscCall(MPIU_Allreduce(&nelemLocal, &c->elementsPerPair[p], 1, MPIU_INT, MPI_SUM, BoltMeshComm(m)));
    PetscCall(MPIU_Allreduce(&area, &c->areaPerPair[p], 1, MPIU_REAL, MPI_SUM, BoltMeshComm(m)));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &partA, 1, MPIU_INT, MPI_MAX, BoltMeshComm(m)));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &partB, 1, MPIU_INT, MPI_MAX, BoltMeshComm(m)));
    PetscCheck(partA >= 0 && partB >= 0, BoltMeshComm(m), PETSC_ERR_USER_INPUT, "Contact pair %s: a side has no faces on the mesh's hexahedra", c->pairName[p]);
    c->pairPart[p][0] = partA;
    c->pairPart[p][1] = partB;
    PetscCall(ContactPairParameters(c, p, partA, partB));
  }
  PetscCall(MPIU_Allreduce(&hContact, &c->hMin, 1, MPIU_REAL, MPI_MIN, BoltMeshComm(m)));
  /* the strict law's tolerance on a gap: 1e-9 of the shortest contact-face edge, so of every
     element's size; far above the round-off of the displacements, and its traction error
     (the gap times the structure's stiffness per area) is pascals */
  c->gapTolerance = 1e-9 * (c->npairs ? c->hMin : 1.0);
  if (c->activationGap < 0) c->activationGap = c->gapTolerance;
  PetscCall(PetscLogEventEnd(BOLT_EVENT_CONTACT_SET_UP, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltContactSetView(BoltContactSet *c, PetscViewer viewer)
{
  BoltMesh *m = c->mesh;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "Contact: %" PetscInt_FMT " pairs, %" PetscInt_FMT " contact DOFs, penalty %g x E(softer) per metre\n", c->npairs, c->contactDofs, (double)c->penaltyFactor));
  for (PetscInt p = 0; p < c->npairs; p++)
    PetscCall(PetscViewerASCIIPrintf(viewer, "  pair %-14s %-12s / %-12s %5" PetscInt_FMT " elements, %6" PetscInt_FMT " DOFs, area %.4e m^2, eps %.3e Pa/m\n", c->pairName[p], BoltMeshPartName(m, c->pairPart[p][0]), BoltMeshPartName(m, c->pairPart[p][1]), c->elementsPerPair[p], c->contactDofsPerPair[p], (double)c->areaPerPair[p], (double)c->epsN[p]));
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
  PetscCall(VecDestroy(&(*cs)->layout));
  PetscCall(PetscFree((*cs)->nodalArea));
  PetscCall(VecScatterDestroy(&(*cs)->scatter));
  PetscCall(BoltContactLawDestroy(&(*cs)->law));
  PetscCall(PetscFree(*cs));
  PetscFunctionReturn(0);
}

/* What the other modules read of element e (local): its pair, its key (face a's number in the
   mesh as read: it names the element on any partition), its 24 global DOFs (side a's four
   nodes, then side b's; -1 where held) and side a's corner coordinates (12). */
PetscInt BoltContactSetElementPair(const BoltContactSet *c, PetscInt e)
{
  return c->elem[e].pair;
}

PetscInt BoltContactSetElementKey(const BoltContactSet *c, PetscInt e)
{
  return c->elem[e].key;
}

const PetscInt *BoltContactSetElementDofs(const BoltContactSet *c, PetscInt e)
{
  return c->elem[e].dofs;
}

const PetscReal *BoltContactSetElementCoordinates(const BoltContactSet *c, PetscInt e)
{
  return c->elem[e].Xa;
}
