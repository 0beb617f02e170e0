/* The contact conditions checked at every node pair, from gaps the caller computed at every point:
   a reduced model that keeps some pairs in their state (held) computes their gaps only now and
   then, and this is where it learns whether the law would still keep them so. */
#include "private/contact.h"

/* For the raw gaps graw (u_b - u_a, 3 per local point, every point), after a converged step:
   worst[0] the largest penetration of an open point [m]; worst[1] the largest normal tension of a
   closed point [Pa] (smoothed through the nodes, as the strict law's opening test); worst[2] the
   largest excess of a closed point's tangential traction over the Coulomb cone, relative to
   mu |t_N| (0 without friction); *leaving: the held points (the state's mayChange is false) whose
   state the law would change: an open one that penetrates beyond the activation gap, a closed one
   in tension beyond its pair's band, a sticking one outside its Coulomb cone. tied (or NULL)
   marks the points whose traction is given in tTied (3 each), a reduced model's ties': their
   gaps cannot show it. tnGiven (or NULL) is the opening test's traction at every point, where the
   model has it in a closed form (a reduced model's); without friction it is all the check reads
   of the tractions. Collective. */
PetscErrorCode BoltContactStateCheck(BoltContactState *s, const PetscReal graw[], const PetscBool tied[], const PetscReal tTied[], const PetscReal tnGiven[], PetscReal worst[3], PetscInt *leaving)
{
  BoltContactSet *c   = s->set;
  const PetscInt  ngp = 4 * c->nelem;
  const PetscBool friction = BoltContactStateHasFriction(s), given = (PetscBool)(tnGiven && !friction);
  PetscReal      *g, *t, *tn, loc[3] = {0, 0, 0};
  PetscInt        nloc = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc3(3 * ngp + 1, &g, 3 * ngp + 1, &t, ngp + 1, &tn));
  PetscCall(PetscArraycpy(g, graw, 3 * ngp));
  BoltContactStateAnchorGaps(s, g);
  for (PetscInt gp = 0; gp < ngp && !given; gp++) {
    const PetscInt pair = c->elem[gp / 4].pair;
    PetscReal     *tp   = &t[3 * gp];
    if (!s->active[gp]) tp[0] = tp[1] = tp[2] = 0;
    else if (tied && tied[gp]) PetscCall(PetscArraycpy(tp, &tTied[3 * gp], 3));
    else if (BoltContactStateLambdaIsTraction(s)) PetscCall(PetscArraycpy(tp, &s->lambda[3 * gp], 3));
    else s->law->ops.traction(&s->lambda[3 * gp], &g[3 * gp], &c->gpNormal[3 * gp], s->epsN[pair], BoltContactStateEpsT(s, gp, pair), tp);
  }
  if (given) PetscCall(PetscArraycpy(tn, tnGiven, ngp));
  else PetscCall(BoltContactSetSmoothedNormalTraction(c, s->work, t, tn));
  for (PetscInt gp = 0; gp < ngp; gp++) {
    const PetscInt   pair = c->elem[gp / 4].pair;
    const PetscReal *n = &c->gpNormal[3 * gp], *gr = &graw[3 * gp], *tp = &t[3 * gp];
    const PetscReal  gn   = gr[0] * n[0] + gr[1] * n[1] + gr[2] * n[2];
    const PetscBool  held = (PetscBool)(s->mayChange && !s->mayChange[gp]);
    if (!s->active[gp]) {
      loc[0] = PetscMax(loc[0], -gn);
      if (held && -gn > s->activationGap) nloc++;
    } else {
      loc[1] = PetscMax(loc[1], tn[gp]);
      if (held && tn[gp] > s->bandTraction[pair]) nloc++;
      if (friction && c->friction[pair] > 0) {
        const PetscReal tnp = tp[0] * n[0] + tp[1] * n[1] + tp[2] * n[2];
        PetscReal       tt  = 0, excess;
        for (PetscInt k = 0; k < 3; k++) tt += PetscSqr(tp[k] - tnp * n[k]);
        if (!(tnp < 0)) continue;
        excess = PetscSqrtReal(tt) / (c->friction[pair] * -tnp) - 1;
        loc[2] = PetscMax(loc[2], excess);
        if (held && excess > PETSC_SQRT_MACHINE_EPSILON) nloc++; /* a held stick that would slip */
      }
    }
  }
  PetscCall(PetscFree3(g, t, tn));
  PetscCall(MPIU_Allreduce(loc, worst, 3, MPIU_REAL, MPI_MAX, BoltMeshComm(c->mesh)));
  PetscCall(MPIU_Allreduce(&nloc, leaving, 1, MPIU_INT, MPI_SUM, BoltMeshComm(c->mesh)));
  PetscFunctionReturn(0);
}
