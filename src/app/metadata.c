/* What a result file says about its run, so that a reader needs no log: the root attributes of
   the HDF5 file and the same load and friction fields in the JSON summary.

   Root attributes of <output_name>.h5 (group "/"):
     units            string   "SI: m, kg, s, N, Pa"
     probe_group      string   the point group of the probe histories (-probe_group)
     probe_component  integer  0, 1 or 2: x, y or z (-probe_component)
     load_force       real     the external load [N] (-load_force)
     load_direction   3 reals  its unit direction (-load_direction, normalised)
     load_history     string   step, sine, ramp, release or sweep (-load_history); "none" without
                               a transient (a static run only)
     load_frequency   real     [Hz] for sine and sweep, else 0 (-load_frequency)
     contact_law      string   -contact_law
     pair_names       strings  the contact pairs, in the order of friction
     friction         reals    the Coulomb coefficient per pair, 0 for a frictionless law
     options          string   the run's options, as PetscOptionsGetAll gives them */
#include "private/app.h"

/* In the order of BoltLoadHistory, as -load_history takes them. */
static const char *const boltLoadHistoryNames[] = {"step", "sine", "ramp", "release", "sweep"};

/* The load's time history and frequency (0 where it has none) of the run's transient. */
static PetscErrorCode BoltRunLoadHistory(const BoltSummary *s, const char **name, PetscReal *frequency)
{
  BoltNewmark    *nm = s->fomRun ? s->fomRun : s->romRun;
  BoltLoadHistory history;

  PetscFunctionBeginUser;
  *name      = "none";
  *frequency = 0;
  if (!nm) PetscFunctionReturn(0);
  PetscCall(BoltNewmarkGetLoad(nm, &history, frequency));
  *name = boltLoadHistoryNames[history];
  PetscFunctionReturn(0);
}

/* The Coulomb coefficient of each pair, 0 for a frictionless law. */
static void BoltRunFriction(const BoltContactSet *c, PetscReal mu[])
{
  for (PetscInt p = 0; p < BoltContactSetPairCount(c); p++) mu[p] = BoltContactSetHasFriction(c) ? BoltContactSetFriction(c, p) : 0;
}

/* The root attributes above, on the file that v has open (every rank, same values). */
PetscErrorCode BoltSummaryWriteAttributes(const BoltSummary *s, PetscViewer v)
{
  const BoltLoadSet    *l = s->loads;
  const BoltContactSet *c = s->contact;
  const char           *history, *names[BOLTROM_MAX_PAIRS];
  char                 *options;
  PetscReal             frequency, mu[BOLTROM_MAX_PAIRS];

  PetscFunctionBeginUser;
  PetscCall(BoltRunLoadHistory(s, &history, &frequency));
  BoltRunFriction(c, mu);
  for (PetscInt p = 0; p < BoltContactSetPairCount(c); p++) names[p] = BoltContactSetPairName(c, p);
  PetscCall(PetscOptionsGetAll(NULL, &options));
  PetscCall(BoltHDF5AttributeString(v, "units", "SI: m, kg, s, N, Pa"));
  PetscCall(BoltHDF5AttributeString(v, "probe_group", BoltLoadSetProbeGroup(l)));
  PetscCall(BoltHDF5AttributeInt(v, "probe_component", BoltLoadSetProbeComponent(l)));
  {
    const PetscReal force = BoltLoadSetLoadForce(l);
    PetscCall(BoltHDF5AttributeReals(v, "load_force", -1, &force));
  }
  PetscCall(BoltHDF5AttributeReals(v, "load_direction", 3, BoltLoadSetLoadDirection(l)));
  PetscCall(BoltHDF5AttributeString(v, "load_history", history));
  PetscCall(BoltHDF5AttributeReals(v, "load_frequency", -1, &frequency));
  PetscCall(BoltHDF5AttributeString(v, "contact_law", BoltContactSetLawType(c)));
  PetscCall(BoltHDF5AttributeStrings(v, "pair_names", BoltContactSetPairCount(c), names));
  PetscCall(BoltHDF5AttributeReals(v, "friction", BoltContactSetPairCount(c), mu));
  PetscCall(BoltHDF5AttributeString(v, "options", options));
  PetscCall(PetscFree(options));
  PetscFunctionReturn(0);
}

/* The same load and friction fields in the JSON summary ("friction_per_pair": pair: coefficient). */
PetscErrorCode BoltSummaryWriteLoad(BoltJSON *j, const BoltSummary *s)
{
  const BoltLoadSet    *l = s->loads;
  const BoltContactSet *c = s->contact;
  const char           *history;
  PetscReal             frequency, mu[BOLTROM_MAX_PAIRS];

  PetscFunctionBeginUser;
  PetscCall(BoltRunLoadHistory(s, &history, &frequency));
  BoltRunFriction(c, mu);
  PetscCall(BoltJSONString(j, "probe_group", BoltLoadSetProbeGroup(l)));
  PetscCall(BoltJSONInt(j, "probe_component", BoltLoadSetProbeComponent(l)));
  PetscCall(BoltJSONReal(j, "load_force", BoltLoadSetLoadForce(l)));
  PetscCall(BoltJSONRealArray(j, "load_direction", 3, BoltLoadSetLoadDirection(l)));
  PetscCall(BoltJSONString(j, "load_history", history));
  PetscCall(BoltJSONReal(j, "load_frequency", frequency));
  PetscCall(BoltJSONBeginObject(j, "friction_per_pair"));
  for (PetscInt p = 0; p < BoltContactSetPairCount(c); p++) PetscCall(BoltJSONReal(j, BoltContactSetPairName(c, p), mu[p]));
  PetscCall(BoltJSONEndObject(j));
  PetscFunctionReturn(0);
}
