/* The dual loop's keys of the run summary: its phase times [s] and counters; full (the FOM's)
   adds the largest iteration counts and, for one-sided contact, the check of the transient's
   converged steps. */
#include "private/solve.h"

PetscErrorCode BoltDualSummaryWrite(BoltDual *d, BoltJSON *j, PetscBool full)
{
  PetscFunctionBeginUser;
  PetscCall(BoltJSONReal(j, "contact_stiffness_s", d->tContactStiffness));
  PetscCall(BoltJSONReal(j, "displacements_s", d->tDisplacements));
  PetscCall(BoltJSONReal(j, "contact_forces_s", d->tContactForces));
  PetscCall(BoltJSONInt(j, "factorizations", d->factorizations));
  PetscCall(BoltJSONInt(j, "low_rank_updates", d->updates));
  PetscCall(BoltJSONInt(j, "solves", d->solves));
  PetscCall(BoltJSONInt(j, "outer_total", d->outerTotal));
  PetscCall(BoltJSONInt(j, "inner_total", d->innerTotal));
  PetscCall(BoltJSONInt(j, "set_updates_proved_unchanged", d->keptUpdates));
  if (full) {
    PetscCall(BoltJSONInt(j, "outer_max", d->outerMax));
    PetscCall(BoltJSONInt(j, "inner_max", d->innerMax));
  }
  PetscCall(BoltJSONInt(j, "failures", d->failures));
  PetscCall(BoltJSONInt(j, "cycles", d->cycles));
  if (full && BoltContactStateIsComplementarity(d->op->state) && BoltContactStateAugmented(d->op->state)) {
    /* one-sided contact after every converged step of the transient: penetration relative to
       the shortest contact-face edge, the largest tension of a closed pair and the largest
       |t.n g.n|, relative to the largest compression (times that edge) */
    const PetscReal h = BoltContactSetMinEdge(d->op->contact), tc = d->worstCompression > 0 ? d->worstCompression : 1;
    PetscCall(BoltJSONBeginObject(j, "strict_check"));
    PetscCall(BoltJSONReal(j, "penetration_over_h", d->worstPenetration / h));
    PetscCall(BoltJSONReal(j, "tension_pa", d->worstTension));
    PetscCall(BoltJSONReal(j, "compression_pa", d->worstCompression));
    PetscCall(BoltJSONReal(j, "tension_rel", d->worstTension / tc));
    PetscCall(BoltJSONReal(j, "complementarity_rel", d->worstProduct / (tc * h)));
    PetscCall(BoltJSONEndObject(j));
  }
  PetscCall(BoltDualCheckSummaryWrite(d, j));
  PetscFunctionReturn(0);
}
