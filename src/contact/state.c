/* The contact state of one model: its law and penalties, and the multipliers, gaps and active
   sets at the Gauss points, with the element matrices and K_c of the active set. The full and
   the reduced model each own one over the shared geometry (BoltContactSet), so neither changes
   the other's penalties or multipliers. */
#include "private/contact.h"
#include <stdint.h>
#include <string.h>

/* A state with the geometry's default law and penalties, every point active, no multipliers. */
PetscErrorCode BoltContactStateCreate(BoltContactSet *c, BoltContactState **sp)
{
  BoltContactState *s;
  const PetscInt    ne = c->nelem;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&s));
  s->set = c;
  PetscCall(PetscStrncpy(s->lawType, c->lawType, sizeof(s->lawType)));
  s->law = c->law; /* the set's, looked up once when it read -contact_law */
  s->augment       = c->augment;
  s->activationGap = c->activationGap;
  /* the strict law judges a closed pair on its nodal traction (force over tributary area): with
     nodal quadrature that is the node pair's own multiplier, shared by its element corners */
  s->openTest      = BoltContactStateIsComplementarity(s) ? BOLT_OPEN_NODAL : c->openTest;
  for (PetscInt p = 0; p < c->npairs; p++) {
    s->epsN[p]         = c->epsN[p];
    s->epsT[p]         = c->epsT[p];
    s->bandTraction[p] = c->bandTraction[p];
    s->stickStiffness[p] = c->stickStiffness[p];
  }
  PetscCall(PetscCalloc2(12 * ne + 1, &s->lambda, 12 * ne + 1, &s->gap));
  PetscCall(PetscCalloc2(12 * ne + 1, &s->anchor, 12 * ne + 1, &s->lambdaForce));
  PetscCall(PetscCalloc4(12 * ne + 1, &s->lambdaPrev, 4 * ne + 1, &s->closedSteps, 12 * ne + 1, &s->slipStart, 16 * ne + 1, &s->slipDir));
  PetscCall(PetscCalloc1(12 * ne + 1, &s->tractionStart));
  s->reanchor = c->reanchor;
  s->slipAngleTolerance = c->slipAngleTolerance;
  s->slipStiffnessRatio = c->slipStiffnessRatio;
  PetscCall(PetscMalloc4(4 * ne + 1, &s->active, 4 * ne + 1, &s->activeOld, 4 * ne + 1, &s->activeOlder, 4 * ne + 1, &s->released));
  PetscCall(PetscMalloc1(ne + 1, &s->dirty));
  PetscCall(BoltContactWorkCreate(c, &s->work));
  PetscCall(BoltContactStateReset(s));
  *sp = s;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltContactStateDestroy(BoltContactState **sp)
{
  BoltContactState *s = *sp;

  PetscFunctionBeginUser;
  if (!s) PetscFunctionReturn(0);
  PetscCall(BoltContactWorkDestroy(&s->work));
  PetscCall(PetscFree2(s->lambda, s->gap));
  PetscCall(PetscFree2(s->anchor, s->lambdaForce));
  PetscCall(PetscFree4(s->lambdaPrev, s->closedSteps, s->slipStart, s->slipDir));
  PetscCall(PetscFree(s->tractionStart));
  PetscCall(PetscFree4(s->active, s->activeOld, s->activeOlder, s->released));
  PetscCall(PetscFree(s->dirty));
  PetscCall(PetscFree(s->Ke));
  PetscCall(MatDestroy(&s->Kc));
  PetscCall(PetscFree(*sp));
  PetscFunctionReturn(0);
}

/* This model's penalties: scale times the geometry's defaults, and its opening band (the
   tension at which a closed point opens) band times the default; every element is due for a
   stiffness update. */
PetscErrorCode BoltContactStateSetPenaltyScale(BoltContactState *s, PetscReal scale, PetscReal band)
{
  BoltContactSet *c = s->set;

  PetscFunctionBeginUser;
  for (PetscInt p = 0; p < c->npairs; p++) {
    s->epsN[p]         = c->epsN[p] * scale;
    s->epsT[p]         = c->epsT[p] * scale;
    s->bandTraction[p] = c->bandTraction[p] * band;
  }
  for (PetscInt e = 0; e < c->nelem; e++) s->dirty[e] = PETSC_TRUE;
  BoltContactStateChanged(s);
  PetscFunctionReturn(0);
}

/* Frees the element matrices and K_c (a finished run's); the next stiffness request rebuilds
   them from the active set. */
PetscErrorCode BoltContactStateReleaseStiffness(BoltContactState *s)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(s->Ke));
  PetscCall(MatDestroy(&s->Kc));
  s->KcAssembled = PETSC_FALSE;
  for (PetscInt e = 0; e < s->set->nelem; e++) s->dirty[e] = PETSC_TRUE;
  BoltContactStateChanged(s);
  PetscFunctionReturn(0);
}

/* Closed points that slide (strict law, -contact_reclose slide: they have opened once), and
   closed points that stick where they closed again (-contact_reclose stick), global. */
PetscErrorCode BoltContactStateCountReclosed(BoltContactState *s, PetscInt *nsliding, PetscInt *nanchored)
{
  PetscInt n[2] = {0, 0}, glob[2];

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < 4 * s->set->nelem; i++) {
    const PetscReal *a = &s->anchor[3 * i];
    n[0] += (s->active[i] && s->released[i]) ? 1 : 0;
    n[1] += (s->active[i] && (a[0] != 0 || a[1] != 0 || a[2] != 0)) ? 1 : 0;
  }
  PetscCall(MPIU_Allreduce(n, glob, 2, MPIU_INT, MPI_SUM, BoltMeshComm(s->set->mesh)));
  *nsliding = glob[0];
  if (nanchored) *nanchored = glob[1];
  PetscFunctionReturn(0);
}

/* nactive from the active flags (after they were set from outside, e.g. a checkpoint). */
PetscErrorCode BoltContactStateCountActive(BoltContactState *s)
{
  PetscInt nact = 0;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < 4 * s->set->nelem; i++) nact += s->active[i] ? 1 : 0;
  PetscCall(MPIU_Allreduce(&nact, &s->nactive, 1, MPIU_INT, MPI_SUM, BoltMeshComm(s->set->mesh)));
  PetscFunctionReturn(0);
}

/* Element e's state as BOLT_CONTACT_PACK values (checkpoints): multipliers (12), gaps (12), the
   active flags of the last three outer iterations and the released flags (4 each), anchors (12),
   the multipliers of the step before (12), the closed steps in a row (4) and the raw gaps at the
   start of the step (12), the slip directions and stiffnesses (16, friction) and the tractions at
   the start of the step (12). */
void BoltContactStatePack(BoltContactState *s, PetscInt e, PetscReal buf[])
{
  PetscInt k = 0;

  for (PetscInt i = 0; i < 12; i++) buf[k++] = s->lambda[12 * e + i];
  for (PetscInt i = 0; i < 12; i++) buf[k++] = s->gap[12 * e + i];
  for (PetscInt i = 0; i < 4; i++) buf[k++] = s->active[4 * e + i];
  for (PetscInt i = 0; i < 4; i++) buf[k++] = s->activeOld[4 * e + i];
  for (PetscInt i = 0; i < 4; i++) buf[k++] = s->activeOlder[4 * e + i];
  for (PetscInt i = 0; i < 4; i++) buf[k++] = s->released[4 * e + i];
  for (PetscInt i = 0; i < 12; i++) buf[k++] = s->anchor[12 * e + i];
  for (PetscInt i = 0; i < 12; i++) buf[k++] = s->lambdaPrev[12 * e + i];
  for (PetscInt i = 0; i < 4; i++) buf[k++] = s->closedSteps[4 * e + i];
  for (PetscInt i = 0; i < 12; i++) buf[k++] = s->slipStart[12 * e + i];
  for (PetscInt i = 0; i < 16; i++) buf[k++] = s->slipDir[16 * e + i];
  for (PetscInt i = 0; i < 12; i++) buf[k++] = s->tractionStart[12 * e + i];
}

/* The inverse of BoltContactStatePack; the element is due for a stiffness update. Not collective:
   the caller calls BoltContactStateChanged once all elements are unpacked. */
void BoltContactStateUnpack(BoltContactState *s, PetscInt e, const PetscReal buf[])
{
  for (PetscInt i = 0; i < 12; i++) s->lambda[12 * e + i] = buf[i];
  for (PetscInt i = 0; i < 12; i++) s->gap[12 * e + i] = buf[12 + i];
  for (PetscInt i = 0; i < 4; i++) s->active[4 * e + i] = buf[24 + i] != 0 ? PETSC_TRUE : PETSC_FALSE;
  for (PetscInt i = 0; i < 4; i++) s->activeOld[4 * e + i] = buf[28 + i] != 0 ? PETSC_TRUE : PETSC_FALSE;
  for (PetscInt i = 0; i < 4; i++) s->activeOlder[4 * e + i] = buf[32 + i] != 0 ? PETSC_TRUE : PETSC_FALSE;
  for (PetscInt i = 0; i < 4; i++) s->released[4 * e + i] = buf[36 + i] != 0 ? PETSC_TRUE : PETSC_FALSE;
  for (PetscInt i = 0; i < 12; i++) {
    s->anchor[12 * e + i] = buf[40 + i];
    if (buf[40 + i] != 0) s->anchored = PETSC_TRUE;
  }
  for (PetscInt i = 0; i < 12; i++) s->lambdaPrev[12 * e + i] = buf[52 + i];
  for (PetscInt i = 0; i < 4; i++) s->closedSteps[4 * e + i] = (PetscInt)buf[64 + i];
  for (PetscInt i = 0; i < 12; i++) s->slipStart[12 * e + i] = buf[68 + i];
  for (PetscInt i = 0; i < 16; i++) s->slipDir[16 * e + i] = buf[80 + i];
  for (PetscInt i = 0; i < 12; i++) s->tractionStart[12 * e + i] = buf[96 + i];
  s->dirty[e]    = PETSC_TRUE;
  s->KcAssembled = PETSC_FALSE;
}

PetscErrorCode BoltContactStateReset(BoltContactState *s)
{
  BoltContactSet *c = s->set;

  PetscFunctionBeginUser;
  for (PetscInt g = 0; g < 4 * c->nelem; g++) {
    s->active[g] = s->activeOld[g] = s->activeOlder[g] = PETSC_TRUE;
    s->released[g] = PETSC_FALSE;
  }
  for (PetscInt e = 0; e < c->nelem; e++) s->dirty[e] = PETSC_TRUE;
  s->KcAssembled = PETSC_FALSE;
  PetscCall(PetscArrayzero(s->lambda, 12 * c->nelem));
  PetscCall(PetscArrayzero(s->gap, 12 * c->nelem));
  PetscCall(PetscArrayzero(s->anchor, 12 * c->nelem));
  PetscCall(PetscArrayzero(s->slipStart, 12 * c->nelem));
  PetscCall(PetscArrayzero(s->tractionStart, 12 * c->nelem));
  s->dissipated = s->contactWork = 0;
  s->anchored = PETSC_FALSE;
  s->nactive = c->ngpGlobal;
  BoltContactStateChanged(s);
  PetscFunctionReturn(0);
}

/* Gap vectors g = u_b - u_a at every Gauss point, from uc, less the anchors. */
PetscErrorCode BoltContactStateGaps(BoltContactState *s)
{
  BoltContactSet *c = s->set;

  PetscFunctionBeginUser;
  PetscCall(BoltContactSetGapsOf(c, s->work, s->gap));
  BoltContactStateAnchorGaps(s, s->gap);
  PetscFunctionReturn(0);
}

/* Puts a given active set in place (a stored preloaded state), with the points that slide
   (released; NULL: under the strict law, those that are open): the sets of the last two outer
   iterations are taken to be the same, and every element is due for a stiffness update. */
PetscErrorCode BoltContactStateSetActive(BoltContactState *s, const PetscBool active[], const PetscBool released[])
{
  BoltContactSet *c = s->set;
  PetscInt        nact = 0;

  PetscFunctionBeginUser;
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
    s->active[gp] = s->activeOld[gp] = s->activeOlder[gp] = active[gp];
    /* the law says which points slide (the strict law: the open ones; under friction every
       closed pair starts sticking, and its trial traction decides again whether it slips) */
    s->released[gp] = s->law->ops.presetReleased ? s->law->ops.presetReleased(s, gp, active, released) : PETSC_FALSE;
    if (active[gp]) nact++;
  }
  for (PetscInt e = 0; e < c->nelem; e++) s->dirty[e] = PETSC_TRUE;
  BoltContactStateChanged(s);
  PetscCall(MPIU_Allreduce(&nact, &s->nactive, 1, MPIU_INT, MPI_SUM, BoltMeshComm(c->mesh)));
  PetscFunctionReturn(0);
}

/* K_c of the active Gauss points in the global layout; only elements whose activity changed
   are recomputed. */
PetscErrorCode BoltContactStateStiffness(BoltContactState *s, Mat *Kc)
{
  BoltContactSet *c = s->set;
  PetscScalar    *v;
  PetscInt        changed = 0, any;

  PetscFunctionBeginUser;
  if (!s->Kc) { /* a model that never asks for the global K_c (the ROM) holds none */
    PetscCall(PetscMalloc1(576 * c->nelem + 1, &s->Ke));
    PetscCall(BoltContactSetStiffnessMatrix(c, &s->Kc));
  }
  for (PetscInt e = 0; e < c->nelem; e++) {
    if (!s->dirty[e]) continue;
    PetscCall(s->law->ops.elementStiffness(s, e, &s->Ke[576 * e]));
    s->dirty[e] = PETSC_FALSE;
    changed++;
  }
  PetscCall(MPIU_Allreduce(&changed, &any, 1, MPIU_INT, MPI_SUM, BoltMeshComm(c->mesh)));
  *Kc = s->Kc;
  if (!any && s->KcAssembled) PetscFunctionReturn(0); /* nothing changed since the last call */
  s->KcAssembled = PETSC_TRUE;
#if defined(PETSC_USE_COMPLEX)
  SETERRQ(c->mesh->comm, PETSC_ERR_SUP, "Real scalars only");
#else
  v = (PetscScalar *)s->Ke;
#endif
  PetscCall(MatSetValuesCOO(s->Kc, v, INSERT_VALUES));
  PetscFunctionReturn(0);
}

/* K + Kc as a new symmetric matrix named name. */
static PetscErrorCode AddContactStiffness(Mat K, Mat Kc, const char name[], Mat *Ksum)
{
  PetscFunctionBeginUser;
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, Ksum));
  PetscCall(MatAXPY(*Ksum, 1.0, Kc, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatSetOption(*Ksum, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(PetscObjectSetName((PetscObject)*Ksum, name));
  PetscFunctionReturn(0);
}

/* K + Kc with every contact element active (the tied joint), from a state of its own. */
PetscErrorCode BoltContactSetAssembleTied(BoltContactSet *c, Mat K, Mat *Ktied)
{
  BoltContactState *s;
  Mat               Kc;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_CONTACT_ASSEMBLY, 0, 0, 0, 0));
  PetscCall(BoltContactStateCreate(c, &s)); /* every point active */
  PetscCall(BoltContactStateStiffness(s, &Kc));
  PetscCall(AddContactStiffness(K, Kc, "K_tied", Ktied));
  PetscCall(BoltContactStateDestroy(&s));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_CONTACT_ASSEMBLY, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* K + Kc linearised about the state, for small vibrations about it (a preloaded joint): each
   closed point's normal penalty, and where it sticks its tangential stiffness (the law's: the
   penalty, or coulomb's elastic stick). None where it slides or slips, not even coulomb's across
   the slip (that is the return map's, for a slip that goes on; a vibration reverses it), and none
   at a pair without friction (-contact_<pair>_friction 0), which then carries normal load only.
   n[0..2]: the closed and the sticking points, and all points (global). The state is unchanged. */
PetscErrorCode BoltContactStateAssembleLinearised(BoltContactState *s, Mat K, Mat *Klin, PetscInt n[3])
{
  BoltContactSet *c = s->set;
  PetscReal      *Ke;
  PetscInt        mine[2] = {0, 0};
  Mat             Kc;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_CONTACT_ASSEMBLY, 0, 0, 0, 0));
  PetscCall(PetscMalloc1(576 * c->nelem + 1, &Ke));
  for (PetscInt e = 0; e < c->nelem; e++) {
    const PetscInt  pair         = c->elem[e].pair;
    const PetscBool frictionless = (PetscBool)(BoltContactSetHasFriction(c) && c->friction[pair] == 0);
    PetscBool       slides[4];
    for (PetscInt q = 0; q < 4; q++) {
      const PetscInt gp = 4 * e + q;
      slides[q]         = (PetscBool)(s->released[gp] || frictionless);
      mine[0] += s->active[gp] ? 1 : 0;
      mine[1] += (s->active[gp] && !slides[q]) ? 1 : 0;
    }
    PetscCall(BoltContactSetElementStiffness(c, e, s->epsN[pair], s->law->ops.stickStiffness(s, pair), &s->active[4 * e], slides, NULL, &Ke[576 * e]));
  }
  PetscCall(MPIU_Allreduce(mine, n, 2, MPIU_INT, MPI_SUM, BoltMeshComm(c->mesh)));
  n[2] = c->ngpGlobal;
  PetscCall(BoltContactSetStiffnessMatrix(c, &Kc));
  PetscCall(MatSetValuesCOO(Kc, (PetscScalar *)Ke, INSERT_VALUES));
  PetscCall(PetscFree(Ke));
  PetscCall(AddContactStiffness(K, Kc, "K_preloaded", Klin));
  PetscCall(MatDestroy(&Kc));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_CONTACT_ASSEMBLY, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The law's penalty traction at point gp of a multiplier and a gap, under the point's penalties. */
void BoltContactStateTrialOf(const BoltContactState *s, PetscInt gp, const PetscReal lambda[3], const PetscReal g[3], PetscReal t[3])
{
  const PetscInt pair = s->set->elem[gp / 4].pair;

  s->law->ops.traction(lambda, g, &s->set->gpNormal[3 * gp], s->epsN[pair], BoltContactStateEpsT(s, gp, pair), t);
}

/* Point gp's penalties, normal and tangential (none where it slides): what its trial traction's
   penalty part is made of. */
void BoltContactStatePointPenalties(const BoltContactState *s, PetscInt gp, PetscReal *epsN, PetscReal *epsT)
{
  const PetscInt pair = s->set->elem[gp / 4].pair;

  *epsN = s->epsN[pair];
  *epsT = BoltContactStateEpsT(s, gp, pair);
}

/* Element e's stiffness block under the state's law (a model that assembles its own K_c). */
PetscErrorCode BoltContactStateElementStiffness(BoltContactState *s, PetscInt e, PetscReal Ke[576])
{
  PetscFunctionBeginUser;
  PetscCall(s->law->ops.elementStiffness(s, e, Ke));
  PetscFunctionReturn(0);
}

/* Raises the state's version, so models caching what they derive from it rebuild (see version). */
void BoltContactStateChanged(BoltContactState *s)
{
  s->version++;
  s->unchangedUpdates = 0;
}

/* Whether the point-by-point update may be skipped where a model proves that no point would
   change (BoltDualUpdateActive): after two updates in a row that changed nothing, with nothing of
   the state changed since, the sets of the last two iterations equal the current one, so an
   update that changes nothing leaves the state exactly as it is. Not with return maps (they move
   multipliers at every update) nor with a held set. */
PetscBool BoltContactStateSettled(const BoltContactState *s)
{
  return (PetscBool)(s->unchangedUpdates >= 2 && !s->holdContact && !s->law->ops.returnMap && !s->law->ops.returnChange);
}
